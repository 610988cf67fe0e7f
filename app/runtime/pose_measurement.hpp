// What the pose tracker takes from one frame's estimate: the estimator's verdict read as sound,
// its bounds, and on a partial view the sphere centres whose rims the rims' fit confirms in both
// views.
#pragma once

#include "control/pose_tracker.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/model/marker_model.hpp"

namespace rovctl::app {

// Sound: ok by its own frame's tests, or held back only by the frame-to-frame confirmation (the
// tracker confirms it against its own prediction instead). Not sound but recognised, with a sharp
// rims' fit: the spheres whose rim support reaches `rim_support` in both views, placed by that fit
// (a hidden part of a sphere moves its blob's centre, not the rest of its rim; the estimate's own
// pose, fitted to all three spheres, was centimetres off in depth behind the sim's bars).
control::PoseMeasurement pose_measurement(const estimator::PoseEstimate& estimate,
                                          const hal::MarkerModel& marker, double rim_support);

}  // namespace rovctl::app
