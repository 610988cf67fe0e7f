// Every `sim` parameter is declared with a unit, a meaning and a range holding its default.
#include "hal/mock/sim_params.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace rovctl::hal::mock {
namespace {

class Checker : public ParamVisitor {
 public:
  std::set<std::string> keys;
  std::string prefix;
  void section(std::string_view key, std::string_view doc,
               const std::function<void(ParamVisitor&)>& body) override {
    EXPECT_FALSE(doc.empty()) << key;
    const std::string saved = prefix;
    prefix += std::string(key) + ".";
    body(*this);
    prefix = saved;
  }
  void check(std::string_view key, double value, const ParamMeta& m) {
    const std::string k = prefix + std::string(key);
    EXPECT_TRUE(keys.insert(k).second) << "duplicate " << k;
    EXPECT_FALSE(m.unit.empty()) << k;
    EXPECT_FALSE(m.doc.empty()) << k;
    EXPECT_GE(value, m.min) << k;
    EXPECT_LE(value, m.max) << k;
  }
  void param(std::string_view key, double& value, const ParamMeta& m) override {
    check(key, value, m);
  }
  void param(std::string_view key, int& value, const ParamMeta& m) override {
    check(key, value, m);
  }
  void param(std::string_view key, bool&, std::string_view doc) override {
    EXPECT_FALSE(doc.empty()) << key;
    keys.insert(prefix + std::string(key));
  }
  void param(std::string_view key, Eigen::Vector3d& value, const ParamMeta& m) override {
    check(key, value.minCoeff(), m);
    keys.erase(prefix + std::string(key));
    check(key, value.maxCoeff(), m);
  }
  void param(std::string_view key, std::string&, std::string_view doc,
             const std::vector<std::string>&, bool) override {
    EXPECT_FALSE(doc.empty()) << key;
  }
  void path(std::string_view, std::string&, std::string_view, bool) override {}
  void list(std::string_view, std::string_view, std::size_t, std::size_t, std::size_t,
            const std::function<void(std::size_t)>&,
            const std::function<void(ParamVisitor&, std::size_t)>&) override {}
};

TEST(SimParams, DefaultsLieInTheirDeclaredRanges) {
  SimParams p;
  Checker c;
  describe(c, p);
  EXPECT_TRUE(c.keys.count("dynamics.mass_kg"));
  EXPECT_TRUE(c.keys.count("camera.latency_ms"));
  EXPECT_TRUE(c.keys.count("trials.current_max_mps"));
  EXPECT_TRUE(c.keys.count("faults.bus_timeout_at_s"));
  EXPECT_GT(c.keys.size(), 50u);
}

}  // namespace
}  // namespace rovctl::hal::mock
