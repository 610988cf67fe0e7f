// VehicleLoop: one 33 ms tick of the application — capture, estimate, mission and servo,
// failsafe, allocation, actuate, telemetry — over the hal interfaces, so the same code flies the
// vehicle and the simulation. Nothing in tick() allocates or blocks on a non-real-time thread.
#pragma once

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "app/runtime/app_config.hpp"
#include "app/runtime/cyclic_scheduler.hpp"
#include "app/runtime/frame_monitor.hpp"
#include "app/runtime/operator_link.hpp"
#include "app/runtime/telemetry.hpp"
#include "control/attitude_aided_pose.hpp"
#include "control/attitude_filter.hpp"
#include "control/attitude_stabilizer.hpp"
#include "control/control_allocation_pseudo_inverse.hpp"
#include "control/failsafe.hpp"
#include "control/mission.hpp"
#include "control/pd_visual_servo.hpp"
#include "control/pose_tracker.hpp"
#include "control/thruster_health.hpp"
#include "drivers/mavlink/gcs_status.hpp"
#include "estimator/pose_confirmation.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/interfaces/sensors.hpp"
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/stereo_rig.hpp"
#include "hal/primitives/spsc_ring.hpp"

namespace rovctl::app {

// A mission transition, failsafe trip or thruster failure, handed from the tick to whoever logs
// (POD, no heap).
struct LoopEvent {
  std::chrono::nanoseconds time{0};
  bool failsafe = false;
  control::MissionState from = control::MissionState::search;
  control::MissionState to = control::MissionState::search;
  control::FailsafeCause cause = control::FailsafeCause::none;
  control::SafeAction action = control::SafeAction::none;
  control::FailsafeEventKind failsafe_kind = control::FailsafeEventKind::trip;
  std::uint64_t tick = 0;  // the loop's tick count when it happened (failsafes, thrusters)
  // Static string: why a mission transition happened, or why the bus reported a fault (its
  // fault_reason(), empty when it does not say).
  const char* reason = "";
  int aborts = 0;
  // A thruster failed and was removed from the allocation (thruster >= 0: its layout index).
  int thruster = -1;
  int thruster_channel = -1;
  control::ThrusterFailure thruster_failure = control::ThrusterFailure::none;
  std::size_t thrusters_left = 0;
  bool servo_axes_controllable = true;
};
std::string format_event(const LoopEvent& e);

class VehicleLoop {
 public:
  // `telemetry` may be null.
  VehicleLoop(const AppConfig& config, const hal::StereoRig& rig, hal::StereoCamera& camera,
              hal::ThrusterBus& bus, hal::Sensors* sensors, CyclicScheduler& scheduler,
              TelemetryRing* telemetry, std::uint64_t seed);
  VehicleLoop(const VehicleLoop&) = delete;
  VehicleLoop& operator=(const VehicleLoop&) = delete;

  // Arms the thrusters (neutral first). False with a message naming the bus on failure.
  bool arm(std::string& error);
  // One tick; false when the mission has ended (docked and settled, failed, or a failsafe
  // latched — with an operator attached, a latched failsafe waits for START instead).
  bool tick(const TickInfo& info);
  // Neutral and disarm; safe to call more than once.
  void disarm();
  // The operator ends the charge: the next tick in CHARGING starts UNDOCK. Any thread.
  void request_undock() { undock_requested_.store(true); }

  // The operator's view and commands (ABORT: neutral and hold until START, which begins a new
  // mission from SEARCH). Before the first tick; may be null.
  void attach_operator(OperatorLink* link) { operator_link_ = link; }
  bool operator_hold() const { return operator_hold_; }
  // The ground station's status (ArduSub's link): each tick posts its values there, lock-free.
  // Before the first tick; may be null.
  void attach_gcs(drivers::GcsStatus* gcs) { gcs_ = gcs; }
  // Starts held: neutral until the operator's START (a mission begun from the ground station).
  void hold_for_operator() { operator_hold_ = true; }

  // Events queued by tick(); pop from the logging side (the same thread in simulation).
  bool pop_event(LoopEvent& e) { return events_.try_pop(e); }

  const control::Mission& mission() const { return mission_; }
  const control::Failsafe& failsafe() const { return failsafe_; }
  const estimator::PoseEstimate& last_estimate() const { return estimate_; }
  // The pose tracked across frames this tick (source none while the tracker is off).
  const control::TrackedPose& tracked_pose() const { return tracked_; }
  const hal::ThrusterCommand& last_command() const { return command_; }
  const control::ThrusterHealth& thruster_health() const { return health_; }
  const control::ControlAllocator& allocator() const { return allocator_; }
  std::uint64_t ticks() const { return ticks_; }
  // The last tick's processor time for its frame: segment, estimate and control (capture waits
  // on the camera, actuate on the bus), by the steady clock.
  std::chrono::nanoseconds last_compute_time() const { return compute_time_; }
  std::uint64_t recognised_ticks() const { return recognised_ticks_; }
  std::uint64_t grab_failures() const { return grab_failures_; }
  std::uint64_t dropped_events() const { return dropped_events_; }

 private:
  // What one tick's stages hand each other, on the tick's stack (no heap).
  struct TickState {
    explicit TickState(const TickInfo& i) : info(i), now(i.deadline) {}
    const TickInfo& info;
    std::chrono::nanoseconds now;
    std::uint32_t flags = 0;  // telemetry_flag bits found on the way
    hal::GrabStatus grab = hal::GrabStatus::ok;
    bool have_images = false;
    bool seen = false;           // a recognised, finite estimate this tick
    bool have_readings = false;  // the sensors answered
    bool attitude = false;       // ... with a usable attitude
    bool levelled = false;       // the IMU levels roll and pitch this tick
    Eigen::Vector2d level_nm = Eigen::Vector2d::Zero();
    bool backing_out = false;  // the failsafe backs out since an earlier tick
    control::MissionInput in;
    control::MissionOutput out;
    control::Wrench wrench = control::Wrench::Zero();
    control::SafeAction action = control::SafeAction::none;
  };

  // The stages, in ARCHITECTURE.md's order; each times itself against its budget.
  void capture(TickState& t);
  void segment(TickState& t);
  void estimate(TickState& t);
  void control(TickState& t);
  void actuate(TickState& t);
  void telemetry(TickState& t);
  // Whether the run goes on after this tick (a finished mission settles for a while first).
  bool keep_running(std::chrono::nanoseconds now);

  // The control stage's parts.
  void mission_input(TickState& t);
  // The frame's estimate into the tracker; an ok track becomes the mission's pose.
  void track(TickState& t);
  void aid_partial_view(TickState& t);
  void take_operator_commands(std::chrono::nanoseconds now);
  void servo_wrench(TickState& t);
  control::Wrench back_out_wrench(const TickState& t) const;
  void run_failsafe(TickState& t);
  control::FailsafeInput failsafe_input(const TickState& t);
  void restart_mission(std::chrono::nanoseconds now, const char* reason);
  // The actuate stage's parts.
  void retry_disarm();
  void rearm_after_failsafe();
  // The telemetry stage's parts.
  void queue_mission_and_failsafe_events();
  void post_gcs_values(const TickState& t);
  void fill_record(const TickState& t, TelemetryRecord& rec) const;

  void queue(const LoopEvent& e);
  // Reads the ESCs' telemetry, judges it against the last commands and removes newly failed
  // thrusters from the allocation, each logged.
  void check_thrusters(std::chrono::nanoseconds now, std::chrono::nanoseconds period);

  const AppConfig& config_;
  hal::StereoCamera& camera_;
  hal::ThrusterBus& bus_;
  hal::Sensors* sensors_;
  CyclicScheduler& scheduler_;
  TelemetryRing* telemetry_;
  OperatorLink* operator_link_ = nullptr;
  drivers::GcsStatus* gcs_ = nullptr;

  estimator::PoseEstimator estimator_;
  estimator::PoseConfirmation confirmation_;  // an ok estimate must agree with the frame before
  control::PdVisualServo servo_;
  control::AttitudeStabilizer attitude_;
  control::ControlAllocator allocator_;
  control::ThrusterHealth health_;
  control::Mission mission_;
  control::Failsafe failsafe_;
  control::AttitudeAidedPose aided_pose_;
  control::AttitudeFilter attitude_filter_;  // the attitude the tracker carries the pose by
  control::PoseTracker tracker_;
  FrameMonitor frame_monitor_;
  SpscRing<LoopEvent> events_{256};

  hal::StereoFrame frame_;
  hal::SensorReadings readings_;
  estimator::PoseEstimate estimate_;
  control::TrackedPose tracked_;
  hal::ThrusterCommand command_;
  hal::ThrusterCommand neutral_;
  hal::BusStatus bus_status_ = hal::BusStatus::ok;       // the last write's (or arm's)
  hal::BusStatus bus_read_status_ = hal::BusStatus::ok;  // this tick's telemetry read
  bool disarm_unacked_ = false;                          // the failsafe's disarm not taken
  hal::ThrusterTelemetry thruster_telemetry_;
  bool thrusters_uncontrollable_ = false;
  bool armed_ = false;
  bool disarmed_by_failsafe_ = false;
  bool operator_hold_ = false;
  bool overrun_counted_ = false;  // this tick's overrun went to the failsafe already
  std::chrono::nanoseconds last_servo_time_{-1};
  double axial_trim_n_ = 0.0;       // the servo's x integral kept at ALIGN -> DOCK (MissionOutput)
  double last_hold_force_n_ = 0.0;  // horizontal force commanded last tick (the hold's effort)
  std::atomic<bool> undock_requested_{false};
  std::chrono::nanoseconds ended_at_{-1};
  std::uint64_t ticks_ = 0;
  std::chrono::nanoseconds compute_time_{0};
  std::uint64_t recognised_ticks_ = 0;
  std::uint64_t grab_failures_ = 0;
  std::uint64_t dropped_events_ = 0;
};

}  // namespace rovctl::app
