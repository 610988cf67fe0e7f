// PD (+ optional I) visual servo: the error between where the marker is and where it should be,
// expressed as the motion the body must make (body axes), drives a body wrench.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>

#include "control/control_params.hpp"
#include "control/disturbance_estimate.hpp"
#include "control/rate_filter.hpp"
#include "control/thruster_effectiveness.hpp"

namespace rovctl::control {

// [x y z roll pitch yaw] error: the desired body pose seen from the current body, in body axes
// (m, rad). Positive x: the vehicle must go forward; positive yaw: it must turn to starboard.
using PoseError = Eigen::Matrix<double, 6, 1>;

// The body-frame pose error between a measured and a desired T_cl_marker. With six_dof false
// the rotation error's yaw is that of the marker's z axis projected on the body x-y plane, and
// the position error ignores the roll/pitch mismatch (which the vehicle cannot correct).
PoseError pose_error_body(const Eigen::Isometry3d& T_body_cl,
                          const Eigen::Isometry3d& T_cl_marker_measured,
                          const Eigen::Isometry3d& T_cl_marker_desired, bool six_dof);

// The yaw (positive: to starboard) that centres the marker on the camera's axis, both projected
// on the body x-y plane.
double marker_bearing_rad(const Eigen::Isometry3d& T_body_cl, const Eigen::Isometry3d& T_cl_marker);

class PdVisualServo {
 public:
  // Throws std::invalid_argument for a bad rate cut-off.
  PdVisualServo(const ServoParams& params, const Eigen::Isometry3d& T_body_cl);

  // measured/desired: T_cl_marker. dt: time since the previous update (a gap longer than
  // max_update_gap_s restarts the derivative). A non-finite input leaves the state as it was and
  // returns a NaN wrench, for the failsafe to act on. No allocation.
  Wrench update(const Eigen::Isometry3d& T_cl_marker_measured,
                const Eigen::Isometry3d& T_cl_marker_desired, std::chrono::nanoseconds dt);

  // From the next update on, the yaw error is limited to the turns that leave the marker within
  // max_bearing_rad of the camera's axis (its bearing in the body x-y plane); 0 lifts the limit.
  // Pose-based servoing turns to the docking axis's heading wherever the vehicle is: seen far
  // off the axis, that swings the marker out of view before the sway has brought the vehicle
  // round.
  void keep_in_view(double max_bearing_rad) { max_bearing_rad_ = max_bearing_rad; }

  // Anti-windup from the allocation: while the last wrench was scaled down (fraction < 1) the
  // integral may only shrink.
  void set_allocation_fraction(double achieved_fraction) { saturated_ = achieved_fraction < 0.999; }
  // What the thrusters can give along each body axis (ControlAllocator::axis_capacity), again
  // whenever a thruster leaves the allocation: the integral stays within its share of it.
  void set_capacity(const Wrench& capacity) { disturbance_.set_capacity(capacity); }

  // Clears the integral and the derivative; call when the servo (re)starts.
  void reset();
  // The servo takes over again after SEARCH or ABORT: the derivative starts afresh, but the
  // current's estimate is kept (the water has not changed; the station's rotation at the next
  // update turns it by however far the body turned meanwhile). Held axes are released.
  void restart();

  // One axis of the integral term (0-5: x, y, z, roll, pitch, yaw; N or N m): set it (clamped to
  // its limit), or hold it where it is (not integrated) until released. reset() releases.
  void set_integral_term(int axis, double value);
  void hold_integral(int axis, bool hold);

  // Constant feed-forward (net buoyancy), included in update()'s wrench.
  Wrench feedforward_body() const { return feedforward_; }
  // What holds the vehicle's trim while the servo cannot see: the feed-forward plus the
  // integral term (the learned push against the current). Add it to the mission's override
  // wrenches (brief loss, blind push near the socket) in place of feedforward_body().
  Wrench hold_wrench_body() const { return feedforward_ + integral_term(); }

  // The last update's terms, for telemetry.
  const PoseError& error() const { return error_; }
  const PoseError& error_rate() const { return rate_.rate(); }
  Wrench integral_term() const { return disturbance_.wrench_body(); }
  // The integral term as the estimate of the current's push: settled, beyond hold.
  const DisturbanceEstimate& disturbance() const { return disturbance_; }

 private:
  // How the body turned relative to the station since the last update (about the vertical only
  // unless six_dof), and remembers this update's rotation.
  Eigen::Matrix3d body_turn(const Eigen::Matrix3d& R_body_marker);

  ServoParams p_;
  Eigen::Isometry3d T_body_cl_;
  Wrench kp_, kd_, feedforward_;
  RateFilter rate_;
  DisturbanceEstimate disturbance_;
  PoseError error_ = PoseError::Zero();
  bool saturated_ = false;
  double max_bearing_rad_ = 0.0;
  // The station's rotation in the body at the last update: how far the body has turned since.
  Eigen::Matrix3d R_body_marker_last_ = Eigen::Matrix3d::Identity();
  bool have_last_rotation_ = false;
};

}  // namespace rovctl::control
