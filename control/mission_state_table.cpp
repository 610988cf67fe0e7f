// The mission's state table: what Mission's from_<state>() and outputs() do, said once.
#include "control/mission_state_table.hpp"

#include <cctype>

namespace rovctl::control {
namespace {

using S = MissionState;

constexpr MissionExit kSearchExits[] = {
    {"the marker recognised `mission.acquire_frames` frames in a row", S::approach,
     "marker recognised"},
    {"`mission.search_timeout_s` passed (0: never)", S::failed, "search timed out"},
};
constexpr MissionExit kApproachExits[] = {
    {"the marker unseen `mission.lost_frames` frames (an abort that searches from where it is)",
     S::abort, "marker lost"},
    {"the current's estimate at its limit (`control.servo.disturbance.hold_fraction` of the "
     "thrusters) or the thrusters saturated for `control.servo.disturbance.beyond_hold_s`; or the "
     "marker lost while it was at its limit, or lost for the `mission.beyond_hold_losses`-th time "
     "while it was still rising toward the push",
     S::failed, "current beyond hold"},
    {"`mission.approach_timeout_s` passed", S::abort, "approach timed out"},
    {"the probe within `mission.approach_lateral_m`, `mission.approach_axial_m`, "
     "`mission.approach_yaw_rad` of the "
     "stand-off",
     S::align, "stand-off reached"},
};
constexpr MissionExit kAlignExits[] = {
    {"the marker unseen `mission.lost_frames` frames (searches from where it is)", S::abort,
     "marker lost"},
    {"the errors averaged over `mission.align_average_frames` full views within "
     "`mission.align_lateral_m`, "
     "`mission.align_axial_m`, `mission.align_yaw_rad` (each frame within the dock's abort limits) "
     "for "
     "`mission.align_hold_frames` frames, counted once the current's estimate has settled "
     "(`control.servo.disturbance.settle_rate_nps` for `control.servo.disturbance.settle_s`)",
     S::dock, "aligned"},
    {"the current's estimate at its limit (`control.servo.disturbance.hold_fraction` of the "
     "thrusters) or the thrusters saturated for `control.servo.disturbance.beyond_hold_s`; or the "
     "marker lost while it was at its limit, or lost for the `mission.beyond_hold_losses`-th time "
     "while it was still rising toward the push",
     S::failed, "current beyond hold"},
    {"`mission.align_timeout_s` passed, the current's estimate settled", S::abort,
     "align timed out"},
    {"`mission.align_timeout_s` passed, the current's estimate still changing", S::abort,
     "align timed out: current not settled"},
};
constexpr MissionExit kDockExits[] = {
    {"the contact switch closed `mission.contact_frames` frames", S::docked, "contact"},
    {"the probe past `mission.vision_contact_depth_m` on the view `mission.contact_frames` frames",
     S::docked, "contact (vision)"},
    {"lateral error past `mission.dock_abort_lateral_m` for `mission.dock_abort_frames` steered "
     "frames",
     S::abort, "lateral error limit"},
    {"yaw error past `mission.dock_abort_yaw_rad` for `mission.dock_abort_frames` steered frames",
     S::abort, "yaw error limit"},
    {"the marker unseen `mission.lost_frames` frames outside the blind zone", S::abort,
     "marker lost"},
    {"a partial view longer than `mission.dock_partial_timeout_s`", S::abort,
     "partial view while docking"},
    {"blind in the blind zone longer than `mission.dock_blind_timeout_s`", S::abort,
     "no contact after blind push"},
    {"`mission.dock_timeout_s` passed", S::abort, "dock timed out"},
    {"the current's estimate at its limit or the thrusters saturated for "
     "`control.servo.disturbance.beyond_hold_s`",
     S::failed, "current beyond hold"},
    {"a failsafe trips during a re-seat (it backs out)", S::undock,
     "failsafe: backing out of the socket"},
};
constexpr MissionExit kDockedExits[] = {
    {"at once on the recharging mission (the first seat)", S::charging, "seated: charging"},
    {"at once on the recharging mission (a re-seat)", S::charging, "re-seated"},
};
constexpr MissionExit kAbortExits[] = {
    {"`mission.abort_backoff_s` of backing off passed", S::search, "backed off"},
    {"at once after a loss before the dock", S::search, "searching from here"},
    {"at once when the aborts pass `mission.max_retries`", S::failed, "retries exhausted"},
};
constexpr MissionExit kChargingExits[] = {
    {"the operator ends the charge", S::undock, "operator command"},
    {"the hold's force past `mission.recharge.overload_force_n` or its yaw past "
     "`mission.recharge.overload_yaw_rad` for their times, or the current's estimate beyond hold",
     S::undock, "current beyond what the hold resists"},
    {"the probe unseated for `mission.recharge.unseat_confirm_s`, re-seats left", S::dock,
     "probe unseated: re-seat"},
    {"the probe unseated, `mission.recharge.max_reseats` used (UNDOCK ends in the final ABORT)",
     S::undock, "probe unseated: re-seats exhausted"},
    {"state of charge `mission.recharge.soc_complete_fraction`", S::undock,
     "charge complete (state of charge)"},
    {"charge current under `mission.recharge.complete_current_a` past the taper", S::undock,
     "charge complete (current)"},
    {"charger current under `mission.recharge.no_current_a` for `mission.recharge.no_current_s`",
     S::undock, "charger reports no current"},
    {"`mission.recharge.charge_timeout_s` since the first seat", S::undock, "charge time limit"},
    {"a failsafe trips (it backs out)", S::undock, "failsafe: backing out of the socket"},
};
constexpr MissionExit kUndockExits[] = {
    {"the marker in view with the probe back at the stand-off, re-seats exhausted", S::abort,
     "undocked after the re-seats ran out"},
    {"the marker in view with the probe back at the stand-off", S::departed,
     "clear of the station, marker in view"},
    {"`mission.recharge.undock_timeout_s` passed", S::failed, "undock timed out"},
};

const std::array<MissionStateRow, kMissionStateCount> kTable = {{
    {S::search,
     "the mission starts; ABORT's back-off is over; a restart (operator START, failsafe recovered)",
     kSearchExits,
     "yaw moment `mission.search_yaw_moment_nm` (turned toward a marker being confirmed); no "
     "servo"},
    {S::approach, "SEARCH confirmed the marker", kApproachExits,
     "servo to the stand-off, turning only as far as keeps the marker within "
     "`mission.approach_view_bearing_rad`; unseen: hold"},
    {S::align, "APPROACH reached the stand-off", kAlignExits,
     "servo to the stand-off; unseen: hold"},
    {S::dock, "ALIGN held aligned; CHARGING's probe unseated (a re-seat)", kDockExits,
     "servo to a set-point moving in at `mission.dock_speed_mps` (on a full or attitude-aided "
     "view; it waits, at least `mission.dock_wait_backoff_m` behind the probe, while the full "
     "view puts the probe more than `mission.dock_wait_lateral_m` off the axis, its error "
     "low-passed over `mission.dock_wait_filter_s`); in the blind zone without one the push "
     "`mission.dock_blind_push_n` along the docked axis; a re-seat adds "
     "`mission.recharge.charge_push_n` and the seat trim"},
    {S::docked, "DOCK made contact", kDockedExits, "neutral (the docking mission ends here)"},
    {S::abort,
     "APPROACH, ALIGN or DOCK gave up (counted); UNDOCK after the re-seats ran out (the final "
     "ABORT, which ends the mission once backed off)",
     kAbortExits,
     "astern `mission.abort_backoff_force_n` (none after a loss before the dock); neutral once the "
     "final "
     "ABORT has backed off"},
    {S::failed,
     "SEARCH or UNDOCK timed out; aborts past `mission.max_retries`; APPROACH, ALIGN or DOCK "
     "found the current beyond hold",
     {},
     "neutral"},
    {S::charging, "DOCKED on the recharging mission", kChargingExits,
     "servo on lateral and yaw, the set-point following the probe; the push "
     "`mission.recharge.charge_push_n` along the docked axis plus the seat trim (rising while "
     "the probe slips out, `mission.recharge.seat_trim_rise_nps`, seen "
     "`mission.recharge.seat_slip_m` short of the socket's bottom or the contact lost); the axial "
     "trim DOCK kept, not integrated"},
    {S::undock, "CHARGING ends the charge; a failsafe at the station backs out", kUndockExits,
     "servo to a set-point moving out at `mission.recharge.undock_speed_mps` to the stand-off; "
     "unseen: "
     "the push `mission.recharge.undock_push_n` out along the docked axis"},
    {S::departed,
     "UNDOCK came clear of the station",
     {},
     "`mission.recharge.departed_action` hold: servo at the stand-off; else neutral"},
}};

std::string upper(const char* s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

}  // namespace

const std::array<MissionStateRow, kMissionStateCount>& mission_state_table() { return kTable; }

std::string mission_state_table_markdown() {
  std::string md = "| state | entered when | leaves when | outputs |\n|---|---|---|---|\n";
  for (const MissionStateRow& row : kTable) {
    md += "| " + upper(to_string(row.state)) + " | " + row.entered_when + " | ";
    if (row.exits.empty()) md += "end of the mission";
    for (std::size_t i = 0; i < row.exits.size(); ++i) {
      const MissionExit& x = row.exits[i];
      if (i > 0) md += "; ";
      md += std::string(x.when) + " → " + upper(to_string(x.to)) + " (\"" + x.reason + "\")";
    }
    md += std::string(" | ") + row.outputs + " |\n";
  }
  return md;
}

}  // namespace rovctl::control
