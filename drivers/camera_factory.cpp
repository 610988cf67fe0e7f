// Camera backend selection.
#include "drivers/camera_factory.hpp"

#include <stdexcept>

#include "drivers/replay/replay_stereo_camera.hpp"
#include "drivers/v4l2/v4l2_stereo_camera.hpp"

namespace rovctl::drivers {

std::unique_ptr<hal::StereoCamera> make_stereo_camera(const CameraParams& params,
                                                      hal::Clock& clock) {
  if (params.backend == "v4l2") return std::make_unique<V4l2StereoCamera>(params.v4l2, clock);
  if (params.backend == "replay") return std::make_unique<ReplayStereoCamera>(params.replay, clock);
  if (params.backend == "mock") return nullptr;
  throw std::invalid_argument("camera.backend: '" + params.backend +
                              "' is not one of: mock, v4l2, replay");
}

}  // namespace rovctl::drivers
