// The simulated vehicle's 6-DOF rigid-body dynamics in Fossen's form, with a BlueROV2 Heavy
// parameter set: M nu_dot + C(nu) nu + D(nu_r) nu_r + g(eta) = tau, integrated by RK4.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// Fossen's hydrodynamic derivatives, in his sign convention (added mass and damping derivatives
// are negative). Default values: Wu, C.-J., "6-DoF Modelling and Control of a Remotely Operated
// Vehicle", Master's thesis, Flinders University, 2018 (BlueROV2), as used for the BlueROV2 Heavy
// by von Benzon et al., "An Open-Source Benchmark Simulator: Control of a BlueROV2 Underwater
// Robot", J. Mar. Sci. Eng. 2022, 10(12), 1898.
struct VehicleDynamicsParams {
  double mass_kg = 13.5;                                       // Heavy configuration
  Eigen::Vector3d inertia_kgm2{0.26, 0.23, 0.37};              // Ix, Iy, Iz about the CG
  Eigen::Vector3d added_mass_linear{-6.36, -7.12, -18.68};     // X_udot, Y_vdot, Z_wdot [kg]
  Eigen::Vector3d added_mass_angular{-0.189, -0.135, -0.222};  // K_pdot, M_qdot, N_rdot [kg m^2]
  // Linear damping X_u, Y_v, Z_w [N s/m] and K_p, M_q, N_r [N m s/rad]. The source gives
  // M_q = +0.8, which would feed energy into pitch (negative damping); it is kept out: 0 here.
  Eigen::Vector3d damping_linear{-13.7, 0.0, -33.0};
  Eigen::Vector3d damping_angular{0.0, 0.0, 0.0};
  // Quadratic damping X_u|u|, Y_v|v|, Z_w|w| [N s^2/m^2] and K_p|p|, M_q|q|, N_r|r| [N m
  // s^2/rad^2].
  Eigen::Vector3d damping_quadratic_linear{-141.0, -217.0, -190.0};
  Eigen::Vector3d damping_quadratic_angular{-1.19, -0.47, -1.5};
  double weight_n = 112.8;    // W = m g
  double buoyancy_n = 114.8;  // B: slightly positive, the vehicle rises slowly
  Eigen::Vector3d centre_of_gravity_body_m{0.0, 0.0, 0.0};
  Eigen::Vector3d centre_of_buoyancy_body_m{0.0, 0.0, -0.01};  // above the CG (z down)
  // Hull height (BlueROV2 Heavy: 254 mm): near the surface buoyancy falls with the submerged
  // fraction, so a vehicle left to itself floats instead of rising out of the water.
  double hull_height_m = 0.254;
};

void describe(ParamVisitor& v, VehicleDynamicsParams& p);

using Vector6d = Eigen::Matrix<double, 6, 1>;

// The vehicle's state: pose in the world (NED) and body-frame velocities over ground.
struct VehicleState {
  Eigen::Vector3d position_world_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();
  Vector6d nu_body = Vector6d::Zero();  // [u v w p q r]: m/s and rad/s in the body frame

  Eigen::Isometry3d T_world_body() const;
  Eigen::Vector3d velocity_body_mps() const { return nu_body.head<3>(); }
  Eigen::Vector3d omega_body_radps() const { return nu_body.tail<3>(); }
};

class VehicleDynamics {
 public:
  explicit VehicleDynamics(const VehicleDynamicsParams& params);

  // nu_dot for the given state, body wrench tau = [force; moment about the body origin] and
  // water current in the world frame (velocity and its time derivative).
  Vector6d acceleration(const VehicleState& s, const Vector6d& tau_body,
                        const Eigen::Vector3d& current_world_mps,
                        const Eigen::Vector3d& current_rate_world_mps2) const;

  // One RK4 step of `dt_s` with tau and the current held over the step (zero-order hold).
  void step(VehicleState& s, const Vector6d& tau_body, const Eigen::Vector3d& current_world_mps,
            const Eigen::Vector3d& current_rate_world_mps2, double dt_s) const;

  // Kinetic energy of the vehicle plus its added mass, relative to the water at rest [J].
  double kinetic_energy_j(const VehicleState& s) const;

  // Restoring (gravity + buoyancy) wrench in the body frame for the attitude, with the body
  // origin at `depth_m` (buoyancy shrinks as the hull leaves the water).
  Vector6d restoring_wrench(const Eigen::Quaterniond& q_world_body, double depth_m = 1e9) const;

  const VehicleDynamicsParams& params() const { return p_; }

 private:
  VehicleDynamicsParams p_;
  Eigen::Matrix3d inertia_;            // rigid-body inertia about the origin
  Eigen::Matrix<double, 6, 6> m_;      // M_RB + M_A
  Eigen::Matrix<double, 6, 6> m_inv_;  // (M_RB + M_A)^-1
  Vector6d added_;                     // positive added-mass diagonal (-X_udot, ...)
};

}  // namespace rovctl::hal::mock
