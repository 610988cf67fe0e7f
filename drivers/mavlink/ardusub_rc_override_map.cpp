// Fractions -> PWM per RC channel for ArduSub's thrusters mode.
#include "drivers/mavlink/ardusub_rc_override_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rovctl::drivers {

namespace {

constexpr const char* kKey = "thruster_bus.ardusub.rc_override";
constexpr std::size_t kChannels = 18;     // in the message
constexpr int kPassthroughChannels = 16;  // ArduPilot's SERVOn_FUNCTION RCIN1..RCIN16

}  // namespace

ArdusubRcOverrideMap::ArdusubRcOverrideMap(const hal::ThrusterLayout& layout,
                                           const ArdusubRcOverrideParams& params)
    : count_(layout.thrusters.size()), pwm_(params) {
  pwm_.channels.clear();  // the map keeps only the PWM range; channels live in channel_index_
  if (count_ > hal::kMaxThrusters) {
    throw std::invalid_argument(std::string(kKey) + ": the layout has more than 8 thrusters");
  }
  if (!(params.pwm_min_us < params.pwm_neutral_us && params.pwm_neutral_us < params.pwm_max_us)) {
    throw std::invalid_argument(std::string(kKey) +
                                ".pwm_neutral_us: must lie between pwm_min_us and pwm_max_us");
  }
  if (params.channels.empty()) {
    for (std::size_t i = 0; i < count_; ++i) channel_index_[i] = i;
    return;
  }
  if (params.channels.size() != count_) {
    throw std::invalid_argument(
        std::string(kKey) + ".channels: " + std::to_string(params.channels.size()) + " given for " +
        std::to_string(count_) + " thrusters (all or none)");
  }
  std::array<bool, hal::kMaxThrusters> mapped{};
  std::array<bool, kChannels> used{};
  for (const ArdusubRcChannel& c : params.channels) {
    const auto it = std::find_if(layout.thrusters.begin(), layout.thrusters.end(),
                                 [&c](const hal::Thruster& t) { return t.name == c.thruster; });
    if (it == layout.thrusters.end()) {
      throw std::invalid_argument(std::string(kKey) + ".channels: no thruster '" + c.thruster +
                                  "' in vehicle.thrusters");
    }
    const auto i = static_cast<std::size_t>(it - layout.thrusters.begin());
    if (c.channel < 1 || c.channel > kPassthroughChannels) {
      throw std::invalid_argument(std::string(kKey) + ".channels: channel " +
                                  std::to_string(c.channel) + " outside 1..16 (RCIN1..16)");
    }
    const auto ch = static_cast<std::size_t>(c.channel - 1);
    if (mapped[i] || used[ch]) {
      throw std::invalid_argument(std::string(kKey) + ".channels: thruster '" + c.thruster +
                                  "' or channel " + std::to_string(c.channel) + " given twice");
    }
    mapped[i] = true;
    used[ch] = true;
    channel_index_[i] = ch;
    reversed_[i] = c.reversed;
  }
}

std::uint16_t ArdusubRcOverrideMap::pwm_us(double fraction, bool reversed) const {
  const double f = std::clamp(reversed ? -fraction : fraction, -1.0, 1.0);
  const double span =
      f >= 0.0 ? pwm_.pwm_max_us - pwm_.pwm_neutral_us : pwm_.pwm_neutral_us - pwm_.pwm_min_us;
  return static_cast<std::uint16_t>(std::lround(pwm_.pwm_neutral_us + f * span));
}

mavlink::RcChannelsOverride ArdusubRcOverrideMap::message(const hal::ThrusterCommand& command,
                                                          bool armed) const {
  mavlink::RcChannelsOverride m = neutral();
  if (!armed) return m;
  const std::size_t n = std::min(count_, command.count);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(command.thrust_fraction[i])) return neutral();
  }
  for (std::size_t i = 0; i < n; ++i) {
    m.channels_us[channel_index_[i]] = pwm_us(command.thrust_fraction[i], reversed_[i]);
  }
  return m;
}

mavlink::RcChannelsOverride ArdusubRcOverrideMap::neutral() const {
  mavlink::RcChannelsOverride m;
  for (std::size_t i = 0; i < m.channels_us.size(); ++i) m.channels_us[i] = rc_override_ignore(i);
  const auto neutral_us = static_cast<std::uint16_t>(pwm_.pwm_neutral_us);
  for (std::size_t i = 0; i < count_; ++i) m.channels_us[channel_index_[i]] = neutral_us;
  return m;
}

}  // namespace rovctl::drivers
