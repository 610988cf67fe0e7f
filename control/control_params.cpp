// Parameter declarations of the `control` and `mission` config sections.
#include "control/control_params.hpp"

namespace rovctl::control {

void describe(hal::ParamVisitor& v, DisturbanceParams& p) {
  v.param("hold_fraction", p.hold_fraction,
          {"-", 0.1, 1.0,
           "share of the thrusters' force along each axis the current's estimate may take"});
  v.param(
      "settle_rate_nps", p.settle_rate_nps,
      {"N/s", 0.01, 100.0, "the estimate is settled while its horizontal force changes slower"});
  v.param("settle_s", p.settle_s,
          {"s", 0.0, 60.0, "... for this long (ALIGN's hold counts only settled frames)"});
  v.param("rate_cutoff_hz", p.rate_cutoff_hz,
          {"Hz", 0.01, 15.0, "cut-off of the two low-pass poles on the estimate's rate of change"});
  v.param("beyond_hold_s", p.beyond_hold_s,
          {"s", 0.1, 600.0,
           "at its limit or with the thrusters saturated this long: current beyond hold"});
  v.param("swept_fraction", p.swept_fraction,
          {"-", 0.0, 1.0,
           "share of its limit the still rising estimate must reach for a marker lost to count "
           "toward mission.beyond_hold_losses"});
}

void describe(hal::ParamVisitor& v, ServoParams& p) {
  v.param("six_dof", p.six_dof,
          "servo all six axes; false servoes x, y, z and yaw and only damps roll and pitch");
  v.param("kp_linear", p.kp_linear,
          {"N/m", 0.0, 1000.0, "proportional gains on the position error, body x, y, z"});
  v.param("kd_linear", p.kd_linear,
          {"N s/m", 0.0, 1000.0, "derivative gains on the filtered position-error rate"});
  v.param("ki_linear", p.ki_linear,
          {"N/(m s)", 0.0, 1000.0, "integral gains on the position error (0 = no integral)"});
  v.param("kp_angular", p.kp_angular,
          {"N m/rad", 0.0, 200.0, "proportional gains on the roll, pitch, yaw error"});
  v.param("kd_angular", p.kd_angular,
          {"N m s/rad", 0.0, 200.0, "derivative gains on the filtered angle-error rate"});
  v.param("ki_angular", p.ki_angular,
          {"N m/(rad s)", 0.0, 200.0, "integral gains on the angle error (0 = no integral)"});
  v.param("integral_limit_linear_n", p.integral_limit_linear_n,
          {"N", 0.0, 500.0, "anti-windup: largest integral force per body axis"});
  v.param("integral_limit_angular_nm", p.integral_limit_angular_nm,
          {"N m", 0.0, 100.0, "anti-windup: largest integral moment per body axis"});
  v.param("max_position_error_m", p.max_position_error_m,
          {"m", 0.01, 20.0, "position error norm seen by P and I (bounds the approach speed)"});
  v.param("max_angle_error_rad", p.max_angle_error_rad,
          {"rad", 0.01, 3.2, "rotation error norm seen by P and I"});
  v.param("rate_cutoff_hz", p.rate_cutoff_hz,
          {"Hz", 0.05, 15.0, "cut-off of the low-pass on the differentiated error"});
  v.param("max_rate_linear_mps", p.max_rate_linear_mps,
          {"m/s", 0.0, 20.0, "position-error rate clamp before the low-pass (0 = none)"});
  v.param("max_rate_angular_radps", p.max_rate_angular_radps,
          {"rad/s", 0.0, 50.0, "angle-error rate clamp before the low-pass (0 = none)"});
  v.param("max_update_gap_s", p.max_update_gap_s,
          {"s", 0.01, 5.0, "a longer gap between updates restarts the derivative"});
  v.param("net_buoyancy_n", p.net_buoyancy_n,
          {"N", -100.0, 100.0, "buoyancy minus weight; fed forward as a downward force"});
  v.section("disturbance", "the integral term as the estimate of the current's push",
            [&p](hal::ParamVisitor& s) { describe(s, p.disturbance); });
}

void describe(hal::ParamVisitor& v, AllocationParams& p) {
  hal::param_list(v, "thruster_weights",
                  "effort weights of named thrusters (higher = used less; others weigh 1)",
                  p.thruster_weights, 0, 8, [](hal::ParamVisitor& e, ThrusterWeight& w) {
                    e.param("thruster", w.thruster, "thruster name from vehicle.thrusters", {},
                            true);
                    e.param("weight", w.weight, {"-", 0.01, 100.0, "effort weight", true});
                  });
  v.param("axis_weights_force", p.axis_weights_force,
          {"-", 0.001, 1000.0, "priority of Fx, Fy, Fz when not every axis can be produced"});
  v.param("axis_weights_moment", p.axis_weights_moment,
          {"-", 0.001, 1000.0, "priority of Mx, My, Mz when not every axis can be produced"});
  v.param("deadband", p.deadband,
          {"-", 0.0, 0.5, "ESC deadband (command fraction) that the commands skip; 0 for none"});
}

void describe(hal::ParamVisitor& v, FailsafeParams& p) {
  v.param("camera_timeout_ticks", p.camera_timeout_ticks,
          {"ticks", 0, 1000, "consecutive camera timeouts tolerated (vision lost beyond)"});
  v.param("bus_degraded_ticks", p.bus_degraded_ticks,
          {"ticks", 0, 1000,
           "consecutive degraded bus reports tolerated (bus slow beyond); a real bus reports "
           "degraded only once its heartbeat gap passed thruster_bus.timing.degraded_ms"});
  v.param("max_mission_time_s", p.max_mission_time_s,
          {"s", 1.0, 86400.0, "mission time (CHARGING not counted) after which it is made safe"});
  v.param("action", p.action, "safe state of the causes whose policy action is 'default'",
          {"disarm", "neutral"});
  v.param(
      "backout_s", p.backout_s,
      {"s", 0.0, 60.0, "a trip in the socket: back out along the docking axis this long first"});
  v.param("frozen_ticks", p.frozen_ticks,
          {"ticks", 1, 1000, "identical images this many ticks in a row: vision frozen"});
  v.param("stale_ms", p.stale_ms, {"ms", 1.0, 10000.0, "the newest frame older: vision stale"});
  v.param("stereo_skew_ms", p.stereo_skew_ms,
          {"ms", 0.0, 1000.0, "left and right captured further apart: stereo skew"});
  v.param("dead_range_levels", p.dead_range_levels,
          {"levels", 0, 255, "an image spanning no more grey levels is dead (black, covered)"});
  v.param("sensor_lost_ticks", p.sensor_lost_ticks,
          {"ticks", 1, 1000, "the sensors silent this many ticks in a row: sensors lost"});
  v.param("min_depth_m", p.min_depth_m,
          {"m", -100.0, 0.0, "shallowest plausible depth reading (above the surface: negative)"});
  v.param("max_depth_m", p.max_depth_m, {"m", 1.0, 11000.0, "deepest plausible depth reading"});
  v.param("max_rate_radps", p.max_rate_radps,
          {"rad/s", 0.1, 100.0, "fastest plausible gyro reading on any axis"});
  v.param("min_soc_fraction", p.min_soc_fraction,
          {"-", 0.0, 0.5,
           "battery state of charge below which the failsafe trips battery_low (0: never); below "
           "what the recharge mission docks at"});
  v.param("attitude_limit_rad", p.attitude_limit_rad,
          {"rad", 0.05, 3.14, "roll or pitch beyond this: attitude limit"});
  v.param("overrun_ticks", p.overrun_ticks,
          {"ticks", 1, 1000, "consecutive ticks past the next release: cpu overrun"});
  v.param("recover_ticks", p.recover_ticks,
          {"ticks", 1, 10000, "an auto cause gone this many ticks in a row: recovered"});
  v.param("recover_within_s", p.recover_within_s,
          {"s", 0.1, 86400.0, "an auto trip not recovered within this latches"});
  v.section("policy", "per cause: the safe action and whether the trip recovers or latches",
            [&p](hal::ParamVisitor& s) { describe(s, p.policy); });
}

void describe(hal::ParamVisitor& v, AttitudeParams& p) {
  v.param("enabled", p.enabled,
          "hold roll and pitch level from the IMU (when the servo is not six_dof)");
  v.param("roll_kp_nm_per_rad", p.roll_kp_nm_per_rad,
          {"N m/rad", 0.0, 200.0, "roll moment per radian of roll"});
  v.param("roll_kd_nms_per_rad", p.roll_kd_nms_per_rad,
          {"N m s/rad", 0.0, 200.0, "roll moment per rad/s of roll rate (gyro)"});
  v.param("pitch_kp_nm_per_rad", p.pitch_kp_nm_per_rad,
          {"N m/rad", 0.0, 200.0, "pitch moment per radian of pitch"});
  v.param("pitch_kd_nms_per_rad", p.pitch_kd_nms_per_rad,
          {"N m s/rad", 0.0, 200.0, "pitch moment per rad/s of pitch rate (gyro)"});
  v.param("max_moment_nm", p.max_moment_nm,
          {"N m", 0.0, 200.0, "largest levelling moment per axis"});
}

void describe(hal::ParamVisitor& v, ControlParams& p) {
  v.section("servo", "PD visual servo on the relative-pose error",
            [&p](hal::ParamVisitor& s) { describe(s, p.servo); });
  v.section("attitude", "roll and pitch levelling from the IMU",
            [&p](hal::ParamVisitor& s) { describe(s, p.attitude); });
  v.section("allocation", "thruster allocation (weighted pseudo-inverse)",
            [&p](hal::ParamVisitor& s) { describe(s, p.allocation); });
  v.section("failsafe", "run-time fault monitors and the safe state",
            [&p](hal::ParamVisitor& s) { describe(s, p.failsafe); });
  v.section("thruster_health", "failed thrusters detected from ESC telemetry, then not allocated",
            [&p](hal::ParamVisitor& s) { describe(s, p.thruster_health); });
  v.section("tracker",
            "the marker's pose carried across frames: sound estimates fused, declined frames "
            "coasted on the attitude and the track's velocity with a growing bound",
            [&p](hal::ParamVisitor& s) { describe(s, p.tracker); });
}

void describe(hal::ParamVisitor& v, PoseTrackerParams& p) {
  v.param("enabled", p.enabled,
          "the mission acts on the pose tracked across frames; false: on each frame's estimate "
          "alone");
  v.param(
      "max_coast_s", p.max_coast_s,
      {"s", 0.0, 10.0, "the tracked pose is ok at most this long after the last fused estimate"});
  v.param("accel_mps2", p.accel_mps2,
          {"m/s^2", 0.0, 20.0,
           "how fast the vehicle's velocity changes: a coast's position bound grows by half this "
           "times its time squared"});
  v.param("speed_mps", p.speed_mps,
          {"m/s", 0.01, 10.0,
           "the fastest the vehicle moves: the velocity's bound before the track has a history"});
  v.param("attitude_drift_dps", p.attitude_drift_dps,
          {"deg/s", 0.0, 90.0,
           "the attitude sensor's error growth: a coast's rotation bound grows at this rate"});
  v.param(
      "attitude_filter_s", p.attitude_filter_s,
      {"s", 0.0, 60.0,
       "the body rates carry the attitude between reads, pulled toward the attitude sensor's "
       "with this time constant (its read-to-read noise moves the marker at range); 0: as read"});
  v.param("turn_rate_dps", p.turn_rate_dps,
          {"deg/s", 0.0, 720.0,
           "the fastest the vehicle turns: the rotation bound's growth without a valid attitude"});
  v.param("floor_mm", p.floor_mm,
          {"mm", 0.0, 1000.0, "the fused position bound never goes below this"});
  v.param("floor_deg", p.floor_deg,
          {"deg", 0.0, 180.0, "the fused rotation bound never goes below this"});
  v.param("fused_bound_share", p.fused_bound_share,
          {"-", 0.0, 1.0,
           "nor below this share of the newest estimate's own bound (consecutive estimates share "
           "their errors)"});
  v.param("partial_point_mm", p.partial_point_mm,
          {"mm", 0.0, 100.0,
           "a partial view's sphere centres (their rims seen in both views) lie within this: two "
           "or more that agree under the track's rotation update its translation; 0: not used"});
  v.param("unexplained_window_s", p.unexplained_window_s,
          {"s", 0.0, 60.0,
           "sound estimates' disagreement with the prediction beyond both bounds, over about this "
           "long, is the camera's motion the attitude does not carry (shaking on its mount): it "
           "widens the prediction's bounds; 0: off"});
  v.param("velocity_window_s", p.velocity_window_s,
          {"s", 0.05, 10.0,
           "the velocity is the slope of the fused positions over this much of the history"});
}

void describe(hal::ParamVisitor& v, ThrusterHealthParams& p) {
  v.param("enabled", p.enabled, "read the ESCs' telemetry each tick and drop failed thrusters");
  v.param("full_thrust_rpm", p.full_thrust_rpm,
          {"rpm", 100.0, 100000.0, "propeller speed at full thrust"});
  v.param("time_constant_s", p.time_constant_s,
          {"s", 0.0, 2.0, "lag of the thrust behind its command, for the expected rpm"});
  v.param("min_expected_rpm", p.min_expected_rpm,
          {"rpm", 0.0, 100000.0, "expected rpm below which the rpm ratio is not judged"});
  v.param("stuck_idle_rpm", p.stuck_idle_rpm,
          {"rpm", 0.0, 100000.0, "rpm that, with next to none expected, means a stuck thruster"});
  v.param("dead_rpm_ratio", p.dead_rpm_ratio, {"-", 0.0, 1.0, "rpm / expected below this: dead"});
  v.param("weak_rpm_ratio", p.weak_rpm_ratio, {"-", 0.0, 1.0, "rpm / expected below this: weak"});
  v.param("overspeed_rpm_ratio", p.overspeed_rpm_ratio,
          {"-", 1.0, 100.0, "rpm / expected above this (or reversed): stuck"});
  v.param("fault_flag_ticks", p.fault_flag_ticks,
          {"ticks", 1, 1000, "consecutive ticks an ESC fault flag must last to fail the thruster"});
  v.param("mismatch_ticks", p.mismatch_ticks,
          {"ticks", 1, 1000, "consecutive ticks an rpm mismatch must last to fail the thruster"});
}

void describe(hal::ParamVisitor& v, RechargeParams& p) {
  v.param("charge_push_n", p.charge_push_n,
          {"N", 0.0, 200.0, "CHARGING: feed-forward push along the docking axis"});
  v.param("seat_trim_rise_nps", p.seat_trim_rise_nps,
          {"N/s", 0.0, 100.0,
           "CHARGING: the push grows at this rate while the probe slips out of the seat (the "
           "contact lost, or seen seat_slip_m short of the socket's bottom), up to "
           "overload_force_n"});
  v.param("seat_trim_decay_nps", p.seat_trim_decay_nps,
          {"N/s", 0.0, 100.0, "CHARGING: the added push shrinks at this rate while seated"});
  v.param("seat_slip_m", p.seat_slip_m,
          {"m", 0.0, 0.1,
           "CHARGING: the probe seen (over a tenth of a second) this far short of the socket's "
           "bottom (station.capture_depth_m) is slipping out; not shallower than "
           "mission.vision_contact_depth_m"});
  v.param("soc_complete_fraction", p.soc_complete_fraction,
          {"-", 0.0, 1.0, "state of charge that completes the charge"});
  v.param("complete_current_a", p.complete_current_a,
          {"A", 0.0, 1000.0, "charge current below which the charge is complete (tapered)"});
  v.param("complete_min_soc_fraction", p.complete_min_soc_fraction,
          {"-", 0.0, 1.0, "SoC from which a low charge current means complete, not a fault"});
  v.param("charge_timeout_s", p.charge_timeout_s,
          {"s", 1.0, 1e6, "CHARGING time limit (then UNDOCK)"});
  v.param("unseat_confirm_s", p.unseat_confirm_s,
          {"s", 0.0, 60.0, "contact lost (or vision: probe out) this long counts as unseated"});
  v.param("vision_unseat_m", p.vision_unseat_m,
          {"m", 0.0, 0.5, "vision: probe this far short of the socket mouth is unseated"});
  v.param("max_reseats", p.max_reseats,
          {"-", 0, 100, "re-seats (DOCK again) allowed; one more unseat: UNDOCK, then ABORT"});
  v.param("no_current_a", p.no_current_a,
          {"A", 0.0, 1000.0, "charge current below which the charger delivers nothing"});
  v.param("no_current_s", p.no_current_s,
          {"s", 0.1, 600.0, "seated without charge current this long: UNDOCK (charger fault)"});
  v.param("overload_force_n", p.overload_force_n,
          {"N", 1.0, 1000.0, "horizontal hold force beyond which the current is too strong"});
  v.param("overload_s", p.overload_s,
          {"s", 0.0, 600.0, "how long the hold may exceed overload_force_n before UNDOCK"});
  v.param("overload_yaw_rad", p.overload_yaw_rad,
          {"rad", 0.0, 1.0, "seated yaw error beyond which the current turns the vehicle off"});
  v.param("overload_yaw_s", p.overload_yaw_s,
          {"s", 0.0, 600.0, "how long the yaw error may exceed overload_yaw_rad before UNDOCK"});
  v.param("undock_speed_mps", p.undock_speed_mps,
          {"m/s", 0.005, 1.0, "UNDOCK: speed of the set-point backing out along the axis"});
  v.param("undock_push_n", p.undock_push_n,
          {"N", 0.0, 200.0, "UNDOCK: backward push while the marker is not seen"});
  v.param("undock_timeout_s", p.undock_timeout_s,
          {"s", 1.0, 3600.0, "UNDOCK time limit (then FAILED)"});
  v.param("departed_action", p.departed_action,
          "DEPARTED: thrusters neutral, or hold the stand-off on the servo", {"neutral", "hold"});
}

void describe(hal::ParamVisitor& v, MissionParams& p) {
  v.param("kind", p.kind,
          "dock: end at DOCKED; recharge: then hold seated while charging, undock and depart",
          {"dock", "recharge"});
  v.section("recharge", "the recharging mission after DOCKED",
            [&p](hal::ParamVisitor& s) { describe(s, p.recharge); });
  v.param("min_fitness", p.min_fitness,
          {"-", 0.0, 1.0, "estimate fitness at or above which the marker counts as recognised"});
  v.param("acquire_frames", p.acquire_frames,
          {"frames", 1, 1000, "consecutive recognised frames that end SEARCH"});
  v.param("lost_frames", p.lost_frames,
          {"frames", 1, 1000, "consecutive unrecognised frames that abort APPROACH/ALIGN/DOCK"});
  v.param("search_yaw_moment_nm", p.search_yaw_moment_nm,
          {"N m", -20.0, 20.0,
           "yaw moment of the SEARCH scan; its sign is the direction, except while a marker "
           "found is confirmed (mission.acquire_frames): then the scan turns toward it"});
  v.param("search_timeout_s", p.search_timeout_s,
          {"s", 1.0, 86400.0, "SEARCH time after which the failsafe trips (search_time)"});
  v.param("standoff_m", p.standoff_m,
          {"m", 0.05, 5.0, "stand-off distance back from docked along the docking axis"});
  v.param("approach_lateral_m", p.approach_lateral_m,
          {"m", 0.001, 2.0, "lateral error that ends APPROACH"});
  v.param("approach_axial_m", p.approach_axial_m,
          {"m", 0.001, 2.0, "axial error that ends APPROACH"});
  v.param("approach_yaw_rad", p.approach_yaw_rad,
          {"rad", 0.001, 3.2, "yaw error that ends APPROACH"});
  v.param("approach_view_bearing_rad", p.approach_view_bearing_rad,
          {"rad", 0.0, 1.5,
           "APPROACH: the servo turns toward the docking axis's heading only as far as keeps the "
           "marker within this bearing of the camera's axis; seen far off the axis, turning to "
           "the axis's heading first swings the marker out of view. 0: no limit"});
  v.param("approach_timeout_s", p.approach_timeout_s,
          {"s", 1.0, 3600.0, "APPROACH time limit (then ABORT)"});
  v.param("align_lateral_m", p.align_lateral_m,
          {"m", 0.0005, 1.0, "ALIGN: lateral error threshold"});
  v.param("align_axial_m", p.align_axial_m, {"m", 0.0005, 1.0, "ALIGN: axial error threshold"});
  v.param("align_yaw_rad", p.align_yaw_rad, {"rad", 0.0005, 1.0, "ALIGN: yaw error threshold"});
  v.param("align_average_frames", p.align_average_frames,
          {"frames", 1.0, 1000.0,
           "ALIGN judges the signed errors exponentially averaged over about this many full "
           "views (the estimate's frame-to-frame noise); each frame must still be within the "
           "dock abort limits. 1: each frame alone"});
  v.param("align_hold_frames", p.align_hold_frames,
          {"frames", 1, 10000, "consecutive frames within the ALIGN thresholds before DOCK"});
  v.param("align_timeout_s", p.align_timeout_s,
          {"s", 1.0, 3600.0, "ALIGN time limit (then ABORT)"});
  v.param("dock_speed_mps", p.dock_speed_mps,
          {"m/s", 0.005, 1.0, "speed of the DOCK set-point along the docking axis"});
  v.param("dock_overshoot_m", p.dock_overshoot_m,
          {"m", 0.0, 0.5, "how far past the socket mouth the DOCK set-point goes"});
  v.param("dock_abort_lateral_m", p.dock_abort_lateral_m,
          {"m", 0.001, 1.0, "DOCK aborts beyond this lateral error"});
  v.param("dock_abort_yaw_rad", p.dock_abort_yaw_rad,
          {"rad", 0.001, 3.2, "DOCK aborts beyond this yaw error"});
  v.param(
      "dock_wait_lateral_m", p.dock_wait_lateral_m,
      {"m", 0.001, 1.0, "DOCK's set-point waits while the probe is seen this far off the axis"});
  v.param("dock_wait_backoff_m", p.dock_wait_backoff_m,
          {"m", 0.0, 0.2,
           "while DOCK waits, its set-point stays at least this far behind the probe: a "
           "set-point left ahead, where the servo's lag put it, carries the probe on into the "
           "station face off the axis"});
  v.param(
      "dock_wait_filter_s", p.dock_wait_filter_s,
      {"s", 0.0, 5.0,
       "time constant of the lateral error DOCK's wait judges: a vibrating mount's swing "
       "(tenths of a second) averages out, a gust's drift (seconds) does not; 0: each frame's"});
  v.param("dock_abort_frames", p.dock_abort_frames,
          {"frames", 1, 1000, "consecutive frames past the dock abort limits before aborting"});
  v.param("dock_timeout_s", p.dock_timeout_s, {"s", 1.0, 3600.0, "DOCK time limit (then ABORT)"});
  v.param("dock_partial_timeout_s", p.dock_partial_timeout_s,
          {"s", 0.0, 60.0,
           "partial view in DOCK (a sphere hidden or half out of the frame): the push holds where "
           "it is for up to this long, then ABORT"});
  v.param("partial_view_attitude_s", p.partial_view_attitude_s,
          {"s", 0.0, 60.0,
           "a partial view's marker rotation comes from the attitude sensor and the last full "
           "view for up to this long (the heading drifts); DOCK steers on a partial view only so "
           "aided. 0: off"});
  v.param("dock_blind_distance_m", p.dock_blind_distance_m,
          {"m", 0.0, 2.0, "remaining distance within which losing the marker does not abort"});
  v.param("dock_blind_push_n", p.dock_blind_push_n,
          {"N", 0.0, 200.0, "push along the docking axis while docking blind"});
  v.param("dock_blind_timeout_s", p.dock_blind_timeout_s,
          {"s", 0.0, 60.0, "longest blind push before ABORT"});
  v.param("contact_switch", p.contact_switch, "the contact input (switch, sim) ends DOCK");
  v.param("contact_from_vision", p.contact_from_vision,
          "vision alone may end DOCK (probe past the socket mouth, within the lateral limit)");
  v.param("vision_contact_depth_m", p.vision_contact_depth_m,
          {"m", 0.0, 0.5, "depth past the socket mouth that vision counts as contact"});
  v.param("contact_frames", p.contact_frames,
          {"frames", 1, 1000, "consecutive frames of contact that end DOCK"});
  v.param("abort_backoff_force_n", p.abort_backoff_force_n,
          {"N", 0.0, 200.0, "backward force while backing off in ABORT"});
  v.param("abort_backoff_s", p.abort_backoff_s,
          {"s", 0.0, 60.0,
           "duration of the back-off; none after a marker lost in APPROACH or ALIGN, short of the "
           "station, which searches at once"});
  v.param("max_retries", p.max_retries,
          {"-", 0, 100, "aborts allowed; one more and the mission fails"});
  v.param("beyond_hold_losses", p.beyond_hold_losses,
          {"-", 1, 100,
           "markers lost before the dock while the current's estimate was still rising toward "
           "the push (since it last settled in view) that make the current beyond hold"});
}

}  // namespace rovctl::control
