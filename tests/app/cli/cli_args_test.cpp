// CliArgs: options, numbers and comma lists, each bad value a usage error naming the option.
#include "app/cli/cli_args.hpp"

#include <gtest/gtest.h>

#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

CliArgs parse(const std::vector<std::string>& words) {
  return CliArgs::parse("faults", words, {"--only", "--trials", "--at"}, {"--json"});
}

TEST(CliArgs, ListsSplitAtCommasInOrder) {
  EXPECT_TRUE(parse({}).get_list("--only").empty()) << "absent: no items, not one empty item";
  EXPECT_EQ(parse({"--only", "camera_drop"}).get_list("--only"),
            (std::vector<std::string>{"camera_drop"}));
  EXPECT_EQ(parse({"--only=tilt,cpu_stall,bus_slow"}).get_list("--only"),
            (std::vector<std::string>{"tilt", "cpu_stall", "bus_slow"}));
  EXPECT_EQ(parse({"--only", "a", "--only", "b,c"}).get_list("--only"),
            (std::vector<std::string>{"b", "c"}))
      << "the last value given, as get()";
}

TEST(CliArgs, AnEmptyListItemIsAUsageErrorNamingTheOptionAndWhere) {
  for (const std::string value : {"", ",", "tilt,", ",tilt", "tilt,,cpu_stall"}) {
    try {
      parse({"--only", value}).get_list("--only");
      ADD_FAILURE() << "'" << value << "' was accepted";
    } catch (const UsageError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("rovctl faults: --only"), std::string::npos) << what;
      EXPECT_NE(what.find("'" + value + "'"), std::string::npos) << what;
      EXPECT_NE(what.find("empty item at character"), std::string::npos) << what;
    }
  }
}

TEST(CliArgs, NumbersOutOfRangeOrMalformedAreUsageErrors) {
  EXPECT_EQ(parse({"--trials", "20"}).get_int("--trials", 1, 1, 10000), 20);
  EXPECT_EQ(parse({}).get_int("--trials", 7, 1, 10000), 7);
  EXPECT_THROW(parse({"--trials", "0"}).get_int("--trials", 1, 1, 10000), UsageError);
  EXPECT_THROW(parse({"--trials", "2x"}).get_int("--trials", 1, 1, 10000), UsageError);
  EXPECT_DOUBLE_EQ(parse({"--at", "8.5"}).get_double("--at", 1.0, 0.1, 3600.0), 8.5);
  EXPECT_THROW(parse({"--at", "nan"}).get_double("--at", 1.0, 0.1, 3600.0), UsageError);
  EXPECT_THROW(parse({"--bogus"}), UsageError);
  EXPECT_THROW(parse({"--only"}), UsageError) << "an option without its value";
}

TEST(CliArgs, AscendingNumbersAreReadOrRefusedNamingTheOptionAndTheItem) {
  EXPECT_TRUE(parse({}).get_ascending("--at", 0.0, 20.0, "ranges").empty());
  EXPECT_EQ(parse({"--at", "0.3,1.5"}).get_ascending("--at", 0.0, 20.0, "ranges"),
            (std::vector<double>{0.3, 1.5}));
  for (const std::string value : {"1.5,0.3", "0.3,0.3", "0,1", "0.3,40", "0.3,1.5x", "nan"}) {
    try {
      parse({"--at", value}).get_ascending("--at", 0.0, 20.0, "ranges in (0, 20] m");
      ADD_FAILURE() << "'" << value << "' was accepted";
    } catch (const UsageError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("rovctl faults: --at " + value + ": must be ranges in (0, 20] m"),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("(at '"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace rovctl::app
