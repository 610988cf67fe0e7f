// Names of the failsafe causes, for the logs and the policy table's keys.
#include "control/failsafe_cause.hpp"

#include <array>

namespace rovctl::control {
namespace {

struct CauseNames {
  const char* text;
  const char* key;
};

constexpr std::array<CauseNames, kFailsafeCauseCount> kNames{{
    {"none", "none"},
    {"camera lost", "camera_lost"},
    {"thruster bus fault", "bus_fault"},
    {"estimate not finite", "estimate_not_finite"},
    {"wrench not finite", "wrench_not_finite"},
    {"mission failed", "mission_failed"},
    {"mission time limit", "mission_time"},
    {"vision lost", "vision_lost"},
    {"vision stale", "vision_stale"},
    {"vision frozen", "vision_frozen"},
    {"stereo stamp skew", "stereo_skew"},
    {"camera dead", "camera_dead"},
    {"thruster bus slow", "bus_slow"},
    {"sensors lost", "sensor_lost"},
    {"sensor reading not finite", "sensor_nan"},
    {"sensor reading implausible", "sensor_implausible"},
    {"attitude limit", "attitude_limit"},
    {"search time limit", "search_time"},
    {"cpu overrun streak", "cpu_overrun"},
    {"thruster fault", "thruster_fault"},
    {"leak detected", "leak"},
    {"battery low", "battery_low"},
    {"disarm not acknowledged", "disarm_unacked"},
}};

}  // namespace

const char* to_string(FailsafeCause c) {
  const auto i = static_cast<std::size_t>(c);
  return i < kNames.size() ? kNames[i].text : "?";
}

const char* cause_key(FailsafeCause c) {
  const auto i = static_cast<std::size_t>(c);
  return i < kNames.size() ? kNames[i].key : "?";
}

bool cause_from_key(std::string_view key, FailsafeCause& cause) {
  for (std::size_t i = 0; i < kNames.size(); ++i) {
    if (key == kNames[i].key) {
      cause = static_cast<FailsafeCause>(i);
      return true;
    }
  }
  return false;
}

}  // namespace rovctl::control
