// Thruster health: the expected rpm from the lagged command, the symptom tests and their
// persistence.
#include "control/thruster_health.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::control {

const char* to_string(ThrusterFailure f) {
  switch (f) {
    case ThrusterFailure::none:
      return "none";
    case ThrusterFailure::fault_flag:
      return "ESC fault flag";
    case ThrusterFailure::dead:
      return "dead (no rpm)";
    case ThrusterFailure::weak:
      return "weak (rpm low)";
    case ThrusterFailure::stuck:
      return "stuck (rpm not following)";
  }
  return "?";
}

ThrusterHealth::ThrusterHealth(const ThrusterEffectiveness& effectiveness,
                               const ThrusterHealthParams& params)
    : effectiveness_(effectiveness), p_(params) {
  failure_.fill(ThrusterFailure::none);
  candidate_.fill(ThrusterFailure::none);
}

double ThrusterHealth::expected_rpm(std::size_t i) const {
  const double f = expected_thrust_n_[i];
  const double limit = effectiveness_.limit_n(i, f);
  return std::copysign(p_.full_thrust_rpm * std::sqrt(std::abs(f) / limit), f);
}

ThrusterFailure ThrusterHealth::symptom(std::size_t i, double rpm, std::uint16_t flags) const {
  if (flags != 0) return ThrusterFailure::fault_flag;
  if (!std::isfinite(rpm)) return ThrusterFailure::none;
  const double expected = expected_rpm(i);
  if (std::abs(expected) < p_.min_expected_rpm) {
    return std::abs(rpm) > p_.stuck_idle_rpm ? ThrusterFailure::stuck : ThrusterFailure::none;
  }
  const double ratio = rpm / expected;  // negative: turning the wrong way
  if (ratio < -p_.dead_rpm_ratio || ratio > p_.overspeed_rpm_ratio) return ThrusterFailure::stuck;
  if (ratio < p_.dead_rpm_ratio) return ThrusterFailure::dead;
  if (ratio < p_.weak_rpm_ratio) return ThrusterFailure::weak;
  return ThrusterFailure::none;
}

std::size_t ThrusterHealth::update(const hal::ThrusterTelemetry& telemetry,
                                   const hal::ThrusterCommand& last_command, double dt_s) {
  const std::size_t n = effectiveness_.count();
  const double alpha =
      p_.time_constant_s > 0.0 ? 1.0 - std::exp(-std::max(0.0, dt_s) / p_.time_constant_s) : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto ch = static_cast<std::size_t>(effectiveness_.channel(i));
    const double c = ch < last_command.count ? last_command.thrust_fraction[ch] : 0.0;
    const double target = std::isfinite(c) ? effectiveness_.thrust_for_command(i, c) : 0.0;
    expected_thrust_n_[i] += alpha * (target - expected_thrust_n_[i]);
  }
  if (!p_.enabled || !telemetry.valid) return 0;
  std::size_t newly_failed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto ch = static_cast<std::size_t>(effectiveness_.channel(i));
    if (failed(i) || ch >= telemetry.count) continue;
    const ThrusterFailure s = symptom(i, telemetry.speed_rpm[ch], telemetry.fault_flags[ch]);
    // A symptom counts while it lasts; dead, weak and stuck are one mismatch (a thruster slowing
    // to a stop passes through weak), reported as the latest.
    const bool same = s != ThrusterFailure::none &&
                      (s == candidate_[i] || (s != ThrusterFailure::fault_flag &&
                                              candidate_[i] != ThrusterFailure::fault_flag &&
                                              candidate_[i] != ThrusterFailure::none));
    count_[i] = s == ThrusterFailure::none ? 0 : same ? count_[i] + 1 : 1;
    candidate_[i] = s;
    const int needed = s == ThrusterFailure::fault_flag ? p_.fault_flag_ticks : p_.mismatch_ticks;
    if (s != ThrusterFailure::none && count_[i] >= needed) {
      failure_[i] = s;
      ++newly_failed;
    }
  }
  return newly_failed;
}

}  // namespace rovctl::control
