// Smoke test of `rovctl study --quick --json`: the output's structure and sanity (keys, the quick
// subset's 15 rows, CSV rows, report and PNGs present, finite and plausible numbers), not figures.
// The quick subset is the three lines of the paper's Fig. 9 (selection/mutation 0.4/0.1,
// 0.6/0.1, 0.8/0.15) at populations 10, 20, 40, 60, 80; one seed and a 0.2 s limit keep it short.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "app/runtime/errors.hpp"
#include "app/tools/study.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

std::string config_path() { return std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/sim.yaml"; }

fs::path temp_dir(const std::string& name) {
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  fs::path dir = fs::temp_directory_path() / (name + "-" + std::to_string(stamp));
  fs::create_directories(dir);
  return dir;
}

std::size_t line_count(const fs::path& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// JSON is YAML; yaml-cpp reads `null` as a null node.
bool finite_number(const YAML::Node& n) {
  if (!n.IsScalar()) return false;
  const double v = n.as<double>();
  return std::isfinite(v);
}

// A time is a finite multiple of the frame period within the limit, or null (never).
void expect_time_or_never(const YAML::Node& n, double limit_s, const std::string& what) {
  if (n.IsNull()) return;
  ASSERT_TRUE(finite_number(n)) << what;
  const double v = n.as<double>();
  EXPECT_GT(v, 0.0) << what;
  EXPECT_LE(v, limit_s + 1e-9) << what;
}

TEST(CommandStudy, QuickJsonWritesEverythingSane) {
  const fs::path dir = temp_dir("rovctl-study-test");
  std::ostringstream out, err;
  const int code = run_study_command({"--config", config_path(), "--quick", "--json", "--seeds",
                                      "1", "--limit-s", "0.2", "--out", dir.string()},
                                     out, err);
  ASSERT_EQ(code, kExitOk) << err.str();
  EXPECT_NE(err.str().find("study: runs"), std::string::npos) << "progress goes to stderr";

  const std::string text = out.str();
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.front(), '{');
  EXPECT_EQ(text.find('\n'), text.size() - 1) << "stdout holds one JSON line";
  const YAML::Node json = YAML::Load(text);
  for (const char* key : {"fig8", "fig8_measured", "table1", "best", "variants", "paper", "files",
                          "quick", "seeds", "time_limit_s", "wall_s"}) {
    EXPECT_TRUE(json[key].IsDefined()) << key;
  }
  EXPECT_TRUE(json["quick"].as<bool>());
  EXPECT_EQ(json["seeds"].as<int>(), 1);
  EXPECT_EQ(json["machine_budget_seeds"].as<int>(), 1);  // never more than --seeds
  const double limit_s = json["time_limit_s"].as<double>();
  EXPECT_NEAR(limit_s, 0.2, 1e-9);

  // Fig. 8: generations fall (weakly) with population, at least 1, at the study's populations.
  const YAML::Node fig8 = json["fig8"];
  ASSERT_TRUE(fig8.IsMap());
  std::set<int> populations;
  for (const auto& kv : fig8) {
    populations.insert(kv.first.as<int>());
    EXPECT_GE(kv.second.as<int>(), 1);
  }
  for (int p : {10, 20, 40, 60, 80, 500}) EXPECT_EQ(populations.count(p), 1u) << p;
  EXPECT_GT(fig8["10"].as<int>(), fig8["500"].as<int>());
  for (const auto& m : json["fig8_measured"]) {
    EXPECT_TRUE(finite_number(m["fixed_ms"]));
    EXPECT_GT(m["per_generation_us"].as<double>(), 0.0);
    EXPECT_LT(m["fixed_ms"].as<double>(), 1000.0);
  }

  // Table 1: the quick subset's 15 rows.
  const YAML::Node table1 = json["table1"];
  ASSERT_TRUE(table1.IsSequence());
  ASSERT_EQ(table1.size(), 15u);
  std::set<int> table_populations;
  for (const auto& row : table1) {
    table_populations.insert(row["population"].as<int>());
    const double selection = row["selection"].as<double>();
    const double mutation = row["mutation"].as<double>();
    EXPECT_TRUE(selection == 0.4 || selection == 0.6 || selection == 0.8) << selection;
    EXPECT_TRUE(mutation == 0.1 || mutation == 0.15) << mutation;
    const int failures = row["failures"].as<int>();
    EXPECT_GE(failures, 0);
    EXPECT_LE(failures, 1);
    EXPECT_EQ(row["runs"].as<int>(), 1);
    EXPECT_GE(row["generations_per_frame"].as<int>(), 1);
    expect_time_or_never(row["median_s"], limit_s, "median_s");
    expect_time_or_never(row["p90_s"], limit_s, "p90_s");
    // With one seed: null exactly when that run failed.
    EXPECT_EQ(row["median_s"].IsNull(), failures == 1);
  }
  EXPECT_EQ(table_populations, (std::set<int>{10, 20, 40, 60, 80}));

  // Best: one per population and an overall one that is among the rows.
  const YAML::Node best = json["best"];
  ASSERT_EQ(best["per_population"].size(), 5u);
  EXPECT_TRUE(table_populations.count(best["overall"]["population"].as<int>()) == 1);

  // Every variant has its table; the improved mode exists beside the faithful one.
  std::set<std::string> variants;
  for (const auto& v : json["variants"]) {
    variants.insert(v["name"].as<std::string>());
    EXPECT_EQ(v["table1"].size(), 15u);
  }
  // The main three, the readings' ablation and the non-paper far-field variant.
  EXPECT_EQ(variants, (std::set<std::string>{"faithful", "faithful-paper-pc", "improved",
                                             "per-child", "per-field", "non-elite", "binary",
                                             "rovctl-box", "first-reading", "far-field-paper-pc"}));
  EXPECT_EQ(json["paper"]["table1"].size(), 5u);

  // Files: CSV with a header and one row per run (15 combinations x 1 seed x each variant).
  const YAML::Node files = json["files"];
  for (const char* key : {"csv", "report", "fig8_png", "fig9_png", "pose_png"}) {
    const fs::path file = files[key].as<std::string>();
    EXPECT_TRUE(fs::is_regular_file(file)) << key;
    EXPECT_GT(fs::file_size(file), 100u) << key;
    EXPECT_EQ(file.parent_path(), dir) << key;
  }
  EXPECT_EQ(line_count(files["csv"].as<std::string>()), 1u + 15u * variants.size());
  std::ifstream report(files["report"].as<std::string>());
  const std::string md((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  for (const char* heading :
       {"## Fig. 8", "## Table 1", "## Table 2", "Where and why",
        "ablation at the paper PC's budget", "Which of the paper's claims",
        "Pose error at first fitness", "profile around the truth", "Not the paper"}) {
    EXPECT_NE(md.find(heading), std::string::npos) << heading;
  }
  EXPECT_NE(md.find("0.125"), std::string::npos) << "the paper's C beside ours";
  fs::remove_all(dir);
}

TEST(CommandStudy, UsageErrors) {
  std::ostringstream out, err;
  EXPECT_THROW(run_study_command({"--bogus"}, out, err), UsageError);
  EXPECT_THROW(run_study_command({"--seeds", "0"}, out, err), UsageError);
  EXPECT_THROW(run_study_command({"--seeds"}, out, err), UsageError);
  EXPECT_THROW(run_study_command({"--limit-s", "abc"}, out, err), UsageError);
  EXPECT_THROW(run_study_command({"--config", "/nonexistent/rovctl.yaml", "--quick"}, out, err),
               ConfigError);
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
}  // namespace rovctl::app
