// Pose error in body axes and the PID law with filtered derivative and clamped integral.
#include "control/pd_visual_servo.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rovctl::control {
namespace {

double wrap_pi(double a) { return std::remainder(a, 2.0 * M_PI); }

// Heading of the marker's z axis (the docking axis) in the body x-y plane.
double docking_axis_yaw(const Eigen::Matrix3d& R_body_marker) {
  const Eigen::Vector3d z = R_body_marker.col(2);
  return std::atan2(z.y(), z.x());
}

template <class V>
V clip_norm(const V& v, double max_norm) {
  const double n = v.norm();
  return n > max_norm ? V(v * (max_norm / n)) : v;
}

// 0 in the config: no clamp.
RateFilter::Vector rate_limits(const ServoParams& p) {
  const double inf = std::numeric_limits<double>::infinity();
  const double linear = p.max_rate_linear_mps > 0.0 ? p.max_rate_linear_mps : inf;
  const double angular = p.max_rate_angular_radps > 0.0 ? p.max_rate_angular_radps : inf;
  return (RateFilter::Vector() << Eigen::Vector3d::Constant(linear),
          Eigen::Vector3d::Constant(angular))
      .finished();
}

}  // namespace

PoseError pose_error_body(const Eigen::Isometry3d& T_body_cl,
                          const Eigen::Isometry3d& T_cl_marker_measured,
                          const Eigen::Isometry3d& T_cl_marker_desired, bool six_dof) {
  const Eigen::Isometry3d T_body_marker_m = T_body_cl * T_cl_marker_measured;
  const Eigen::Isometry3d T_body_marker_d = T_body_cl * T_cl_marker_desired;
  // The rotation taking the marker's desired body orientation to its measured one is the
  // rotation the body must make to put it back.
  const Eigen::Matrix3d R_err = T_body_marker_m.linear() * T_body_marker_d.linear().transpose();
  const Eigen::AngleAxisd aa(R_err);
  Eigen::Vector3d rot = aa.angle() * aa.axis();
  Eigen::Matrix3d R_used = R_err;
  if (!six_dof) {
    rot.z() = wrap_pi(docking_axis_yaw(T_body_marker_m.linear()) -
                      docking_axis_yaw(T_body_marker_d.linear()));
    R_used = Eigen::AngleAxisd(rot.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  // Where the desired body origin is, in the current body frame: the marker is at p_m now and
  // must end up at p_d in a body that has turned by R_used.
  PoseError e;
  e << T_body_marker_m.translation() - R_used * T_body_marker_d.translation(), rot;
  return e;
}

double marker_bearing_rad(const Eigen::Isometry3d& T_body_cl,
                          const Eigen::Isometry3d& T_cl_marker) {
  const Eigen::Vector3d to_marker = T_body_cl.linear() * T_cl_marker.translation();
  const Eigen::Vector3d axis = T_body_cl.linear().col(2);
  return wrap_pi(std::atan2(to_marker.y(), to_marker.x()) - std::atan2(axis.y(), axis.x()));
}

PdVisualServo::PdVisualServo(const ServoParams& params, const Eigen::Isometry3d& T_body_cl)
    : p_(params), T_body_cl_(T_body_cl), rate_(params.rate_cutoff_hz, rate_limits(params)) {
  kp_ << p_.kp_linear, p_.kp_angular;
  kd_ << p_.kd_linear, p_.kd_angular;
  ki_ << p_.ki_linear, p_.ki_angular;
  if (!p_.six_dof) {
    // Roll and pitch: passively stable; only their damping term stays.
    kp_[3] = kp_[4] = 0.0;
    ki_[3] = ki_[4] = 0.0;
  }
  integral_limit_ << p_.integral_limit_linear_n, p_.integral_limit_angular_nm;
  feedforward_.setZero();
  feedforward_[2] = p_.net_buoyancy_n;  // body z is down: a buoyant vehicle needs a push down
}

void PdVisualServo::reset() {
  rate_.reset();
  integral_.setZero();
  error_.setZero();
  saturated_ = false;
  held_.setConstant(false);
}

void PdVisualServo::set_integral_term(int axis, double value) {
  if (ki_[axis] <= 0.0) return;
  const double bound = integral_limit_[axis] / ki_[axis];
  integral_[axis] = std::clamp(value / ki_[axis], -bound, bound);
}

Wrench PdVisualServo::update(const Eigen::Isometry3d& T_cl_marker_measured,
                             const Eigen::Isometry3d& T_cl_marker_desired,
                             std::chrono::nanoseconds dt) {
  if (!T_cl_marker_measured.matrix().allFinite() || !T_cl_marker_desired.matrix().allFinite()) {
    return Wrench::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  const double dt_s = std::chrono::duration<double>(dt).count();
  PoseError e = pose_error_body(T_body_cl_, T_cl_marker_measured, T_cl_marker_desired, p_.six_dof);
  if (max_bearing_rad_ > 0.0) {
    // Turned by e[5], the marker's bearing would be b - e[5]. Limited before the derivative,
    // which then follows the bearing while the limit holds.
    const double b = marker_bearing_rad(T_body_cl_, T_cl_marker_measured);
    e[5] = std::clamp(e[5], b - max_bearing_rad_, b + max_bearing_rad_);
  }
  error_ = e;

  if (dt_s > p_.max_update_gap_s) rate_.reset();  // stale previous sample: no derivative kick
  const PoseError& e_rate = rate_.update(e, dt_s);

  PoseError e_clipped;
  e_clipped << clip_norm<Eigen::Vector3d>(e.head<3>(), p_.max_position_error_m),
      clip_norm<Eigen::Vector3d>(e.tail<3>(), p_.max_angle_error_rad);

  if (dt_s > 0.0 && dt_s <= p_.max_update_gap_s) {
    for (int i = 0; i < 6; ++i) {
      if (ki_[i] <= 0.0) {
        integral_[i] = 0.0;
        continue;
      }
      if (held_[i]) continue;
      const double next = integral_[i] + e_clipped[i] * dt_s;
      // Conditional integration while the thrusters saturate, then a hard clamp.
      if (saturated_ && std::abs(next) > std::abs(integral_[i])) continue;
      const double bound = integral_limit_[i] / ki_[i];
      integral_[i] = std::clamp(next, -bound, bound);
    }
  }

  return kp_.cwiseProduct(e_clipped) + ki_.cwiseProduct(integral_) + kd_.cwiseProduct(e_rate) +
         feedforward_;
}

}  // namespace rovctl::control
