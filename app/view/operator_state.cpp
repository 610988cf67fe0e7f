// Field names carry units, as in the telemetry CSV; NaN becomes null.
#include "app/view/operator_state.hpp"

#include <cmath>

#include "app/tools/json_writer.hpp"
#include "control/mission.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::app {

std::string operator_state_json(const TelemetryRecord& r, const OperatorStateContext& context) {
  const auto flag = [&r](std::uint32_t bit) { return (r.flags & bit) != 0; };
  const bool estimate = flag(telemetry_flag::estimate_valid);
  const bool errors = flag(telemetry_flag::dock_errors_valid);
  const int state = r.mission_state;
  const char* state_name = state >= 0 && state < control::kMissionStateCount
                               ? control::to_string(static_cast<control::MissionState>(state))
                               : "unknown";
  const double distance_m =
      estimate ? std::sqrt(r.est_t_m[0] * r.est_t_m[0] + r.est_t_m[1] * r.est_t_m[1] +
                           r.est_t_m[2] * r.est_t_m[2])
               : NAN;
  JsonWriter w;
  w.begin_object();
  w.field("source", context.source);
  w.field("tick", static_cast<long>(r.tick));
  w.field("time_s", r.time_s);
  w.field("state", state_name);
  w.field("operator_hold", flag(telemetry_flag::operator_hold));
  w.field("failsafe", flag(telemetry_flag::failsafe));
  w.field("armed", flag(telemetry_flag::armed));
  w.field("capture_failed", flag(telemetry_flag::capture_failed));
  w.field("overrun", flag(telemetry_flag::overrun));
  w.field("recognised", flag(telemetry_flag::recognised));
  w.field("ok", flag(telemetry_flag::full_view));
  // Not ok says which test failed: a bound over the line is not a partial view.
  w.field("not_ok_reason",
          estimator::to_string(static_cast<estimator::NotOkReason>(r.not_ok_reason)));
  w.field("fitness", estimate ? r.fitness : NAN);
  w.begin_array("spheres_seen").value(r.spheres_seen_left).value(r.spheres_seen_right).end_array();
  w.field("error_bound_mm", r.error_bound_m * 1000.0);
  w.field("error_bound_deg", r.error_bound_deg);
  w.field("distance_m", distance_m);
  w.field("lateral_error_mm", errors ? r.dock_lateral_error_m * 1000.0 : NAN);
  w.field("axial_error_mm", errors ? r.dock_axial_error_m * 1000.0 : NAN);
  w.field("yaw_error_deg", errors ? r.dock_yaw_error_rad * 180.0 / M_PI : NAN);
  w.begin_array("thrust_fraction");
  for (int i = 0; i < r.thruster_count && i < static_cast<int>(r.thruster_cmd.size()); ++i) {
    w.value(r.thruster_cmd[static_cast<std::size_t>(i)]);
  }
  w.end_array();
  w.field("bus", hal::to_string(static_cast<hal::BusStatus>(r.bus_status)));
  w.field("commands_enabled", context.commands_enabled);
  w.field("abort_requested_tick", static_cast<long>(context.abort_requested_tick));
  w.end_object();
  return w.str();
}

}  // namespace rovctl::app
