// `rovctl sim` start-up errors for the charging faults (exit 2 in main, before any trial): an
// unknown --charge-fault names the faults there are, and a fault needs the recharging mission.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

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

// Serving beyond loopback is said out loud, with whether the view takes commands.
TEST(CommandSim, ServingOnEveryAddressPrintsTheExposureWarning) {
  const fs::path out = fs::temp_directory_path() / "rovctl_sim_exposure";
  fs::remove_all(out);
  for (const bool token : {false, true}) {
    std::vector<std::string> words = {"--serve",        "0.0.0.0:0",  "--max-time", "1",
                                      "--out",          out.string(), "--plots",    "0",
                                      "--serve-linger", "0"};
    if (token) words.insert(words.end(), {"--token", "secret"});
    testing::internal::CaptureStderr();
    const int code = command_sim(words);
    const std::string said = testing::internal::GetCapturedStderr();
    EXPECT_EQ(code, 0) << said;
    EXPECT_NE(said.find("warning: the operator view listens on every address of this machine"),
              std::string::npos)
        << said;
    EXPECT_NE(said.find(token ? "commands enabled: whoever has the token can ABORT and START"
                              : "read-only: no token, ABORT and START are refused"),
              std::string::npos)
        << said;
  }
  fs::remove_all(out);
}

TEST(CommandSim, ServingOnLoopbackSaysSoWithoutAWarning) {
  const fs::path out = fs::temp_directory_path() / "rovctl_sim_loopback";
  fs::remove_all(out);
  testing::internal::CaptureStderr();
  const int code = command_sim({"--serve", "127.0.0.1:0", "--max-time", "1", "--out", out.string(),
                                "--plots", "0", "--serve-linger", "0"});
  const std::string said = testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, 0) << said;
  EXPECT_NE(said.find("operator view on this machine only (127.0.0.1)"), std::string::npos) << said;
  EXPECT_EQ(said.find("warning: the operator view"), std::string::npos) << said;
  fs::remove_all(out);
}

}  // namespace
}  // namespace rovctl::app
