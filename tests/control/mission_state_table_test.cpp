// The mission's state table against the code that implements it (every transition a from_<state>
// function makes is a row's exit, every exit's reason is logged somewhere) and against the table
// docs/control.md shows between its mission-states markers.
#include "control/mission_state_table.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

namespace rovctl::control {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

using Transition = std::tuple<std::string, std::string, std::string>;  // from, to, reason

// The transitions mission.cpp's from_<state> functions make: enter(MissionState::to, ...,
// "reason"), start_undock(..., "reason") and lost_before_dock() (an ABORT, "marker lost").
std::set<Transition> transitions_in_source(const std::string& src) {
  std::set<Transition> found;
  const std::regex fn(R"(void Mission::from_(\w+)\(const Sight& s\) \{)");
  const std::regex call(
      R"((enter\(MissionState::(\w+)|start_undock\(|lost_before_dock\()([^;]*);)");
  const std::regex literal(R"re("([^"]*)")re");
  for (std::sregex_iterator f(src.begin(), src.end(), fn), end; f != end; ++f) {
    const std::size_t body_begin = static_cast<std::size_t>(f->position() + f->length());
    const std::string body = src.substr(body_begin, src.find("\n}\n", body_begin) - body_begin);
    for (std::sregex_iterator c(body.begin(), body.end(), call); c != end; ++c) {
      const std::string head = (*c)[1];
      if (head.starts_with("lost_before_dock")) {
        found.insert({(*f)[1], "abort", "marker lost"});
        continue;
      }
      const std::string to = head.starts_with("start_undock") ? "undock" : (*c)[2].str();
      const std::string args = (*c)[3];
      for (std::sregex_iterator l(args.begin(), args.end(), literal); l != end; ++l)
        found.insert({(*f)[1], to, (*l)[1]});
    }
  }
  return found;
}

TEST(MissionStateTable, OneRowPerStateInTheEnumsOrder) {
  const auto& table = mission_state_table();
  for (int i = 0; i < kMissionStateCount; ++i) {
    EXPECT_EQ(static_cast<int>(table[i].state), i) << to_string(table[i].state);
    EXPECT_NE(std::string(table[i].entered_when), "");
    EXPECT_NE(std::string(table[i].outputs), "");
  }
}

TEST(MissionStateTable, EveryTransitionTheCodeMakesIsInTheTable) {
  const std::string src = read_text(std::string(ROVCTL_SOURCE_DIR) + "/control/mission.cpp");
  ASSERT_FALSE(src.empty());
  const std::set<Transition> code = transitions_in_source(src);
  ASSERT_GE(code.size(), 20u) << "the scan of control/mission.cpp found too few transitions";
  std::set<Transition> table;
  for (const MissionStateRow& row : mission_state_table())
    for (const MissionExit& x : row.exits)
      table.insert({to_string(row.state), to_string(x.to), x.reason});
  for (const Transition& t : code) {
    EXPECT_TRUE(table.contains(t))
        << "control/mission.cpp: from_" << std::get<0>(t) << " -> " << std::get<1>(t) << " (\""
        << std::get<2>(t) << "\") is not in mission_state_table()";
  }
  // The other way: each exit's reason is one the code logs (the failsafe's back-out is logged by
  // the loop, the exhausted retries by enter()).
  const std::string loop =
      read_text(std::string(ROVCTL_SOURCE_DIR) + "/app/runtime/vehicle_loop.cpp");
  for (const Transition& t : table) {
    const std::string quoted = "\"" + std::get<2>(t) + "\"";
    EXPECT_TRUE(code.contains(t) || src.find(quoted) != std::string::npos ||
                loop.find(quoted) != std::string::npos)
        << std::get<0>(t) << " -> " << std::get<1>(t) << " (\"" << std::get<2>(t)
        << "\") is logged nowhere";
  }
}

TEST(MissionStateTable, DocsShowTheTableTheCodeDeclares) {
  const std::string path = std::string(ROVCTL_SOURCE_DIR) + "/docs/control.md";
  const std::string doc = read_text(path);
  if (doc.empty()) GTEST_SKIP() << path << " does not exist";
  const std::string begin = "<!-- mission-states:begin -->\n";
  const std::string end = "<!-- mission-states:end -->";
  const std::size_t b = doc.find(begin);
  const std::size_t e = doc.find(end);
  ASSERT_NE(b, std::string::npos) << path << " has no " << begin;
  ASSERT_NE(e, std::string::npos) << path << " has no " << end;
  ASSERT_LT(b, e);
  EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), mission_state_table_markdown())
      << path << "'s mission-states table differs from mission_state_table_markdown() (the "
      << "second text above is the code's)";
}

}  // namespace
}  // namespace rovctl::control
