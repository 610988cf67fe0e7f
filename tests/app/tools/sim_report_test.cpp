// The sim report's verdict: a trial is docked only when the simulator captured the probe within
// the tolerances and the mission itself reached DOCKED.
#include "app/tools/sim_report.hpp"

#include <gtest/gtest.h>

namespace rovctl::app {
namespace {

TrialResult captured_trial(bool mission_docked, double lateral_mm) {
  TrialResult r;
  r.docked = true;
  r.mission_docked = mission_docked;
  r.lateral_error_mm = lateral_mm;
  r.yaw_error_deg = 0.5;
  r.time_to_dock_s = 20.0;
  r.success = trial_docked(r);
  return r;
}

TEST(SimReport, ATrialIsDockedOnlyWhenTheMissionSaysSo) {
  const std::vector<TrialResult> results = {captured_trial(true, 3.0), captured_trial(false, 3.0),
                                            captured_trial(true, 25.0), TrialResult{}};
  EXPECT_TRUE(results[0].success);
  EXPECT_FALSE(results[1].success) << "touched the socket, but the mission never reached DOCKED";
  EXPECT_FALSE(results[2].success) << "off the lateral tolerance";
  EXPECT_FALSE(results[3].success);
  const SimSummary s = summarise(results);
  EXPECT_EQ(s.trials, 4);
  EXPECT_EQ(s.captured, 3);
  EXPECT_EQ(s.docked, 1);
  EXPECT_DOUBLE_EQ(s.success_rate, 0.25);
}

TEST(SimReport, ATouchOffTheSocketAxisIsCountedEvenWhenTheTrialDockedLater) {
  std::vector<TrialResult> results = {captured_trial(true, 3.0), captured_trial(true, 3.0),
                                      TrialResult{}};
  results[0].touch_lateral_max_mm = 4.0;   // touched inside the funnel
  results[1].touch_lateral_max_mm = 26.0;  // hit the rim first, then docked
  const SimSummary s = summarise(results);
  EXPECT_EQ(s.touched_off_centre, 1);
  EXPECT_DOUBLE_EQ(s.touch_lateral_mm_max, 26.0);
  EXPECT_NE(summary_json(s).find("\"touched_off_centre\": 1"), std::string::npos)
      << summary_json(s);
  EXPECT_EQ(summarise({TrialResult{}}).touch_lateral_mm_max, -1.0) << "never touched";
}

// The closed loop's false ok: ticks whose ok estimate was wrong, summed over the trials and said in
// the JSON and the text, with the trials that had any and the worst ok tick.
TEST(SimReport, OkButWrongTicksAreSummedAndSaid) {
  std::vector<TrialResult> results = {captured_trial(true, 3.0), captured_trial(true, 3.0),
                                      captured_trial(true, 3.0)};
  results[0].ok_ticks = 600;
  results[0].ok_error_mm_max = 2.5;
  results[0].ok_error_deg_max = 0.4;
  results[1].ok_ticks = 500;
  results[1].ok_wrong_ticks = 3;
  results[1].ok_over_bound_ticks = 5;
  results[1].ok_error_mm_max = 14.0;
  results[1].ok_error_deg_max = 1.1;
  results[2].ok_ticks = 550;
  results[2].ok_wrong_ticks = 1;
  results[2].ok_error_mm_max = 6.0;
  results[2].ok_error_deg_max = 7.5;
  const SimSummary s = summarise(results);
  EXPECT_EQ(s.ok_ticks, 1650u);
  EXPECT_EQ(s.ok_wrong_ticks, 4u);
  EXPECT_EQ(s.trials_ok_wrong, 2);
  EXPECT_EQ(s.ok_over_bound_ticks, 5u);
  EXPECT_DOUBLE_EQ(s.ok_error_mm_max, 14.0);
  EXPECT_DOUBLE_EQ(s.ok_error_deg_max, 7.5);
  const std::string json = summary_json(s);
  EXPECT_NE(json.find("\"ok_wrong_ticks\": 4"), std::string::npos) << json;
  EXPECT_NE(json.find("\"trials_ok_wrong\": 2"), std::string::npos) << json;
  EXPECT_NE(json.find("\"ok_over_bound_ticks\": 5"), std::string::npos) << json;
  const std::string text = summary_text(s, results);
  EXPECT_NE(text.find("ok but wrong (>= 10 mm or 5 deg from their image's truth) 4 in 2 trials"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("off by more than their own error bound 5"), std::string::npos) << text;
}

// A figure with no sample is -1 in the JSON; the text says so in words, not as a number that reads
// like a measurement ("hold/charged median -100.00 %" when no trial charged).
TEST(SimReport, FiguresWithoutASampleReadNoneInTheText) {
  TrialResult knocked_out;  // recharge trial that docked but never charged or departed
  knocked_out.recharge = true;
  knocked_out.docked = true;
  knocked_out.mission_docked = true;
  knocked_out.time_to_dock_s = 18.0;
  knocked_out.lateral_error_mm = 2.0;
  knocked_out.final_state = "IDLE";
  const SimSummary s = summarise({knocked_out, TrialResult{}});
  ASSERT_TRUE(s.recharge);
  EXPECT_EQ(s.hold_fraction_median, -1.0);
  EXPECT_EQ(s.undock_clearance_m_min, -1.0);
  EXPECT_NE(summary_json(s).find("\"undock_clearance_m_min\": -1"), std::string::npos)
      << "the JSON keeps its documented -1";
  const std::string text = summary_text(s, {knocked_out, TrialResult{}});
  EXPECT_NE(text.find("hold/charged median none % (max none %)"), std::string::npos) << text;
  EXPECT_NE(text.find("undock clearance min none m"), std::string::npos) << text;
  EXPECT_NE(text.find("contact held min none (median none)"), std::string::npos) << text;
  EXPECT_NE(text.find("largest touch none mm"), std::string::npos) << text;
  EXPECT_EQ(text.find("-1."), std::string::npos) << text;
  EXPECT_EQ(text.find("-100"), std::string::npos) << text;
  EXPECT_NE(text.find("time to dock median 18.0 s"), std::string::npos) << text;

  // A signed figure is not a sentinel: a docked trial's yaw error of -0.35 deg prints as such.
  TrialResult turned_left = knocked_out;
  turned_left.yaw_error_deg = -0.35;
  EXPECT_NE(summary_text(summarise({turned_left}), {turned_left}).find("  -0.35  "),
            std::string::npos);
}

}  // namespace
}  // namespace rovctl::app
