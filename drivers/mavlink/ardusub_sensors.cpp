// ArduSub's MAVLink telemetry as the vehicle's sensor readings.
#include "drivers/mavlink/ardusub_sensors.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "drivers/mavlink/mavlink_messages.hpp"

namespace rovctl::drivers {

namespace {

constexpr double kGravityMps2 = 9.80665;

bool contains(std::string_view text, std::string_view word) {
  return text.find(word) != std::string_view::npos;
}

}  // namespace

ArdusubSensors::ArdusubSensors(const ArdusubSensorParams& params, const hal::Clock& clock)
    : params_(params), clock_(clock) {}

void ArdusubSensors::accept(const mavlink::Frame& frame) {
  const std::chrono::nanoseconds now = clock_.now();
  hal::SensorReadings& r = building_.readings;
  mavlink::AttitudeQuaternion att;
  mavlink::ScaledPressure2 press;
  mavlink::SysStatus sys;
  mavlink::StatusText text;
  if (mavlink::unpack(frame, att)) {
    // MAVLink's q is body FRD relative to NED, w first: the body's attitude in the world (NED).
    r.q_world_body = Eigen::Quaterniond(att.q_ned_body[0], att.q_ned_body[1], att.q_ned_body[2],
                                        att.q_ned_body[3]);
    r.omega_body_radps =
        Eigen::Vector3d(att.rollspeed_rad_s, att.pitchspeed_rad_s, att.yawspeed_rad_s);
    r.attitude_valid = true;
    building_.attitude_stamp = now;
  } else if (mavlink::unpack(frame, press)) {
    r.depth_m = (static_cast<double>(press.press_abs_hpa) - params_.surface_pressure_hpa) * 100.0 /
                (params_.water_density_kg_m3 * kGravityMps2);
    r.depth_valid = true;
    building_.depth_stamp = now;
  } else if (mavlink::unpack(frame, sys)) {
    // UINT16_MAX volts and -1 % mean ArduSub does not know.
    r.battery_valid = sys.battery_remaining_pct >= 0 && sys.voltage_battery_mv != 0xFFFF;
    r.soc_fraction = r.battery_valid ? sys.battery_remaining_pct / 100.0 : 0.0;
    r.battery_voltage_v = sys.voltage_battery_mv / 1000.0;
    building_.battery_stamp = now;
  } else if (mavlink::unpack(frame, text)) {
    // ArduSub's leak detector says "Leak Detected" (CRITICAL); it latches until reboot there too.
    if (!contains(mavlink::text_of(text.text), "Leak")) return;
    r.leak_valid = true;
    r.leak = true;
  } else {
    return;
  }
  r.stamp = now;
  slot_.back() = building_;
  slot_.publish();
}

bool ArdusubSensors::read(hal::SensorReadings& readings) {
  (void)slot_.take();
  const ArdusubSample* s = slot_.current();
  if (s == nullptr) return false;
  const std::chrono::nanoseconds now = clock_.now();
  const auto stale = std::chrono::milliseconds(params_.stale_ms);
  readings = s->readings;
  readings.attitude_age = now - s->attitude_stamp;
  readings.depth_age = now - s->depth_stamp;
  readings.battery_age = now - s->battery_stamp;
  readings.attitude_valid = readings.attitude_valid && now - s->attitude_stamp <= stale;
  readings.depth_valid = readings.depth_valid && now - s->depth_stamp <= stale;
  readings.battery_valid = readings.battery_valid && now - s->battery_stamp <= stale;
  return true;
}

}  // namespace rovctl::drivers
