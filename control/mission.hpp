// The docking mission: SEARCH -> APPROACH -> ALIGN -> DOCK -> DOCKED, with ABORT (back off, search
// again, a bounded number of times) and FAILED. Decides what the servo aims at and when the
// thrusters may push; every transition is queued as an event. The tick allocates nothing.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstddef>

#include "control/control_params.hpp"
#include "control/thruster_effectiveness.hpp"

namespace rovctl::control {

enum class MissionState { search, approach, align, dock, docked, abort, failed };
const char* to_string(MissionState s);

struct MissionInput {
  std::chrono::nanoseconds now{0};
  bool recognised = false;  // the estimator's verdict
  // Every sphere supported in both views (the estimator's ok). A partial view is enough to
  // search and approach on; aligning for the dock and docking itself need the full view (inside
  // the blind zone at the end of the push a partial view is all there is).
  bool full_view = false;
  double fitness = 0.0;  // the estimate's fitness (also gated by min_fitness)
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  bool contact = false;  // contact switch if the vehicle has one; the sim reports it
};

// The application's contract: thrusters_enabled false -> neutral. Else if servo_active:
// servo_restart -> PdVisualServo::reset(), then the wrench is the servo's, aimed at
// T_cl_marker_desired. Else if use_override: wrench_override_body plus the servo's
// hold_wrench_body() (feed-forward and integral: the trim against buoyancy and current).
// The servo need not be reset after a brief loss (it restarts its derivative after a gap).
struct MissionOutput {
  MissionState state = MissionState::search;
  bool servo_active = false;
  bool servo_restart = false;  // the servo starts afresh this tick (integral and derivative)
  Eigen::Isometry3d T_cl_marker_desired = Eigen::Isometry3d::Identity();
  Wrench wrench_override_body = Wrench::Zero();
  bool use_override = false;
  bool thrusters_enabled = true;
  // The control point's error against the docking axis, when the marker is seen this tick:
  // lateral = off the axis, axial = along it (negative: short of the docked position), yaw of
  // the docking axis in body x-y.
  bool errors_valid = false;
  double lateral_error_m = 0.0;
  double axial_error_m = 0.0;
  double yaw_error_rad = 0.0;
};

struct MissionEvent {
  std::chrono::nanoseconds time{0};
  MissionState from = MissionState::search;
  MissionState to = MissionState::search;
  const char* reason = "";  // static string
  int aborts = 0;
};

// The desired T_cl_marker with the vehicle moved back by `back_m` along the docking axis
// (marker +z) from `T_cl_marker_docked`; negative values go past it, into the station.
Eigen::Isometry3d offset_along_docking_axis(const Eigen::Isometry3d& T_cl_marker_docked,
                                            double back_m);

class Mission {
 public:
  static constexpr std::size_t kEventCapacity = 32;

  // control_point_body_m: the body point that must meet the socket (the probe tip); lateral and
  // axial errors are measured there. The docked pose comes from hal::docked_T_cl_marker().
  Mission(const MissionParams& params, const Eigen::Isometry3d& T_body_cl,
          const Eigen::Isometry3d& T_cl_marker_docked,
          const Eigen::Vector3d& control_point_body_m = Eigen::Vector3d::Zero());

  // One tick. `in.now` must not go backwards. No allocation.
  MissionOutput update(const MissionInput& in);

  // Back to SEARCH with no aborts counted (a new mission); logged.
  void restart(std::chrono::nanoseconds now);

  MissionState state() const { return state_; }
  int aborts() const { return aborts_; }
  const Eigen::Isometry3d& standoff_T_cl_marker() const { return T_standoff_; }
  const Eigen::Isometry3d& docked_T_cl_marker() const { return T_docked_; }

  // Oldest queued transition; false when none. The queue keeps the newest kEventCapacity
  // events; dropped_events() counts those overwritten.
  bool pop_event(MissionEvent& event);
  std::size_t dropped_events() const { return dropped_; }

 private:
  struct Errors {
    double lateral_m, axial_m, yaw_rad;
  };
  Errors errors(const Eigen::Isometry3d& T_cl_marker) const;
  void enter(MissionState to, std::chrono::nanoseconds now, const char* reason);
  void push_event(const MissionEvent& e);

  MissionParams p_;
  Eigen::Isometry3d T_body_cl_;
  Eigen::Isometry3d T_docked_;
  Eigen::Isometry3d T_standoff_;
  Eigen::Vector3d control_point_body_m_;
  Eigen::Vector3d cp_docked_marker_m_;  // the control point in the marker frame when docked

  MissionState state_ = MissionState::search;
  std::chrono::nanoseconds entered_{0};
  bool started_ = false;
  bool servo_was_active_ = false;
  int aborts_ = 0;
  int seen_frames_ = 0;
  int unseen_frames_ = 0;
  int partial_frames_ = 0;  // consecutive frames recognised on a partial view
  int hold_frames_ = 0;
  int contact_frames_ = 0;
  int dock_off_frames_ = 0;  // consecutive seen frames past the dock abort limits
  bool have_last_ = false;
  double last_axial_m_ = 0.0;
  Eigen::Vector3d docked_axis_body_ = Eigen::Vector3d::UnitX();  // docking axis when docked
  std::chrono::nanoseconds blind_since_{-1};

  std::array<MissionEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_count_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace rovctl::control
