// What the pose tracker takes from one frame's estimate: the estimator's verdict read as sound,
// its bounds, and on a partial view the sphere centres the estimate is supported by in both views.
#pragma once

#include "control/pose_tracker.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/model/marker_model.hpp"

namespace rovctl::app {

// Sound: ok by its own frame's tests, or held back only by the frame-to-frame confirmation (the
// tracker confirms it against its own prediction instead). Not sound but recognised: the spheres
// whose scores reach `sphere_support` in both views.
control::PoseMeasurement pose_measurement(const estimator::PoseEstimate& estimate,
                                          const hal::MarkerModel& marker, double sphere_support);

}  // namespace rovctl::app
