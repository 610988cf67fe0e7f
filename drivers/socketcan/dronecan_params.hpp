// Settings of the DroneCAN thruster bus (uavcan.equipment.esc.RawCommand over SocketCAN).
#pragma once

#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

struct DronecanParams {
  std::string interface = "can0";
  int node_id = 100;                 // rovctl's own DroneCAN node ID (source of the commands)
  int priority = 8;                  // transfer priority, 0 highest .. 31 lowest
  int status_timeout_ms = 500;       // esc.Status older than this marks the channel stale
  int max_consecutive_failures = 3;  // failed ticks in a row after which write() reports a fault
};

void describe(hal::ParamVisitor& v, DronecanParams& p);

}  // namespace rovctl::drivers
