// One closed-loop docking trial: the real VehicleLoop and scheduler against a SimulatedHal, from
// the trial's randomised start until docked, failed or out of time. Shared by `rovctl sim`, the
// integration tests and the benchmarks.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "app/runtime/app_config.hpp"
#include "app/runtime/operator_link.hpp"
#include "app/runtime/telemetry.hpp"
#include "control/failsafe.hpp"
#include "hal/mock/trial_generator.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

struct TrialOptions {
  bool realtime = false;                  // pace by the wall clock (else virtual time)
  double max_time_s = 150.0;              // sim time limit per trial
  bool keep_records = false;              // keep every tick's telemetry (for CSV and plots)
  bool log_events = false;                // print mission/failsafe events to stderr live
  OperatorLink* operator_link = nullptr;  // a live operator view (rovctl sim --serve), or none
  bool operator_hold_at_start = false;    // begin held: the operator's START begins the mission
  // The simulated operator asks to end the charge (VehicleLoop::request_undock()) once the
  // mission has been in CHARGING this long (physics time); < 0: never.
  double undock_request_after_charging_s = -1.0;
  // One thruster fails mid-approach: "dead", "weak" or "stuck" (sim.faults.thruster_*; "" for
  // none). Which of the layout's thrusters, and when — uniform over the first
  // thruster_fault_window_s of APPROACH, or its last tick if it ends sooner — are drawn per trial
  // from its seed.
  std::string thruster_fault;
  double thruster_fault_window_s = 2.0;
};

// One sample per tick of the recharging side, for the plots (kept with keep_records).
struct ChargeSample {
  double time_s = 0.0;
  double soc_fraction = 0.0;
  double charge_current_a = 0.0;
  double thruster_power_w = 0.0;   // electrical, from the thrusters' thrust
  double current_speed_mps = 0.0;  // the water's horizontal speed at the vehicle
  bool seated = false;
};

// The recharging mission's figures for one trial, from the simulator's truth. Times and energies
// in battery time (the charge sped up by sim.recharge.seated_time_scale) unless named _physics_.
struct RechargeResult {
  bool charging_reached = false;
  bool charged = false;                   // the mission ended the charge as complete
  bool departed = false;                  // the mission reached DEPARTED
  std::string end_reason;                 // why the charge ended (the event into UNDOCK)
  double charging_physics_s = 0.0;        // ticks in CHARGING
  double seated_physics_s = 0.0;          // of those, seated (truth)
  double seated_s = 0.0;                  // seated while charging, battery time
  double contact_fraction = 0.0;          // seated_physics_s / charging_physics_s
  double unseated_unnoticed_max_s = 0.0;  // longest unseated stretch still in CHARGING
  int reseats = 0;
  double hold_wh = 0.0;        // thruster energy from the first CHARGING to UNDOCK
  double charged_wh = 0.0;     // given by the charger (to the battery and the loads)
  double hold_fraction = 0.0;  // hold_wh / charged_wh (0 when nothing was charged)
  double soc_start = 0.0;
  double soc_end = 0.0;
  double undock_clearance_m = -1.0;    // probe tip back from the socket mouth on DEPARTED
  double end_clearance_m = 0.0;        // and at the end of the trial, whatever the state
  bool undock_marker_in_view = false;  // the marker recognised in the tick DEPARTED began
  std::vector<ChargeSample> samples;
};

// A failsafe event as the loop logged it (trip, back-out done, recovered, latched).
struct FailsafeLogEntry {
  double time_s = 0.0;
  std::uint64_t tick = 0;
  control::FailsafeCause cause = control::FailsafeCause::none;
  control::FailsafeEventKind kind = control::FailsafeEventKind::trip;
};

struct TrialResult {
  hal::mock::TrialConditions conditions;
  bool docked = false;          // the simulator's verdict: captured, centred, aligned
  bool mission_docked = false;  // the mission reached DOCKED
  bool success = false;         // docked within the lateral/yaw tolerances at contact
  double time_to_dock_s = -1.0;
  double lateral_error_mm = -1.0;  // probe tip off the socket axis at capture
  // The largest lateral error (mm) at which the probe touched the station (face or socket), -1
  // if it never touched: over kTouchOffCentreMm it hit the rim, not the funnel.
  double touch_lateral_max_mm = -1.0;
  double yaw_error_deg = 0.0;  // heading error at capture
  double sim_time_s = 0.0;
  std::string final_state;
  int aborts = 0;
  std::string failsafe;  // cause, or empty
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;  // releases skipped
  // At the mock bus: non-zero commands sent after a later neutral one (stale: must be 0), and
  // non-zero requests already in flight to a slow peer that landed after a neutral was written.
  std::uint64_t bus_stale_sent = 0;
  std::uint64_t bus_landed_after_neutral = 0;
  double jitter_p99_ms = 0.0;
  double jitter_max_ms = 0.0;
  double estimator_ms_mean = 0.0;
  double recognised_fraction = 0.0;
  double estimate_error_mm_median = -1.0;  // while recognised
  // Ticks whose estimate was ok, and of those the ones the truth of their own image (the camera's
  // capture instant, not the tick's: latency is the servo's business) puts at or over
  // kRightTranslationMm or kRightRotationDeg: ok but wrong, as `rovctl bench --set` counts it.
  std::uint64_t ok_ticks = 0;
  std::uint64_t ok_wrong_ticks = 0;
  // Ok ticks whose error against their image's truth is over their own error bound (translation
  // or rotation): how often the bound, a 99 % quantile, fails to cover (about 1 % when it is true).
  std::uint64_t ok_over_bound_ticks = 0;
  double ok_error_mm_max = 0.0, ok_error_deg_max = 0.0;  // the worst ok tick's, against its image
  // Ok ticks whose pose the tracker carried (coasted or aided by a partial view) through a frame
  // whose estimate was not sound.
  std::uint64_t ok_carried_ticks = 0;
  double frame_cpu_ms_p95 = 0.0;  // VehicleLoop::last_compute_time() over the trial's ticks
  std::vector<std::string> events;
  std::vector<FailsafeLogEntry> failsafe_log;
  std::vector<TelemetryRecord> records;  // when keep_records
  bool recharge = false;                 // mission.kind recharge
  RechargeResult charge;
};

// The recharging mission's verdict: docked (as trial_docked), charged to completion, departed
// clear of the station with the marker in view.
bool trial_recharged(const TrialResult& r);

// Tolerances at contact that count as a successful dock (the targets).
constexpr double kSuccessLateralMm = 10.0;
constexpr double kSuccessYawDeg = 3.0;

// Docked means all three: the simulator captured the probe, within the tolerances, and the
// mission itself reached DOCKED (a vehicle that touched the socket but kept thrusting, or
// thought it was elsewhere, did not dock).
bool trial_docked(const TrialResult& r);

// Runs trial `conditions` with `config` on the calibrated rig. Throws on bad config.
TrialResult run_docking_trial(const AppConfig& config, const hal::StereoRig& rig,
                              const hal::mock::TrialConditions& conditions,
                              const TrialOptions& options);

}  // namespace rovctl::app
