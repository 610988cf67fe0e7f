// The control and mission sections: every default lies inside its declared range and every key
// is declared once.
#include "control/control_params.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace rovctl::control {
namespace {

// Checks each visited value against its range and records the key paths.
class RangeCheck : public hal::ParamVisitor {
 public:
  std::set<std::string> keys;
  std::vector<std::string> problems;
  std::string prefix;

  void section(std::string_view key, std::string_view,
               const std::function<void(ParamVisitor&)>& body) override {
    const std::string saved = prefix;
    prefix += std::string(key) + ".";
    body(*this);
    prefix = saved;
  }
  void param(std::string_view key, double& value, const hal::ParamMeta& m) override {
    note(key, value >= m.min && value <= m.max, m);
  }
  void param(std::string_view key, int& value, const hal::ParamMeta& m) override {
    note(key, value >= m.min && value <= m.max, m);
  }
  void param(std::string_view key, bool&, std::string_view) override { note(key, true, {}); }
  void param(std::string_view key, Eigen::Vector3d& value, const hal::ParamMeta& m) override {
    note(key, value.minCoeff() >= m.min && value.maxCoeff() <= m.max, m);
  }
  void param(std::string_view key, std::string& value, std::string_view,
             const std::vector<std::string>& choices, bool) override {
    bool ok = choices.empty();
    for (const auto& c : choices) ok = ok || c == value;
    note(key, ok, {});
  }
  void path(std::string_view key, std::string&, std::string_view, bool) override {
    note(key, true, {});
  }
  void list(std::string_view key, std::string_view, std::size_t, std::size_t, std::size_t,
            const std::function<void(std::size_t)>&,
            const std::function<void(ParamVisitor&, std::size_t)>&) override {
    note(key, true, {});
  }

 private:
  void note(std::string_view key, bool ok, const hal::ParamMeta& m) {
    const std::string k = prefix + std::string(key);
    if (!keys.insert(k).second) problems.push_back("declared twice: " + k);
    if (!ok) problems.push_back("default out of range: " + k);
    if (!m.unit.empty() && m.doc.empty()) problems.push_back("no doc: " + k);
  }
};

TEST(ControlParams, DefaultsWithinRangesAndKeysUnique) {
  RangeCheck v;
  ControlParams c;
  MissionParams m;
  v.section("control", "", [&c](hal::ParamVisitor& s) { describe(s, c); });
  v.section("mission", "", [&m](hal::ParamVisitor& s) { describe(s, m); });
  EXPECT_TRUE(v.problems.empty()) << v.problems.front();
  EXPECT_TRUE(v.keys.count("control.servo.kp_linear"));
  EXPECT_TRUE(v.keys.count("control.allocation.thruster_weights"));
  EXPECT_TRUE(v.keys.count("control.failsafe.action"));
  EXPECT_TRUE(v.keys.count("mission.align_hold_frames"));
  EXPECT_TRUE(v.keys.count("mission.max_retries"));
  EXPECT_GT(v.keys.size(), 45u);
}

TEST(ControlParams, MissionThresholdsAreConsistent) {
  const MissionParams m;
  // ALIGN is stricter than APPROACH, and the dock limits looser than ALIGN.
  EXPECT_LT(m.align_lateral_m, m.approach_lateral_m);
  EXPECT_LT(m.align_yaw_rad, m.approach_yaw_rad);
  EXPECT_GT(m.dock_abort_lateral_m, m.align_lateral_m);
  EXPECT_LT(m.dock_blind_distance_m, m.standoff_m);
}

}  // namespace
}  // namespace rovctl::control
