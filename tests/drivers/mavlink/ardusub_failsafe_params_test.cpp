// The rules `rovctl check` applies to ArduSub's FS_PILOT_INPUT, FS_PILOT_TIMEOUT and
// RC_OVERRIDE_TIME.
#include "drivers/mavlink/ardusub_failsafe_params.hpp"

#include <gtest/gtest.h>

namespace rovctl::drivers {
namespace {

using Values = std::array<std::optional<float>, 3>;

std::vector<bool> safe(const ArdusubParams& p, const Values& v) {
  std::vector<bool> out;
  for (const ArdusubFailsafeVerdict& r : judge_ardusub_failsafes(p, v)) out.push_back(r.safe);
  return out;
}

TEST(ArdusubFailsafeParams, NamesEachParameterInOrder) {
  const auto verdicts = judge_ardusub_failsafes(ArdusubParams{}, Values{2.0F, 0.5F, 0.5F});
  ASSERT_EQ(verdicts.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(verdicts[i].name, kArdusubFailsafeParams[i]);
}

TEST(ArdusubFailsafeParams, PilotInputMustNeutraliseOrDisarm) {
  const ArdusubParams p;
  EXPECT_EQ(safe(p, {2.0F, 0.5F, 3.0F}), (std::vector<bool>{true, true, true}));
  EXPECT_EQ(safe(p, {1.0F, 0.5F, 3.0F})[0], true);
  const auto disabled = judge_ardusub_failsafes(p, Values{0.0F, 0.5F, 3.0F});
  EXPECT_FALSE(disabled[0].safe);
  EXPECT_NE(disabled[0].reason.find("disabled"), std::string::npos);
  EXPECT_FALSE(safe(p, {3.0F, 0.5F, 3.0F})[0]);
}

TEST(ArdusubFailsafeParams, PilotTimeoutBetweenTheAckWaitAndOneSecond) {
  ArdusubParams p;
  p.ack_timeout_ms = 300;
  EXPECT_FALSE(safe(p, {2.0F, 3.0F, 3.0F})[1]);  // ArduSub's default: 3 s of a dead rovctl
  EXPECT_TRUE(safe(p, {2.0F, 1.0F, 3.0F})[1]);
  EXPECT_TRUE(safe(p, {2.0F, 0.31F, 3.0F})[1]);
  EXPECT_FALSE(safe(p, {2.0F, 0.3F, 3.0F})[1]);  // would fire while rovctl waits for an ack
  EXPECT_FALSE(safe(p, {2.0F, 0.1F, 3.0F})[1]);
}

TEST(ArdusubFailsafeParams, OverrideTimeMattersOnlyInThrustersMode) {
  ArdusubParams p;
  p.mode = "wrench";
  EXPECT_TRUE(safe(p, {2.0F, 0.5F, -1.0F})[2]);
  p.mode = "thrusters";
  EXPECT_FALSE(safe(p, {2.0F, 0.5F, -1.0F})[2]);  // never times out
  EXPECT_FALSE(safe(p, {2.0F, 0.5F, 0.0F})[2]);   // overrides disabled
  EXPECT_FALSE(safe(p, {2.0F, 0.5F, 3.0F})[2]);   // the default: too long
  EXPECT_TRUE(safe(p, {2.0F, 0.5F, 0.5F})[2]);
}

TEST(ArdusubFailsafeParams, UnansweredIsUnsafe) {
  const auto verdicts = judge_ardusub_failsafes(ArdusubParams{}, Values{});
  for (const ArdusubFailsafeVerdict& v : verdicts) {
    EXPECT_FALSE(v.safe);
    EXPECT_EQ(v.reason, "no PARAM_VALUE from ArduSub");
  }
}

}  // namespace
}  // namespace rovctl::drivers
