// Names of the hal's status enums, for logs and error messages.
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::hal {

const char* to_string(GrabStatus s) {
  switch (s) {
    case GrabStatus::ok:
      return "ok";
    case GrabStatus::timeout:
      return "timeout";
    case GrabStatus::device_lost:
      return "device lost";
    case GrabStatus::end_of_stream:
      return "end of stream";
  }
  return "?";
}

const char* to_string(BusStatus s) {
  switch (s) {
    case BusStatus::ok:
      return "ok";
    case BusStatus::degraded:
      return "degraded";
    case BusStatus::fault:
      return "fault";
  }
  return "?";
}

}  // namespace rovctl::hal
