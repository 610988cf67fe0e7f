// Builds the StereoCamera backend the `camera` config section names.
#pragma once

#include <memory>

#include "drivers/camera_params.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/interfaces/stereo_camera.hpp"

namespace rovctl::drivers {

// The v4l2 or replay camera, not yet opened (open() reports a bad device or recording), on
// `clock`, which must outlive it. nullptr for `mock`: the simulated camera lives in hal/mock,
// which drivers do not depend on, so the application builds that one itself.
std::unique_ptr<hal::StereoCamera> make_stereo_camera(const CameraParams& params,
                                                      hal::Clock& clock);

}  // namespace rovctl::drivers
