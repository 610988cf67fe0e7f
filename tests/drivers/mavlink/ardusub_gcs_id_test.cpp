// The rule `rovctl check` applies to ArduSub's GCS id under both of its parameter names.
#include "drivers/mavlink/ardusub_gcs_id.hpp"

#include <gtest/gtest.h>

namespace rovctl::drivers {
namespace {

TEST(ArdusubGcsId, TheIdRovctlSendsAsPasses) {
  const ArdusubFailsafeVerdict v = judge_ardusub_gcs_id(255, {255.0F, std::nullopt});
  EXPECT_TRUE(v.safe);
  EXPECT_EQ(v.name, "SYSID_MYGCS");
  EXPECT_EQ(v.reason, "255: ArduSub obeys the system id rovctl sends as");
}

TEST(ArdusubGcsId, AMismatchFailsUnderEitherName) {
  for (const auto& values : {std::array<std::optional<float>, 2>{254.0F, std::nullopt},
                             std::array<std::optional<float>, 2>{std::nullopt, 254.0F}}) {
    const ArdusubFailsafeVerdict v = judge_ardusub_gcs_id(255, values);
    EXPECT_FALSE(v.safe);
    EXPECT_EQ(v.name, values[0] ? "SYSID_MYGCS" : "MAV_GCS_SYSID");
    EXPECT_NE(v.reason.find("every command would be ignored"), std::string::npos) << v.reason;
    EXPECT_NE(v.reason.find("set " + v.name + " to 255 or gcs_system_id to 254"), std::string::npos)
        << v.reason;
  }
  EXPECT_TRUE(judge_ardusub_gcs_id(255, {std::nullopt, 255.0F}).safe);  // ArduSub 4.7's name
}

TEST(ArdusubGcsId, NoAnswerIsNotAPass) {
  const ArdusubFailsafeVerdict v = judge_ardusub_gcs_id(255, {std::nullopt, std::nullopt});
  EXPECT_FALSE(v.safe);
  EXPECT_EQ(v.name, "SYSID_MYGCS/MAV_GCS_SYSID");
}

}  // namespace
}  // namespace rovctl::drivers
