// Framing of rovctl's ground-station status, paced by the caller's clock.
#include "drivers/mavlink/gcs_status.hpp"

#include <iterator>

#include "drivers/mavlink/mavlink_messages.hpp"

namespace rovctl::drivers {

namespace {
constexpr std::uint8_t kMavStateActive = 4;
constexpr std::uint8_t kMavStateCritical = 5;
}  // namespace

GcsStatus::GcsStatus(const GcsStatusParams& params)
    : params_(params),
      writer_(static_cast<std::uint8_t>(params.system_id),
              static_cast<std::uint8_t>(params.component_id)) {}

void GcsStatus::post_values(const GcsValues& values) noexcept {
  values_.back() = values;
  values_.publish();
}

bool GcsStatus::post_text(std::uint8_t severity, std::string_view text) noexcept {
  Text t;
  t.severity = severity;
  mavlink::set_text(t.text, text);
  if (texts_.try_push(t)) return true;
  texts_dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

std::size_t GcsStatus::next_frame(std::chrono::nanoseconds now, std::span<std::uint8_t> out) {
  counters_.texts_dropped = texts_dropped_.load(std::memory_order_relaxed);
  if (!started_) {
    started_ = true;
    start_ = now;
    next_heartbeat_ = now;
    next_values_ = now;
  }
  const auto boot_ms = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(now - start_).count());
  Text t;
  if (texts_.try_pop(t)) {
    mavlink::StatusText m;
    m.severity = t.severity;
    m.text = t.text;
    const std::size_t n = mavlink::write_message(writer_, m, out);
    if (n > 0) ++counters_.texts;
    return n;
  }
  if (now >= next_heartbeat_) {
    // On the grid, not from now: a late poll does not drift the rate; a long gap skips beats.
    next_heartbeat_ += std::chrono::milliseconds(params_.heartbeat_period_ms);
    if (next_heartbeat_ <= now) next_heartbeat_ = now + std::chrono::milliseconds(1);
    (void)values_.take();
    const GcsValues* v = values_.current();
    mavlink::Heartbeat hb;
    hb.type = kMavTypeOnboardController;
    hb.autopilot = kMavAutopilotInvalid;
    hb.system_status = v != nullptr && v->failsafe ? kMavStateCritical : kMavStateActive;
    const std::size_t n = mavlink::write_message(writer_, hb, out);
    if (n > 0) ++counters_.heartbeats;
    return n;
  }
  if (values_pending_ == 0 && now >= next_values_) {
    next_values_ += std::chrono::milliseconds(params_.values_period_ms);
    if (next_values_ <= now) next_values_ = now + std::chrono::milliseconds(1);
    (void)values_.take();
    const GcsValues* v = values_.current();
    if (v == nullptr) return 0;  // the tick has not run yet: nothing to show
    sending_ = *v;
    values_pending_ = kValueNames.size();
  }
  if (values_pending_ > 0) {
    const std::size_t i = kValueNames.size() - values_pending_;
    --values_pending_;
    const float value[] = {sending_.mission_state, sending_.fitness, sending_.distance_m,
                           sending_.lateral_error_m, sending_.not_ok_reason};
    static_assert(std::size(value) == kValueNames.size());
    mavlink::NamedValueFloat m;
    m.time_boot_ms = boot_ms;
    m.value = value[i];
    mavlink::set_text(m.name, kValueNames[i]);
    const std::size_t n = mavlink::write_message(writer_, m, out);
    if (n > 0) ++counters_.values;
    return n;
  }
  return 0;
}

}  // namespace rovctl::drivers
