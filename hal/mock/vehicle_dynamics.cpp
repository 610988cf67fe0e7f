// Fossen's 6-DOF model of the vehicle (rigid body, added mass, Coriolis, damping, restoring) and
// its RK4 integration; the BlueROV2 Heavy parameter declarations with their source.
#include "hal/mock/vehicle_dynamics.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::hal::mock {

namespace {

// Skew-symmetric cross-product matrix: S(a) b = a x b.
Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d S;
  S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return S;
}

// The state's time derivative packed as [p_dot(3), q_dot(4: w x y z), nu_dot(6)].
using Derivative = Eigen::Matrix<double, 13, 1>;

}  // namespace

Eigen::Isometry3d VehicleState::T_world_body() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q_world_body.toRotationMatrix();
  T.translation() = position_world_m;
  return T;
}

VehicleDynamics::VehicleDynamics(const VehicleDynamicsParams& params) : p_(params) {
  const Eigen::Matrix3d S_rg = skew(p_.centre_of_gravity_body_m);
  // Inertia about the body origin (parallel-axis theorem), the CG being at r_g.
  inertia_ = Eigen::Matrix3d(p_.inertia_kgm2.asDiagonal()) - p_.mass_kg * S_rg * S_rg;
  Eigen::Matrix<double, 6, 6> M_rb = Eigen::Matrix<double, 6, 6>::Zero();
  M_rb.topLeftCorner<3, 3>() = p_.mass_kg * Eigen::Matrix3d::Identity();
  M_rb.topRightCorner<3, 3>() = -p_.mass_kg * S_rg;
  M_rb.bottomLeftCorner<3, 3>() = p_.mass_kg * S_rg;
  M_rb.bottomRightCorner<3, 3>() = inertia_;
  added_ << -p_.added_mass_linear, -p_.added_mass_angular;
  m_ = M_rb + Eigen::Matrix<double, 6, 6>(added_.asDiagonal());
  m_inv_ = m_.inverse();
}

Vector6d VehicleDynamics::restoring_wrench(const Eigen::Quaterniond& q_world_body,
                                           double depth_m) const {
  // Weight acts down (+z NED) at the CG, buoyancy up at the CB; both expressed in the body.
  // The submerged fraction treats the hull as a box of hull_height_m centred on the origin.
  const double submerged = std::clamp(0.5 + depth_m / p_.hull_height_m, 0.0, 1.0);
  const Eigen::Matrix3d R_body_world = q_world_body.toRotationMatrix().transpose();
  const Eigen::Vector3d f_g = R_body_world * Eigen::Vector3d(0, 0, p_.weight_n);
  const Eigen::Vector3d f_b = R_body_world * Eigen::Vector3d(0, 0, -submerged * p_.buoyancy_n);
  Vector6d w;
  w << f_g + f_b, p_.centre_of_gravity_body_m.cross(f_g) + p_.centre_of_buoyancy_body_m.cross(f_b);
  return w;
}

Vector6d VehicleDynamics::acceleration(const VehicleState& s, const Vector6d& tau_body,
                                       const Eigen::Vector3d& current_world_mps,
                                       const Eigen::Vector3d& current_rate_world_mps2) const {
  const Eigen::Matrix3d R_world_body = s.q_world_body.toRotationMatrix();
  const Eigen::Vector3d v = s.nu_body.head<3>();
  const Eigen::Vector3d w = s.nu_body.tail<3>();
  const Eigen::Vector3d& rg = p_.centre_of_gravity_body_m;
  const double m = p_.mass_kg;

  // Rigid-body Coriolis and centripetal terms, C_RB(nu) nu (Newton-Euler about the origin).
  Vector6d c_rb;
  c_rb << m * (w.cross(v) + w.cross(w.cross(rg))), w.cross(inertia_ * w) + m * rg.cross(w.cross(v));

  // Velocity relative to the water; the current is irrotational, so only the linear part.
  const Eigen::Vector3d v_c = R_world_body.transpose() * current_world_mps;
  const Eigen::Vector3d v_c_dot =
      -w.cross(v_c) + R_world_body.transpose() * current_rate_world_mps2;
  const Eigen::Vector3d vr = v - v_c;

  // Added-mass Coriolis, C_A(nu_r) nu_r, for a diagonal added-mass matrix.
  const Eigen::Vector3d a_v = added_.head<3>().cwiseProduct(vr);
  const Eigen::Vector3d a_w = added_.tail<3>().cwiseProduct(w);
  Vector6d c_a;
  c_a << w.cross(a_v), vr.cross(a_v) + w.cross(a_w);

  // Damping on the relative velocity; the derivatives are negative, so these are the forces.
  Vector6d nu_r;
  nu_r << vr, w;
  Vector6d d_lin, d_quad;
  d_lin << p_.damping_linear, p_.damping_angular;
  d_quad << p_.damping_quadratic_linear, p_.damping_quadratic_angular;
  const Vector6d damping =
      d_lin.cwiseProduct(nu_r) + d_quad.cwiseProduct(nu_r.cwiseAbs()).cwiseProduct(nu_r);

  // The added mass is accelerated with the water: M_A nu_r_dot = M_A (nu_dot - nu_c_dot).
  Vector6d added_current;
  added_current << added_.head<3>().cwiseProduct(v_c_dot), Eigen::Vector3d::Zero();

  const Vector6d rhs = tau_body - c_rb - c_a + damping +
                       restoring_wrench(s.q_world_body, s.position_world_m.z()) + added_current;
  return m_inv_ * rhs;
}

void VehicleDynamics::step(VehicleState& s, const Vector6d& tau_body,
                           const Eigen::Vector3d& current_world_mps,
                           const Eigen::Vector3d& current_rate_world_mps2, double dt_s) const {
  auto derivative = [&](const VehicleState& x) {
    Derivative d;
    d.head<3>() = x.q_world_body * x.nu_body.head<3>();
    const Eigen::Quaterniond omega(0.0, x.nu_body(3), x.nu_body(4), x.nu_body(5));
    const Eigen::Quaterniond q_dot = x.q_world_body * omega;
    d.segment<4>(3) << 0.5 * q_dot.w(), 0.5 * q_dot.x(), 0.5 * q_dot.y(), 0.5 * q_dot.z();
    d.tail<6>() = acceleration(x, tau_body, current_world_mps, current_rate_world_mps2);
    return d;
  };
  auto advanced = [&](const Derivative& d, double h) {
    VehicleState x = s;
    x.position_world_m += h * d.head<3>();
    x.q_world_body.w() += h * d(3);
    x.q_world_body.vec() += h * d.segment<3>(4);
    x.q_world_body.normalize();
    x.nu_body += h * d.tail<6>();
    return x;
  };
  const Derivative k1 = derivative(s);
  const Derivative k2 = derivative(advanced(k1, 0.5 * dt_s));
  const Derivative k3 = derivative(advanced(k2, 0.5 * dt_s));
  const Derivative k4 = derivative(advanced(k3, dt_s));
  s = advanced((k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0, dt_s);
}

double VehicleDynamics::kinetic_energy_j(const VehicleState& s) const {
  return 0.5 * s.nu_body.dot(m_ * s.nu_body);
}

void describe(ParamVisitor& v, VehicleDynamicsParams& p) {
  // Defaults: Wu (2018), Flinders University MSc thesis, BlueROV2; with the Heavy's mass as in
  // von Benzon et al., J. Mar. Sci. Eng. 2022, 10(12), 1898. Fossen's sign convention.
  v.param("mass_kg", p.mass_kg,
          {"kg", 0.1, 1000.0, "vehicle mass (BlueROV2 Heavy 13.5; Wu 2018, von Benzon 2022)"});
  v.param("inertia_kgm2", p.inertia_kgm2,
          {"kg m^2", 1e-4, 1000.0, "principal moments Ix, Iy, Iz about the CG (Wu 2018)"});
  v.param("added_mass_linear_kg", p.added_mass_linear,
          {"kg", -1000.0, 0.0, "added mass X_udot, Y_vdot, Z_wdot (Fossen sign: <= 0; Wu 2018)"});
  v.param("added_mass_angular_kgm2", p.added_mass_angular,
          {"kg m^2", -1000.0, 0.0, "added inertia K_pdot, M_qdot, N_rdot (<= 0; Wu 2018)"});
  v.param("damping_linear_nspm", p.damping_linear,
          {"N s/m", -1e4, 0.0, "linear damping X_u, Y_v, Z_w (<= 0: dissipative only; Wu 2018)"});
  v.param("damping_angular_nmspr", p.damping_angular,
          {"N m s/rad", -1e4, 0.0,
           "linear damping K_p, M_q, N_r (<= 0; Wu 2018's M_q = +0.8 is non-dissipative and "
           "replaced by 0)"});
  v.param("damping_quadratic_linear", p.damping_quadratic_linear,
          {"N s^2/m^2", -1e5, 0.0, "quadratic damping X_u|u|, Y_v|v|, Z_w|w| (<= 0; Wu 2018)"});
  v.param("damping_quadratic_angular", p.damping_quadratic_angular,
          {"N m s^2/rad^2", -1e4, 0.0, "quadratic damping K_p|p|, M_q|q|, N_r|r| (<= 0; Wu 2018)"});
  v.param("weight_n", p.weight_n, {"N", 0.0, 1e4, "weight W = m g (Wu 2018, Heavy: 112.8)"});
  v.param("buoyancy_n", p.buoyancy_n,
          {"N", 0.0, 1e4, "buoyancy B; B > W makes the vehicle rise slowly (Wu 2018: 114.8)"});
  v.param("centre_of_gravity_m", p.centre_of_gravity_body_m,
          {"m", -1.0, 1.0, "centre of gravity in the body frame (the body origin)"});
  v.param("centre_of_buoyancy_m", p.centre_of_buoyancy_body_m,
          {"m", -1.0, 1.0, "centre of buoyancy in the body frame (z down: -0.01 is above)"});
  v.param("hull_height_m", p.hull_height_m,
          {"m", 0.01, 10.0, "hull height: buoyancy falls as the hull breaks the surface"});
}

}  // namespace rovctl::hal::mock
