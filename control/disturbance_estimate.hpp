// The water's steady push on the vehicle as the servo learns it: the integral of the servo's
// error, kept as a wrench in body axes and carried round with the station as the body turns, so
// a current learnt on one heading still holds on the next; it knows when it has settled and when
// it has reached what the thrusters can give.
#pragma once

#include <Eigen/Core>
#include <chrono>

#include "control/control_params.hpp"
#include "control/thruster_effectiveness.hpp"

namespace rovctl::control {

class DisturbanceEstimate {
 public:
  using Vector6d = Eigen::Matrix<double, 6, 1>;

  // ki: integral gains per body axis (0: that axis is not estimated); limit: the largest
  // magnitude per axis (the anti-windup clamp), before the thrusters' own limit is applied.
  DisturbanceEstimate(const Vector6d& ki, const Vector6d& limit, const DisturbanceParams& params);

  // The body turned relative to the station by R_body_prevbody since the last call: the estimate
  // is a push fixed in the station's frame, so it turns back by as much (held axes keep their
  // body value: the axial trim lies along the docking axis, which turns with the aligned body).
  void turn(const Eigen::Matrix3d& R_body_prevbody);
  // One servo update. error: the (clipped) pose error in body axes; saturated: the last wrench
  // was scaled down by the allocation (then an axis may only shrink). No allocation.
  void integrate(const Vector6d& error, double dt_s, bool saturated);

  // The thrusters' own limit per body axis (ControlAllocator::axis_capacity); the estimate is
  // held under hold_fraction of it, leaving the rest to the servo's P and D terms.
  void set_capacity(const Vector6d& capacity);

  // Starts from nothing (and releases every held axis).
  void reset();
  // One axis (0-5: x, y, z, roll, pitch, yaw; N or N m): set it, clamped to its limit; or hold it
  // where it is (not integrated) until released.
  void set_axis(int axis, double value);
  void hold_axis(int axis, bool hold) { held_[axis] = hold; }

  // The estimate: the wrench the servo adds to cancel the push (N, N m, body axes).
  const Vector6d& wrench_body() const { return wrench_; }
  // Its horizontal force has changed by less than settle_rate_nps for settle_s, off its limit
  // and with the thrusters unsaturated.
  bool settled() const { return settled_for_s_ >= p_.settle_s; }
  // A horizontal axis has been at its limit (or the thrusters saturated) for beyond_hold_s: the
  // current pushes harder than the vehicle may push back.
  bool beyond_hold() const { return at_limit_for_s_ >= p_.beyond_hold_s; }
  // At its limit (or the thrusters saturated) at the last update.
  bool at_limit() const { return at_limit_for_s_ > 0.0; }
  // Still rising toward a strong push: its horizontal force grew along itself faster than
  // settle_rate_nps, or stopped at its limit or with the thrusters saturated, and it has not
  // settled since; and it has reached swept_fraction of its limit (a current that sweeps the
  // marker from view leaves it so; a weak one's estimate stays far under its limit).
  bool rising() const { return rising_ && hold_ratio_ >= p_.swept_fraction; }
  // The horizontal force's magnitude against the limit along its direction (0..1).
  double hold_ratio() const { return hold_ratio_; }
  // The horizontal force's rate of change from the integration (not the turns), low-passed
  // twice at rate_cutoff_hz (N/s).
  double rate_nps() const { return rate_nps_; }

 private:
  DisturbanceParams p_;
  Vector6d ki_;
  Vector6d configured_limit_;
  Vector6d limit_;
  Vector6d wrench_ = Vector6d::Zero();
  Eigen::Matrix<bool, 6, 1> held_ = Eigen::Matrix<bool, 6, 1>::Constant(false);
  Eigen::Vector2d rate_stage_nps_ = Eigen::Vector2d::Zero();  // the rate through the first pole
  Eigen::Vector2d rate_body_nps_ = Eigen::Vector2d::Zero();   // ... and the second
  double rate_nps_ = 0.0;
  double settled_for_s_ = 0.0;
  double at_limit_for_s_ = 0.0;
  double hold_ratio_ = 0.0;
  bool rising_ = false;
};

}  // namespace rovctl::control
