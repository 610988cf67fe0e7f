// Thrusters mode's PWM map: known fractions to known channel values, the "ignore" value on unused
// channels, NaN and disarmed to neutral, and the channel map's checks.
#include "drivers/mavlink/ardusub_rc_override_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rovctl::drivers {
namespace {

hal::ThrusterCommand fractions(std::initializer_list<double> f) {
  hal::ThrusterCommand c;
  for (const double x : f) c.thrust_fraction[c.count++] = x;
  return c;
}

TEST(ArdusubRcOverrideMap, DefaultMapPutsThrusterIOnChannelIPlusOne) {
  const ArdusubRcOverrideMap map(hal::ThrusterLayout::bluerov2_heavy(), ArdusubRcOverrideParams{});
  const mavlink::RcChannelsOverride m =
      map.message(fractions({1.0, -1.0, 0.5, -0.5, 0.0, 0.25, -0.25, 2.0}), true);
  EXPECT_EQ(m.channels_us[0], 1900);
  EXPECT_EQ(m.channels_us[1], 1100);
  EXPECT_EQ(m.channels_us[2], 1700);
  EXPECT_EQ(m.channels_us[3], 1300);
  EXPECT_EQ(m.channels_us[4], 1500);
  EXPECT_EQ(m.channels_us[5], 1600);
  EXPECT_EQ(m.channels_us[6], 1400);
  EXPECT_EQ(m.channels_us[7], 1900);                                         // clamped to full
  for (std::size_t i = 8; i < 18; ++i) EXPECT_EQ(m.channels_us[i], 0) << i;  // 9-18: ignore
}

TEST(ArdusubRcOverrideMap, ConfiguredChannelsReversalAndRange) {
  ArdusubRcOverrideParams p;
  p.pwm_min_us = 1200;
  p.pwm_neutral_us = 1520;
  p.pwm_max_us = 1800;
  const char* names[] = {"t1_front_right",     "t2_front_left",       "t3_rear_right",
                         "t4_rear_left",       "t5_vert_front_right", "t6_vert_front_left",
                         "t7_vert_rear_right", "t8_vert_rear_left"};
  for (int i = 0; i < 8; ++i) p.channels.push_back({names[i], 9 + i, i == 1});
  const ArdusubRcOverrideMap map(hal::ThrusterLayout::bluerov2_heavy(), p);
  const mavlink::RcChannelsOverride m =
      map.message(fractions({0.5, 0.5, -0.5, 0.0, 0.0, 0.0, 0.0, 0.0}), true);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(m.channels_us[i], 0xFFFF) << i;  // 1-8: ignore
  EXPECT_EQ(m.channels_us[8], 1660);                                             // 1520 + 0.5 * 280
  EXPECT_EQ(m.channels_us[9], 1360);   // reversed: 1520 - 0.5 * 320
  EXPECT_EQ(m.channels_us[10], 1360);  // 1520 - 0.5 * 320
  EXPECT_EQ(m.channels_us[11], 1520);
}

TEST(ArdusubRcOverrideMap, DisarmedOrAnyNanIsNeutralOnEveryThruster) {
  const ArdusubRcOverrideMap map(hal::ThrusterLayout::bluerov2_heavy(), ArdusubRcOverrideParams{});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto check_neutral = [](const mavlink::RcChannelsOverride& m) {
    for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(m.channels_us[i], 1500) << i;
  };
  check_neutral(map.message(fractions({0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9}), false));
  check_neutral(map.message(fractions({0.9, nan, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9}), true));
  check_neutral(map.message(fractions({0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, INFINITY}), true));
  check_neutral(map.neutral());
}

TEST(ArdusubRcOverrideMap, RejectsIncompleteUnknownOrDuplicateChannels) {
  const hal::ThrusterLayout layout = hal::ThrusterLayout::bluerov2_heavy();
  ArdusubRcOverrideParams p;
  p.channels = {{"t1_front_right", 1, false}};
  EXPECT_THROW(ArdusubRcOverrideMap(layout, p), std::invalid_argument);  // 1 of 8
  p.channels.clear();
  for (int i = 0; i < 8; ++i) p.channels.push_back({layout.thrusters[i].name, 1 + i, false});
  EXPECT_NO_THROW(ArdusubRcOverrideMap(layout, p));
  p.channels[7].channel = 1;
  EXPECT_THROW(ArdusubRcOverrideMap(layout, p), std::invalid_argument);  // channel twice
  p.channels[7] = {"t9_nowhere", 8, false};
  EXPECT_THROW(ArdusubRcOverrideMap(layout, p), std::invalid_argument);
  p.channels.clear();
  p.pwm_neutral_us = 1100;
  EXPECT_THROW(ArdusubRcOverrideMap(layout, p), std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::drivers
