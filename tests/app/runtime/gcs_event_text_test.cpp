// The loop's events as the ground station's STATUSTEXT: severities by kind, within 50 chars.
#include "app/runtime/gcs_event_text.hpp"

#include <gtest/gtest.h>

namespace rovctl::app {
namespace {

TEST(GcsEventText, MissionTransitionIsInfoIntoAbortAWarning) {
  LoopEvent e;
  e.from = control::MissionState::search;
  e.to = control::MissionState::approach;
  e.reason = "marker seen";
  GcsEventText t = gcs_event_text(e);
  EXPECT_EQ(t.severity, 6);
  EXPECT_EQ(t.text(), "rovctl: search -> approach: marker seen");
  e.to = control::MissionState::abort;
  e.reason = "a reason far too long for the fifty characters a STATUSTEXT has";
  t = gcs_event_text(e);
  EXPECT_EQ(t.severity, 4);
  EXPECT_EQ(t.text().size(), 50U);
  EXPECT_EQ(t.text().substr(0, 24), "rovctl: search -> abort:");
}

TEST(GcsEventText, FailsafeTripLatchAndRecovery) {
  LoopEvent e;
  e.failsafe = true;
  e.cause = control::FailsafeCause::vision_lost;
  e.action = control::SafeAction::neutral;
  e.failsafe_kind = control::FailsafeEventKind::trip;
  GcsEventText t = gcs_event_text(e);
  EXPECT_EQ(t.severity, 4);
  EXPECT_NE(t.text().find("FAILSAFE"), std::string_view::npos);
  EXPECT_NE(t.text().find(control::to_string(e.cause)), std::string_view::npos);
  e.failsafe_kind = control::FailsafeEventKind::latched;
  EXPECT_EQ(gcs_event_text(e).severity, 2);
  e.failsafe_kind = control::FailsafeEventKind::trip;
  e.action = control::SafeAction::disarm;
  EXPECT_EQ(gcs_event_text(e).severity, 2);
  e.failsafe_kind = control::FailsafeEventKind::recovered;
  t = gcs_event_text(e);
  EXPECT_EQ(t.severity, 5);
  EXPECT_NE(t.text().find("recovered"), std::string_view::npos);
  EXPECT_LE(t.text().size(), 50U);
}

// A bus that tells its faults apart (ArduSub) names the fault instead of the cause, within 50
// chars; the log line keeps both.
TEST(GcsEventText, ABusFaultNamesTheBusReason) {
  LoopEvent e;
  e.failsafe = true;
  e.cause = control::FailsafeCause::bus_fault;
  e.action = control::SafeAction::disarm;
  e.reason = "ArduSub link lost";
  const GcsEventText t = gcs_event_text(e);
  EXPECT_EQ(t.text(), "rovctl: FAILSAFE ArduSub link lost -> disarm");
  const std::string line = format_event(e);
  EXPECT_NE(line.find(std::string("FAILSAFE ") + control::to_string(e.cause) +
                      " (ArduSub link lost) -> disarm"),
            std::string::npos)
      << line;
  e.reason = "";
  EXPECT_NE(gcs_event_text(e).text().find(control::to_string(e.cause)), std::string_view::npos);
}

}  // namespace
}  // namespace rovctl::app
