// Short ground-station texts of the loop's events.
#include "app/runtime/gcs_event_text.hpp"

#include <cstdio>
#include <cstring>

#include "drivers/mavlink/gcs_status.hpp"

namespace rovctl::app {

namespace sev = drivers::gcs_severity;

std::string_view GcsEventText::text() const { return {buffer.data(), std::strlen(buffer.data())}; }

GcsEventText gcs_event_text(const LoopEvent& e) {
  GcsEventText t;
  char* b = t.buffer.data();
  const std::size_t n = t.buffer.size();
  if (e.thruster >= 0) {
    t.severity = sev::error;
    std::snprintf(b, n, "rovctl: thruster %d failed: %s", e.thruster,
                  control::to_string(e.thruster_failure));
  } else if (e.failsafe && e.failsafe_kind == control::FailsafeEventKind::recovered) {
    t.severity = sev::notice;
    std::snprintf(b, n, "rovctl: failsafe %s recovered", control::to_string(e.cause));
  } else if (e.failsafe) {
    const bool latched = e.failsafe_kind == control::FailsafeEventKind::latched;
    t.severity = latched || e.action == control::SafeAction::disarm ? sev::critical : sev::warning;
    // The bus's own reason (e.g. "ArduSub link lost") says more than its cause, in 50 chars.
    std::snprintf(b, n, "rovctl: FAILSAFE %s%s -> %s",
                  *e.reason ? e.reason : control::to_string(e.cause), latched ? " latched" : "",
                  control::to_string(e.action));
  } else {
    const bool bad = e.to == control::MissionState::abort || e.to == control::MissionState::failed;
    t.severity = bad ? sev::warning : sev::info;
    std::snprintf(b, n, "rovctl: %s -> %s: %s", control::to_string(e.from),
                  control::to_string(e.to), e.reason);
  }
  return t;
}

}  // namespace rovctl::app
