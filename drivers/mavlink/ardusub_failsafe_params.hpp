// ArduSub's own failsafes that stop the vehicle when rovctl goes silent (FS_PILOT_INPUT,
// FS_PILOT_TIMEOUT, RC_OVERRIDE_TIME) and whether their values are safe for rovctl.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "drivers/mavlink/ardusub_params.hpp"

namespace rovctl::drivers {

// Read with PARAM_REQUEST_READ by `rovctl check`, in this order.
inline constexpr std::array<const char*, 3> kArdusubFailsafeParams = {
    "FS_PILOT_INPUT", "FS_PILOT_TIMEOUT", "RC_OVERRIDE_TIME"};

// Beyond this, ArduSub keeps obeying the last command of a dead rovctl for too long: 1 s at the
// docking speeds (<= 0.3 m/s) is a third of a metre, about the stand-off distance.
inline constexpr double kMaxArdusubSilenceS = 1.0;

struct ArdusubFailsafeVerdict {
  std::string name;
  std::optional<float> value;  // none: ArduSub did not answer
  bool safe = false;
  std::string reason;  // what the value means for rovctl
};

// One verdict per kArdusubFailsafeParams entry; `values` in the same order. The rules:
//  FS_PILOT_INPUT   1 (neutral) or 2 (neutral, disarm): 0 leaves ArduSub obeying the last input.
//  FS_PILOT_TIMEOUT above ack_timeout_ms (rovctl sends no MANUAL_CONTROL while it waits for an
//                   ARM_DISARM ack, and the failsafe would disarm it just armed) and at most
//                   kMaxArdusubSilenceS.
//  RC_OVERRIDE_TIME thrusters mode (RC_CHANNELS_OVERRIDE): in (0, kMaxArdusubSilenceS]; 0
//                   disables overrides, -1 holds the last PWM forever. Not used in wrench mode.
std::vector<ArdusubFailsafeVerdict> judge_ardusub_failsafes(
    const ArdusubParams& params, const std::array<std::optional<float>, 3>& values);

}  // namespace rovctl::drivers
