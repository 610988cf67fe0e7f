// The fault table and how each fault is set up.
#include "app/tools/injected_fault.hpp"

#include <cstdlib>
#include <cstring>

namespace rovctl::app {
namespace {

constexpr InjectedFault kInjectedFaults[] = {
    {"camera_lost", "camera_lost", false, "the stereo camera device disappears"},
    {"camera_drop", "vision_lost", true, "every grab times out for camera_drop_for_s"},
    {"frozen_frames", "vision_frozen", true, "the same images delivered again, newly stamped"},
    {"stale_frames", "vision_stale", true, "frames arrive stale_ms late"},
    {"stamp_skew", "stereo_skew", true, "the right image stamped stamp_skew_ms early"},
    {"camera_black", "camera_dead", false, "the right camera's image is black"},
    {"bus_timeout", "bus_fault", false, "the thruster bus stops answering"},
    {"bus_slow", "bus_slow", true, "the thruster bus answers bus_latency_ms late"},
    {"disarm_unacked", "disarm_unacked", false,
     "the sensors are lost (a disarm) and the bus does not acknowledge the disarm"},
    {"sensor_lost", "sensor_lost", false, "the navigation sensors stop answering"},
    {"sensor_nan", "sensor_nan", false, "depth and attitude read NaN, flagged valid"},
    {"sensor_implausible", "sensor_implausible", false, "depth reads -1000 m, flagged valid"},
    {"tilt", "attitude_limit", true, "the attitude reads tilt_rad of extra roll"},
    {"cpu_stall", "cpu_overrun", true, "each grab stalls the tick by cpu_stall_ms"},
    {"mission_time", "mission_time", false, "control.failsafe.max_mission_time_s set to t"},
    {"search_time", "search_time", false,
     "the marker hidden from the start, mission.search_timeout_s set to t"},
    {nullptr, nullptr, false, nullptr},
};

}  // namespace

const InjectedFault* injected_faults() { return kInjectedFaults; }

std::string injected_fault_names_text() {
  std::string text;
  for (const InjectedFault* f = kInjectedFaults; f->name != nullptr; ++f) {
    text += (text.empty() ? "" : ", ") + std::string(f->name);
  }
  return text;
}

const InjectedFault* find_injected_fault(const std::string& name) {
  for (const InjectedFault* f = kInjectedFaults; f->name != nullptr; ++f) {
    if (name == f->name) return f;
  }
  return nullptr;
}

bool parse_fault_spec(const std::string& spec, double default_at_s, const InjectedFault*& fault,
                      double& at_s, std::string& error) {
  const auto at = spec.find('@');
  const std::string name = spec.substr(0, at);
  fault = find_injected_fault(name);
  if (fault == nullptr) {
    error = "unknown fault '" + name + "' (one of " + injected_fault_names_text() + ")";
    return false;
  }
  at_s = default_at_s;
  if (at != std::string::npos) {
    const std::string time = spec.substr(at + 1);
    char* end = nullptr;
    at_s = std::strtod(time.c_str(), &end);
    if (time.empty() || *end != '\0' || !(at_s >= 0.0 && at_s <= 1e6)) {
      error = "fault '" + spec + "': the time after @ must be seconds in [0, 1e6]";
      return false;
    }
  }
  return true;
}

void apply_injected_fault(const InjectedFault& f, double at_s, AppConfig& config) {
  hal::mock::FaultInjection& x = config.sim.faults;
  const std::string name = f.name;
  if (name == "camera_lost") x.camera_lost_at_s = at_s;
  if (name == "camera_drop") x.camera_drop_at_s = at_s;
  if (name == "frozen_frames") x.frozen_frames_at_s = at_s;
  if (name == "stale_frames") x.stale_frames_at_s = at_s;
  if (name == "stamp_skew") x.stamp_skew_at_s = at_s;
  if (name == "camera_black") x.camera_black_at_s = at_s;
  if (name == "bus_timeout") x.bus_timeout_at_s = at_s;
  if (name == "bus_slow") x.bus_slow_at_s = at_s;
  if (name == "disarm_unacked") {
    x.sensor_lost_at_s = at_s;
    x.disarm_ignored_at_s = at_s;
  }
  if (name == "sensor_lost") x.sensor_lost_at_s = at_s;
  if (name == "sensor_nan") x.sensor_nan_at_s = at_s;
  if (name == "sensor_implausible") x.sensor_implausible_at_s = at_s;
  if (name == "tilt") x.tilt_at_s = at_s;
  if (name == "cpu_stall") x.cpu_stall_at_s = at_s;
  if (name == "mission_time") config.control.failsafe.max_mission_time_s = at_s;
  if (name == "search_time") {
    x.marker_hidden_at_s = 0.0;
    config.mission.search_timeout_s = at_s;
  }
}

}  // namespace rovctl::app
