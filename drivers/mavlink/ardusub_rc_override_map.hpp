// The allocator's thruster fractions as RC_CHANNELS_OVERRIDE PWM (ArduSub's thrusters mode): each
// thruster on its own channel, passed by ArduSub straight to its ESC (SERVOn_FUNCTION = RCINn).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "drivers/mavlink/ardusub_params.hpp"
#include "drivers/mavlink/mavlink_messages.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::drivers {

class ArdusubRcOverrideMap {
 public:
  // Throws std::invalid_argument naming the key (thruster_bus.ardusub.rc_override...) for a
  // channel list that does not give every thruster of `layout` its own channel, or a PWM range
  // that is not min < neutral < max.
  ArdusubRcOverrideMap(const hal::ThrusterLayout& layout, const ArdusubRcOverrideParams& params);

  // Every thruster's channel at its PWM (neutral while `armed` is false, and for every thruster
  // when any fraction is not finite: one thruster's NaN would leave the others pushing an
  // unbalanced wrench); the channels no thruster uses carry MAVLink's "ignore" (UINT16_MAX on
  // 1-8, 0 on 9-18) so ArduSub leaves them as they are. No allocation.
  mavlink::RcChannelsOverride message(const hal::ThrusterCommand& command, bool armed) const;
  // The message with every thruster at neutral.
  mavlink::RcChannelsOverride neutral() const;
  // The PWM of one fraction in [-1, 1] (clamped), in the thruster's positive direction.
  std::uint16_t pwm_us(double fraction, bool reversed) const;

  std::size_t count() const { return count_; }
  // 0-based channel index of thruster i.
  std::size_t channel_index(std::size_t thruster) const { return channel_index_[thruster]; }

 private:
  std::size_t count_ = 0;
  std::array<std::size_t, hal::kMaxThrusters> channel_index_{};
  std::array<bool, hal::kMaxThrusters> reversed_{};
  ArdusubRcOverrideParams pwm_;
};

// MAVLink's "ignore this channel" value for 0-based channel index `i` (common.xml).
constexpr std::uint16_t rc_override_ignore(std::size_t i) { return i < 8 ? 0xFFFFU : 0U; }

}  // namespace rovctl::drivers
