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

Wrench integral_gains(const ServoParams& p) {
  Wrench ki;
  ki << p.ki_linear, p.ki_angular;
  if (!p.six_dof) ki[3] = ki[4] = 0.0;  // roll and pitch: passively stable, only damped
  return ki;
}

Wrench integral_limits(const ServoParams& p) {
  Wrench limit;
  limit << p.integral_limit_linear_n, p.integral_limit_angular_nm;
  return limit;
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
    : p_(params),
      T_body_cl_(T_body_cl),
      rate_(params.rate_cutoff_hz, rate_limits(params)),
      disturbance_(integral_gains(params), integral_limits(params), params.disturbance) {
  kp_ << p_.kp_linear, p_.kp_angular;
  kd_ << p_.kd_linear, p_.kd_angular;
  // Roll and pitch: passively stable; only their damping term stays.
  if (!p_.six_dof) kp_[3] = kp_[4] = 0.0;
  feedforward_.setZero();
  feedforward_[2] = p_.net_buoyancy_n;  // body z is down: a buoyant vehicle needs a push down
}

void PdVisualServo::restart() {
  rate_.reset();
  error_.setZero();
  saturated_ = false;
  for (int i = 0; i < 6; ++i) disturbance_.hold_axis(i, false);
}

void PdVisualServo::reset() {
  rate_.reset();
  disturbance_.reset();
  error_.setZero();
  saturated_ = false;
  have_last_rotation_ = false;
}

void PdVisualServo::set_integral_term(int axis, double value) {
  disturbance_.set_axis(axis, value);
}

void PdVisualServo::hold_integral(int axis, bool hold) { disturbance_.hold_axis(axis, hold); }

Eigen::Matrix3d PdVisualServo::body_turn(const Eigen::Matrix3d& R_body_marker) {
  Eigen::Matrix3d R_body_prevbody = Eigen::Matrix3d::Identity();
  if (have_last_rotation_) {
    R_body_prevbody = R_body_marker * R_body_marker_last_.transpose();
    if (!p_.six_dof) {
      // Only the turn about the vertical: the estimate's roll and pitch noise (about a degree a
      // frame) would tip the heave trim into surge and sway.
      R_body_prevbody = Eigen::AngleAxisd(std::atan2(R_body_prevbody(1, 0), R_body_prevbody(0, 0)),
                                          Eigen::Vector3d::UnitZ())
                            .toRotationMatrix();
    }
  }
  R_body_marker_last_ = R_body_marker;
  have_last_rotation_ = true;
  return R_body_prevbody;
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

  // The station is fixed in the water, so its rotation in the body tells how the body turned even
  // across a gap; the error is integrated only over a short one.
  disturbance_.turn(body_turn((T_body_cl_ * T_cl_marker_measured).linear()));
  if (dt_s <= p_.max_update_gap_s) {
    // What is integrated is the error plus its rate scaled as the PD weighs them: zero while the
    // servo closes a clipped error at the speed its gains set (the approach), so a long approach
    // does not wind the estimate up; at a standstill it is the error itself.
    PoseError integrand = e_clipped;
    for (int i = 0; i < 6; ++i) {
      if (kp_[i] > 0.0) integrand[i] += kd_[i] / kp_[i] * e_rate[i];
    }
    disturbance_.integrate(integrand, dt_s, saturated_);
  }

  return kp_.cwiseProduct(e_clipped) + disturbance_.wrench_body() + kd_.cwiseProduct(e_rate) +
         feedforward_;
}

}  // namespace rovctl::control
