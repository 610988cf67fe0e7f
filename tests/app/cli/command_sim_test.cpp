// `rovctl sim` start-up errors for the charging faults (exit 2 in main, before any trial): an
// unknown --charge-fault names the faults there are, and a fault needs the recharging mission.
#include <gtest/gtest.h>

#include <string>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

std::string usage_error(const Words& words) {
  try {
    command_sim(words);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(CommandSim, UnknownChargeFaultListsTheFaults) {
  const std::string error = usage_error({"--mission", "recharge", "--charge-fault", "meteor"});
  EXPECT_NE(error.find("'meteor'"), std::string::npos) << error;
  EXPECT_NE(error.find("knock, knocks, surge, charger, operator, camera"), std::string::npos)
      << error;
}

TEST(CommandSim, AChargeFaultNeedsTheRechargingMission) {
  const std::string error = usage_error({"--mission", "dock", "--charge-fault", "knock"});
  EXPECT_NE(error.find("--mission recharge"), std::string::npos) << error;
}

}  // namespace
}  // namespace rovctl::app
