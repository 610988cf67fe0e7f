// The simulated world: the vehicle (Fossen dynamics driven by the thruster model), the water
// current, and the docking station fixed in the world with its marker and socket. It integrates
// at a fine fixed step and is the single source of truth the mock backends observe.
#pragma once

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "hal/interfaces/thruster_bus.hpp"
#include "hal/mock/battery_model.hpp"
#include "hal/mock/charger.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/thruster_model.hpp"
#include "hal/mock/vehicle_dynamics.hpp"
#include "hal/mock/water_current.hpp"
#include "hal/model/docking_station.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::hal::mock {

// How the probe stands relative to the socket, in the marker frame (docking axis = marker +z).
struct DockingTruth {
  double axial_distance_m = 0.0;  // probe tip to socket mouth along the docking axis (> 0: short)
  double lateral_error_m = 0.0;   // probe tip off the socket axis
  double yaw_error_rad = 0.0;     // vehicle heading minus docking heading, in (-pi, pi]
  double misalignment_rad = 0.0;  // angle between body x and the docking axis
  bool contact = false;           // the probe presses on the station face or socket bottom now
  bool collided = false;          // the probe has hit the station face outside the socket (latched)
  bool docked = false;            // captured: deep enough, centred and aligned (latched)
  bool seated = false;            // now: in the socket with the charging pins touching
  std::chrono::nanoseconds docked_at{-1};
  double max_contact_force_n = 0.0;
};

struct WorldTruth {
  std::chrono::nanoseconds time{0};
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity_body_mps = Eigen::Vector3d::Zero();  // over ground
  Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d current_world_mps = Eigen::Vector3d::Zero();
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();  // what the estimator seeks
  Eigen::Matrix<double, 6, 1> thrust_wrench_body = Eigen::Matrix<double, 6, 1>::Zero();
  DockingTruth docking;
};

// The battery and charger side of the world. Energies and charge time are in battery time (sped
// up by sim.recharge.seated_time_scale while seated).
struct ChargeTruth {
  double soc_fraction = 0.0;
  double battery_voltage_v = 0.0;
  double charge_current_a = 0.0;    // into the battery now
  double charged_wh = 0.0;          // given by the charger so far (the loads' share too)
  double thruster_wh = 0.0;         // drawn by the thrusters so far
  double seated_thruster_wh = 0.0;  // drawn by the thrusters while seated: the hold's energy
  double seated_s = 0.0;            // physics time seated
  double battery_time_s = 0.0;      // physics time plus the sped-up seated time
};

class SimulatedWorld {
 public:
  // The station stands at params.station; the vehicle starts at rest 1 m short of the docked pose
  // until reset() places it.
  SimulatedWorld(const SimParams& params, const VehicleGeometry& vehicle,
                 const DockingStation& station);

  // Restarts at time 0 with the vehicle in `initial`, the given mean current, thrusters neutral,
  // contact flags clear; `seed` drives the current's random part.
  void reset(const VehicleState& initial, const Eigen::Vector3d& current_mean_world_mps,
             std::uint64_t seed);

  // Integrates up to absolute sim time `t` in fixed steps (the last one shorter if needed).
  // No heap allocation. Does nothing if `t` is not ahead.
  void step_to(std::chrono::nanoseconds t);
  std::chrono::nanoseconds time() const { return std::chrono::nanoseconds(time_ns_.load()); }

  // Thruster commands as the bus delivers them, stamped with the current sim time.
  void command_thrusters(const ThrusterCommand& command);
  void neutral_thrusters();
  const ThrusterModel& thrusters() const { return thrusters_; }
  // Schedules the thruster failures of `faults` (sim.faults at construction; a trial may draw its
  // own). Throws std::invalid_argument for a thruster the layout does not have.
  void set_thruster_faults(const FaultInjection& faults) { thrusters_.set_faults(faults); }

  const VehicleState& state() const { return state_; }
  WorldTruth truth() const;
  const DockingTruth& docking() const { return docking_; }
  const ChargeTruth& charge() const { return charge_; }
  // The charger delivers nothing from now on (fault injection).
  void fail_charger() { charger_failed_ = true; }
  // Time since the probe first seated (physics time); negative before. The seat-timed faults
  // (FaultInjection::*_after_seated_s) count from there.
  double since_first_seated_s() const;
  // Whether a seat-timed fault at `after_s` (negative: never) is active now.
  bool seated_fault_active(double after_s) const {
    return after_s >= 0.0 && since_first_seated_s() >= after_s;
  }
  int knocks() const { return knocks_; }  // knocks delivered so far

  // The body pose at an earlier time, from the history of the last steps (interpolated; clamped
  // to the oldest kept sample), for cameras with capture latency.
  Eigen::Isometry3d T_world_body_at(std::chrono::nanoseconds t) const;
  Eigen::Isometry3d T_cl_marker_at(std::chrono::nanoseconds t) const;
  Eigen::Isometry3d T_cl_marker(const Eigen::Isometry3d& T_world_body) const;

  const Eigen::Isometry3d& T_world_marker() const { return T_world_marker_; }
  // The body pose at which the probe is exactly at the socket mouth, aligned: the docked pose.
  Eigen::Isometry3d docked_T_world_body() const;
  const Eigen::Isometry3d& T_body_cl() const { return T_body_cl_; }
  const VehicleGeometry& vehicle() const { return vehicle_; }
  const DockingStation& station() const { return station_; }
  const SimParams& params() const { return params_; }
  const VehicleDynamics& dynamics() const { return dynamics_; }
  const WaterCurrent& current() const { return current_; }

 private:
  struct Sample {
    std::int64_t t_ns;
    Eigen::Vector3d position;
    Eigen::Quaterniond q;
  };

  void substep(std::int64_t dt_ns);
  // The station's push on the probe tip (world frame), and whether it is touching.
  Eigen::Vector3d contact_force_world(const VehicleState& s, bool& touching) const;
  void update_docking();
  void update_charge(double dt_s);
  void record();
  // The injected knock (world force) and cross-current surge now.
  Eigen::Vector3d knock_force_world();
  Eigen::Vector3d surge_world_mps() const;

  SimParams params_;
  VehicleGeometry vehicle_;
  DockingStation station_;
  VehicleDynamics dynamics_;
  ThrusterModel thrusters_;
  WaterCurrent current_;
  Eigen::Isometry3d T_world_marker_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_marker_world_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_body_cl_ = Eigen::Isometry3d::Identity();
  std::int64_t step_ns_ = 2'000'000;
  std::atomic<std::int64_t> time_ns_{0};  // read by clocks on other threads
  VehicleState state_;
  DockingTruth docking_;
  BatteryModel battery_;
  Charger charger_;
  ChargeTruth charge_;
  bool charger_failed_ = false;
  std::int64_t first_seated_ns_ = -1;
  std::int64_t seated_since_ns_ = -1;  // start of the present seated stretch (-1: not seated)
  std::int64_t knock_until_ns_ = -1;
  int knocks_ = 0;
  Eigen::Vector3d surge_last_world_mps_ = Eigen::Vector3d::Zero();
  std::vector<Sample> history_;   // ring, sized at construction
  std::size_t history_head_ = 0;  // index of the newest sample
  std::size_t history_count_ = 0;
};

}  // namespace rovctl::hal::mock
