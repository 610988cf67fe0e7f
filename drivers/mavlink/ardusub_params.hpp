// Settings of ArduSub as thruster bus (`thruster_bus.ardusub`: the MAVLink link, the ids ArduSub
// expects, the map from newtons to MANUAL_CONTROL's axes) and as sensors (`sensors.ardusub`).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

// Force or torque ArduSub's mixer produces at full stick (axis +-1000, z 0/1000) with the pilot
// gain at 1; the defaults are the BlueROV2 Heavy's eight T200s at their mean of forward and
// reverse thrust (16 V), through ArduSub's vectored-6DOF mixer.
struct ArdusubAxisScale {
  double surge_full_n = 130.0;
  double sway_full_n = 130.0;
  double heave_full_n = 183.0;
  double yaw_full_nm = 34.6;
};

// One thruster's RC channel in thrusters mode: ArduSub passes RCIN<channel> straight to the
// output whose SERVOn_FUNCTION is RCIN<channel>, so its motor direction setting no longer applies.
struct ArdusubRcChannel {
  std::string thruster;   // a name from vehicle.thrusters
  int channel = 0;        // RC_CHANNELS_OVERRIDE channel, 1..18
  bool reversed = false;  // the ESC turns the thruster's negative direction above neutral PWM
};

// Thrusters mode: rovctl's fractions as PWM in RC_CHANNELS_OVERRIDE.
struct ArdusubRcOverrideParams {
  std::vector<ArdusubRcChannel> channels;  // empty: thruster i (layout order) on channel i + 1
  int pwm_min_us = 1100;                   // full reverse
  int pwm_neutral_us = 1500;               // stopped
  int pwm_max_us = 1900;                   // full forward
};

// rovctl's own status to the ground station (Cockpit, QGroundControl) on ArduSub's link.
struct GcsStatusParams {
  bool enabled = true;
  // A component of the vehicle's system: ground stations show a vehicle's STATUSTEXT by its
  // system id, and 191 is MAV_COMP_ID_ONBOARD_COMPUTER.
  int system_id = 1;
  int component_id = 191;
  int heartbeat_period_ms = 1000;  // HEARTBEAT as MAV_TYPE_ONBOARD_CONTROLLER
  int values_period_ms = 250;  // the NAMED_VALUE_FLOATs (state, fitness, distance, lateral, not ok)
};

struct ArdusubParams {
  std::string link = "udpin:0.0.0.0:14660";  // the BlueOS MAVLink endpoint pointed at rovctl
  std::string mode = "wrench";   // wrench: body wrench as MANUAL_CONTROL; thrusters: RC override
  int gcs_system_id = 255;       // ArduSub's SYSID_MYGCS (MAV_GCS_SYSID on 4.7)
  int gcs_component_id = 190;    // MAV_COMP_ID_MISSIONPLANNER
  int vehicle_system_id = 1;     // ArduSub's SYSID_THISMAV
  int vehicle_component_id = 1;  // MAV_COMP_ID_AUTOPILOT1
  std::string flight_mode = "stabilize";  // the mode ArduSub must be in to arm and to stay
  double pilot_gain = 0.5;                // ArduSub's joystick gain (JS_GAIN_DEFAULT)
  ArdusubAxisScale scale;
  ArdusubRcOverrideParams rc_override;
  GcsStatusParams gcs_status;
  int link_timeout_ms = 1500;      // no ArduSub HEARTBEAT (1 Hz) for this long: link lost
  int stream_timeout_ms = 200;     // no ATTITUDE_QUATERNION (asked at 20 Hz) this long: silent
  int heartbeat_period_ms = 1000;  // our own HEARTBEAT as the GCS
  int ack_timeout_ms = 300;        // wait for COMMAND_ACK of arm/disarm (on the I/O thread)
};

// ArduSub's sensors streamed back over the bus's link (config section `sensors.ardusub`).
struct ArdusubSensorParams {
  int stream_interval_ms = 50;  // MAV_CMD_SET_MESSAGE_INTERVAL for attitude, pressure, battery
  int stale_ms = 300;           // a reading older than this is reported invalid
  double surface_pressure_hpa = 1013.25;  // absolute pressure at the surface (depth 0)
  double water_density_kg_m3 = 1025.0;    // sea water; 997 in fresh water
};

// ArduSub's custom_mode number of a `flight_mode` name; -1 for an unknown name.
int ardusub_custom_mode(const std::string& flight_mode);

void describe(hal::ParamVisitor& v, ArdusubAxisScale& p);
void describe(hal::ParamVisitor& v, ArdusubRcOverrideParams& p);
void describe(hal::ParamVisitor& v, GcsStatusParams& p);
void describe(hal::ParamVisitor& v, ArdusubParams& p);
void describe(hal::ParamVisitor& v, ArdusubSensorParams& p);

}  // namespace rovctl::drivers
