// Parameter declarations of the ArduSub thruster bus.
#include "drivers/mavlink/ardusub_params.hpp"

namespace rovctl::drivers {

int ardusub_custom_mode(const std::string& flight_mode) {
  // ArduSub's mode numbers (ArduSub/mode.h); only the modes where MANUAL_CONTROL is pilot input.
  if (flight_mode == "stabilize") return 0;
  if (flight_mode == "alt_hold") return 2;
  if (flight_mode == "manual") return 19;
  return -1;
}

void describe(hal::ParamVisitor& v, ArdusubAxisScale& p) {
  v.param("surge_full_n", p.surge_full_n,
          {"N", 1.0, 2000.0, "forward force at MANUAL_CONTROL x = 1000 with pilot gain 1"});
  v.param("sway_full_n", p.sway_full_n,
          {"N", 1.0, 2000.0, "starboard force at MANUAL_CONTROL y = 1000 with pilot gain 1"});
  v.param("heave_full_n", p.heave_full_n,
          {"N", 1.0, 2000.0, "upward force at MANUAL_CONTROL z = 1000 with pilot gain 1"});
  v.param("yaw_full_nm", p.yaw_full_nm,
          {"N*m", 0.1, 1000.0, "clockwise (from above) torque at MANUAL_CONTROL r = 1000, gain 1"});
}

void describe(hal::ParamVisitor& v, ArdusubRcOverrideParams& p) {
  hal::param_list(
      v, "channels", "RC channel of each thruster (all or none; none: thruster i on channel i + 1)",
      p.channels, 0, 8, [](hal::ParamVisitor& e, ArdusubRcChannel& c) {
        e.param("thruster", c.thruster, "thruster name from vehicle.thrusters", {}, true);
        e.param("channel", c.channel,
                {"-", 1, 16,
                 "RC_CHANNELS_OVERRIDE channel; its output needs SERVOn_FUNCTION = "
                 "RCIN<channel> (50 + channel)",
                 true});
        e.param("reversed", c.reversed,
                "the ESC turns the thruster's negative direction above neutral PWM");
      });
  v.param("pwm_min_us", p.pwm_min_us, {"us", 1000, 1500, "PWM at full reverse thrust"});
  v.param("pwm_neutral_us", p.pwm_neutral_us, {"us", 1400, 1600, "PWM at which the ESC stops"});
  v.param("pwm_max_us", p.pwm_max_us, {"us", 1500, 2000, "PWM at full forward thrust"});
}

void describe(hal::ParamVisitor& v, GcsStatusParams& p) {
  v.param("enabled", p.enabled,
          "send rovctl's HEARTBEAT, STATUSTEXT and NAMED_VALUE_FLOAT to the ground station");
  v.param("system_id", p.system_id,
          {"-", 1, 255,
           "system id of the status; the vehicle's (SYSID_THISMAV) so ground "
           "stations show its STATUSTEXT with the vehicle's"});
  v.param("component_id", p.component_id,
          {"-", 1, 255, "component id of the status (191: MAV_COMP_ID_ONBOARD_COMPUTER)"});
  v.param("heartbeat_period_ms", p.heartbeat_period_ms,
          {"ms", 100, 5000, "period of the status HEARTBEAT (MAV_TYPE_ONBOARD_CONTROLLER)"});
  v.param(
      "values_period_ms", p.values_period_ms,
      {"ms", 50, 5000,
       "period of the NAMED_VALUE_FLOATs rov_state, rov_fit, rov_dist_m, rov_lat_m, rov_notok"});
}

void describe(hal::ParamVisitor& v, ArdusubParams& p) {
  v.param("link", p.link,
          "MAVLink endpoint: udpin:ADDR:PORT listens (a BlueOS endpoint sending to us), "
          "udpout:ADDR:PORT sends to ArduSub, serial:DEVICE:BAUD is ArduSub's serial port "
          "wired to this computer (8N1, no flow control)");
  v.param("mode", p.mode,
          "wrench: the servo's body wrench as MANUAL_CONTROL x, y, z, r (ArduSub allocates and "
          "levels); thrusters: rovctl's allocation as PWM in RC_CHANNELS_OVERRIDE (outputs set "
          "to RC passthrough, ArduSub's mixer and stabilise bypassed)",
          {"wrench", "thrusters"});
  v.param("gcs_system_id", p.gcs_system_id,
          {"-", 1, 255, "system id rovctl sends as; ArduSub takes control only from SYSID_MYGCS"});
  v.param("gcs_component_id", p.gcs_component_id,
          {"-", 0, 255, "component id rovctl sends as (190: MAV_COMP_ID_MISSIONPLANNER)"});
  v.param("vehicle_system_id", p.vehicle_system_id,
          {"-", 1, 255, "ArduSub's SYSID_THISMAV: MANUAL_CONTROL's target; others are ignored"});
  v.param("vehicle_component_id", p.vehicle_component_id,
          {"-", 0, 255, "ArduSub's component id (1: MAV_COMP_ID_AUTOPILOT1)"});
  v.param("flight_mode", p.flight_mode,
          "ArduSub mode rovctl sets (DO_SET_MODE) before it arms and that must stay while armed; "
          "another mode while armed is a bus fault",
          {"stabilize", "alt_hold", "manual"});
  v.param("pilot_gain", p.pilot_gain,
          {"-", 0.1, 1.0, "ArduSub's joystick gain (JS_GAIN_DEFAULT), scales every axis"});
  v.section("scale", "force and torque at full stick, pilot gain 1 (wrench mode)",
            [&p](hal::ParamVisitor& s) { describe(s, p.scale); });
  v.section("rc_override", "thruster PWM channels and range (thrusters mode)",
            [&p](hal::ParamVisitor& s) { describe(s, p.rc_override); });
  v.section("gcs_status", "rovctl's status to the ground station on the same link",
            [&p](hal::ParamVisitor& s) { describe(s, p.gcs_status); });
  v.param("link_timeout_ms", p.link_timeout_ms,
          {"ms", 1100, 30000,
           "no ArduSub HEARTBEAT (sent at 1 Hz) for this long is link lost: a bus fault; keep it "
           "under ArduSub's FS_PILOT_TIMEOUT"});
  v.param("stream_timeout_ms", p.stream_timeout_ms,
          {"ms", 40, 5000,
           "with sensors.backend ardusub: no ATTITUDE_QUATERNION (the stream rovctl asks for at "
           "sensors.ardusub.stream_interval_ms) for this long is ArduSub silent: a bus fault, "
           "neutral and the failsafe; a few stream intervals"});
  v.param("heartbeat_period_ms", p.heartbeat_period_ms,
          {"ms", 100, 5000, "period of rovctl's own HEARTBEAT as the ground station"});
  v.param("ack_timeout_ms", p.ack_timeout_ms,
          {"ms", 10, 5000,
           "wait for ArduSub's COMMAND_ACK of arm or disarm, and for its HEARTBEAT to show the "
           "flight_mode asked with DO_SET_MODE, on the bus's I/O thread; below "
           "thruster_bus.timing.close_timeout_ms"});
}

void describe(hal::ParamVisitor& v, ArdusubSensorParams& p) {
  v.param("stream_interval_ms", p.stream_interval_ms,
          {"ms", 10, 1000,
           "interval requested (MAV_CMD_SET_MESSAGE_INTERVAL) for ATTITUDE_QUATERNION, "
           "SCALED_PRESSURE2 and SYS_STATUS"});
  v.param("stale_ms", p.stale_ms,
          {"ms", 20, 5000, "a reading older than this is invalid (sensor failsafes then apply)"});
  v.param("surface_pressure_hpa", p.surface_pressure_hpa,
          {"hPa", 800.0, 1100.0, "absolute pressure at the surface, where depth is 0"});
  v.param("water_density_kg_m3", p.water_density_kg_m3,
          {"kg/m^3", 990.0, 1050.0, "water density for depth from pressure (997 fresh, 1025 sea)"});
}

}  // namespace rovctl::drivers
