// `rovctl bench --set` split by a manifest number (`--by FIELD --by-edges ...`) on the committed
// water-set sample, and the usage errors that name what is wrong before any pair is scored; a
// sequence folder without its files named.
#include <gtest/gtest.h>

#include <string>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {
namespace {

const std::string kSample = std::string(ROVCTL_TEST_DATA_DIR) + "/water_set";

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) ++n;
  return n;
}

TEST(CommandBench, SplitsEachConditionByAManifestNumber) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const int rc = command_bench(
      {"--set", kSample, "--frames", "1", "--by", "jpeg_quality", "--by-edges", "50,60", "--json"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(rc, 0);
  const std::size_t by_field = out.find("\"by_field\"");
  ASSERT_NE(by_field, std::string::npos) << out;
  // Each condition's row says how its ok pairs' errors stood against their bounds.
  const std::string conditions = out.substr(0, out.find("\"by_range\""));
  EXPECT_EQ(count_of(conditions, "\"bound_held\""), count_of(conditions, "\"condition\""));
  EXPECT_NE(conditions.find("\"rotation_bound_ratio_max\""), std::string::npos) << conditions;
  const std::string rows = out.substr(by_field);
  // Only the JPEG pairs carry a quality (noise_jpeg's q45, q62 and q64; noise_mjpg90's q90; not
  // YUYV's): noise_jpeg has one row under 50 with no lower edge and one from 60 with no upper edge,
  // no row for the empty band between; noise_mjpg90 one row from 60.
  EXPECT_EQ(count_of(rows, "\"field\": \"jpeg_quality\""), 3u) << rows;
  EXPECT_EQ(count_of(rows, "\"condition\": \"noise_jpeg\""), 2u) << rows;
  EXPECT_EQ(count_of(rows, "\"condition\": \"noise_mjpg90\""), 1u) << rows;
  EXPECT_EQ(count_of(rows, "\"condition\": \"noise_yuyv\""), 0u) << rows;
  EXPECT_EQ(count_of(rows, "\"condition\": \"clear\""), 0u) << rows;
  EXPECT_NE(rows.find("\"from\": null, \"to\": 50, \"pairs\": 1"), std::string::npos) << rows;
  EXPECT_NE(rows.find("\"condition\": \"noise_jpeg\", \"field\": \"jpeg_quality\", \"from\": 60, "
                      "\"to\": null, \"pairs\": 2"),
            std::string::npos)
      << rows;
}

template <class Error>
std::string error_of(const Words& words) {
  ::testing::internal::CaptureStdout();
  std::string message;
  try {
    command_bench(words);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");  // no table from bad input
  return message;
}

TEST(CommandBench, ASplitThatCannotBeMadeIsNamed) {
  const std::string unknown =
      error_of<UsageError>({"--set", kSample, "--by", "jpeg_qualty", "--by-edges", "50"});
  EXPECT_NE(unknown.find("'jpeg_qualty'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("manifest.json"), std::string::npos) << unknown;
  EXPECT_NE(error_of<UsageError>({"--set", kSample, "--by", "jpeg_quality"}).find("--by-edges"),
            std::string::npos);
  const std::string descending =
      error_of<UsageError>({"--set", kSample, "--by", "jpeg_quality", "--by-edges", "60,50"});
  EXPECT_NE(descending.find("'50'"), std::string::npos) << descending;
  EXPECT_NE(
      error_of<UsageError>({"--set", kSample, "--by", "range_m", "--by-edges", "1,x"}).find("'x'"),
      std::string::npos);
  EXPECT_NE(error_of<UsageError>({"--by", "jpeg_quality", "--by-edges", "50"}).find("--set"),
            std::string::npos);
}

TEST(CommandBench, ASequenceFolderWithoutItsFilesIsNamed) {
  const std::string missing = error_of<ConfigError>({"--sequence", kSample});
  EXPECT_NE(missing.find("sequence.json: missing"), std::string::npos) << missing;
  EXPECT_NE(error_of<UsageError>({"--sequence", kSample, "--set", kSample}).find("give one"),
            std::string::npos);
}

}  // namespace
}  // namespace rovctl::app
