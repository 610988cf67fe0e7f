// The failsafe policy table: every cause has a rule, the defaults recover the transient causes
// and latch the hardware ones, and the config keys are the causes' keys.
#include "control/failsafe_policy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

namespace rovctl::control {
namespace {

class KeyCollector final : public hal::ParamVisitor {
 public:
  std::set<std::string> sections;
  std::string current;
  void section(std::string_view key, std::string_view,
               const std::function<void(ParamVisitor&)>& body) override {
    current = key;
    sections.insert(current);
    body(*this);
  }
  void param(std::string_view, double&, const hal::ParamMeta&) override {}
  void param(std::string_view, int&, const hal::ParamMeta&) override {}
  void param(std::string_view, bool&, std::string_view) override {}
  void param(std::string_view, Eigen::Vector3d&, const hal::ParamMeta&) override {}
  void param(std::string_view key, std::string& value, std::string_view,
             const std::vector<std::string>& choices, bool) override {
    EXPECT_FALSE(choices.empty()) << current << "." << key;
    EXPECT_NE(std::find(choices.begin(), choices.end(), value), choices.end())
        << current << "." << key << " default '" << value << "' not among its choices";
  }
  void path(std::string_view, std::string&, std::string_view, bool) override {}
  void list(std::string_view, std::string_view, std::size_t, std::size_t, std::size_t,
            const std::function<void(std::size_t)>&,
            const std::function<void(ParamVisitor&, std::size_t)>&) override {}
};

TEST(FailsafePolicy, OneSectionPerCauseNamedByItsKey) {
  FailsafePolicy policy;
  KeyCollector v;
  describe(v, policy);
  EXPECT_EQ(v.sections.size(), kFailsafeCauseCount - 1);  // not `none`
  for (std::size_t i = 1; i < kFailsafeCauseCount; ++i) {
    const auto c = static_cast<FailsafeCause>(i);
    EXPECT_EQ(v.sections.count(cause_key(c)), 1u) << cause_key(c);
    FailsafeCause back = FailsafeCause::none;
    ASSERT_TRUE(cause_from_key(cause_key(c), back));
    EXPECT_EQ(back, c);
  }
}

TEST(FailsafePolicy, DefaultsRecoverTransientAndLatchHardwareCauses) {
  const FailsafePolicy policy;
  for (const FailsafeCause c :
       {FailsafeCause::vision_lost, FailsafeCause::vision_frozen, FailsafeCause::vision_stale,
        FailsafeCause::stereo_skew, FailsafeCause::attitude_limit, FailsafeCause::cpu_overrun}) {
    EXPECT_EQ(policy.rule(c).recovery, "auto") << cause_key(c);
  }
  for (const FailsafeCause c :
       {FailsafeCause::camera_lost, FailsafeCause::camera_dead, FailsafeCause::bus_fault,
        FailsafeCause::sensor_lost, FailsafeCause::sensor_nan, FailsafeCause::sensor_implausible,
        FailsafeCause::mission_time, FailsafeCause::search_time}) {
    EXPECT_EQ(policy.rule(c).recovery, "latch") << cause_key(c);
  }
  FailsafeCause unused;
  EXPECT_FALSE(cause_from_key("no_such_cause", unused));
}

}  // namespace
}  // namespace rovctl::control
