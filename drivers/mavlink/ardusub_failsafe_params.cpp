// The rules that judge ArduSub's pilot-input and RC-override failsafes for rovctl.
#include "drivers/mavlink/ardusub_failsafe_params.hpp"
#include "hal/primitives/number_format.hpp"

#include <cmath>

namespace rovctl::drivers {

namespace {

ArdusubFailsafeVerdict pilot_input(std::optional<float> v) {
  ArdusubFailsafeVerdict r{"FS_PILOT_INPUT", v, false, ""};
  if (!v) return r;
  if (*v == 2.0F) {
    r.safe = true;
    r.reason = "2: neutral, then disarm when rovctl goes silent";
  } else if (*v == 1.0F) {
    r.safe = true;
    r.reason = "1: neutral (stays armed) when rovctl goes silent";
  } else if (*v == 0.0F) {
    r.reason = "0: disabled, ArduSub keeps the last MANUAL_CONTROL when rovctl goes silent; set 2";
  } else {
    r.reason = hal::format_number(*v) + ": not an ArduSub value (0, 1, 2); set 2";
  }
  return r;
}

ArdusubFailsafeVerdict pilot_timeout(const ArdusubParams& p, std::optional<float> v) {
  ArdusubFailsafeVerdict r{"FS_PILOT_TIMEOUT", v, false, ""};
  if (!v) return r;
  // In float, as ArduSub stores it: 0.3 s read back is not above a 300 ms wait.
  const float ack_s = static_cast<float>(p.ack_timeout_ms) / 1000.0F;
  if (!std::isfinite(*v) || *v <= ack_s) {
    r.reason = hal::format_number(*v) + " s: not above thruster_bus.ardusub.ack_timeout_ms (" +
               hal::format_number(ack_s) + " s), the wait for an arm ack without MANUAL_CONTROL";
  } else if (*v > kMaxArdusubSilenceS) {
    r.reason = hal::format_number(*v) +
               " s: ArduSub obeys a silent rovctl's last command that long; at most " +
               hal::format_number(static_cast<float>(kMaxArdusubSilenceS)) + " s";
  } else {
    r.safe = true;
    r.reason = hal::format_number(*v) + " s of silence before ArduSub's pilot-input failsafe";
  }
  return r;
}

ArdusubFailsafeVerdict override_time(const ArdusubParams& p, std::optional<float> v) {
  ArdusubFailsafeVerdict r{"RC_OVERRIDE_TIME", v, false, ""};
  if (!v) return r;
  if (p.mode != "thrusters") {
    r.safe = true;
    r.reason = hal::format_number(*v) + " s: not used by " + p.mode + " mode (MANUAL_CONTROL)";
  } else if (*v < 0.0F) {
    r.reason =
        hal::format_number(*v) + ": overrides never time out, ArduSub holds a silent rovctl's PWM";
  } else if (*v == 0.0F) {
    r.reason = "0: RC overrides disabled, rovctl cannot drive the thrusters";
  } else if (*v > kMaxArdusubSilenceS) {
    r.reason = hal::format_number(*v) +
               " s: ArduSub holds a silent rovctl's PWM that long; at most " +
               hal::format_number(static_cast<float>(kMaxArdusubSilenceS)) + " s";
  } else {
    r.safe = true;
    r.reason = hal::format_number(*v) + " s until ArduSub drops rovctl's RC overrides";
  }
  return r;
}

}  // namespace

std::vector<ArdusubFailsafeVerdict> judge_ardusub_failsafes(
    const ArdusubParams& params, const std::array<std::optional<float>, 3>& values) {
  std::vector<ArdusubFailsafeVerdict> out = {
      pilot_input(values[0]), pilot_timeout(params, values[1]), override_time(params, values[2])};
  for (ArdusubFailsafeVerdict& v : out) {
    if (!v.value) v.reason = "no PARAM_VALUE from ArduSub";
  }
  return out;
}

}  // namespace rovctl::drivers
