// A loop event as the ground station's STATUSTEXT: a MAV_SEVERITY and a line that fits its
// 50 characters (the full line still goes to the log).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "app/runtime/vehicle_loop.hpp"

namespace rovctl::app {

struct GcsEventText {
  std::uint8_t severity = 0;      // MAV_SEVERITY
  std::array<char, 51> buffer{};  // NUL-terminated, at most 50 chars
  std::string_view text() const;
};

// Mission transitions are INFO (WARNING into ABORT or FAILED), failsafe trips WARNING (CRITICAL
// when they disarm or latch), recoveries NOTICE, a failed thruster ERROR.
GcsEventText gcs_event_text(const LoopEvent& e);

}  // namespace rovctl::app
