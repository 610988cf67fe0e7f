// rovctl's status to the ground station (Cockpit, QGroundControl) on ArduSub's MAVLink link: its
// HEARTBEAT as an onboard controller, a STATUSTEXT per event and NAMED_VALUE_FLOATs of the
// mission. Fed lock-free (the tick's values, the event logger's texts); framed by the link's owner.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "drivers/mavlink/ardusub_params.hpp"
#include "drivers/mavlink/mavlink_codec.hpp"
#include "hal/primitives/latest_slot.hpp"
#include "hal/primitives/spsc_ring.hpp"

namespace rovctl::drivers {

// MAV_SEVERITY values used for the texts.
namespace gcs_severity {
constexpr std::uint8_t critical = 2;
constexpr std::uint8_t error = 3;
constexpr std::uint8_t warning = 4;
constexpr std::uint8_t notice = 5;
constexpr std::uint8_t info = 6;
}  // namespace gcs_severity

// What the tick shows the ground station; NaN where not known this tick.
struct GcsValues {
  float mission_state = 0.0F;    // control's mission state id
  float fitness = 0.0F;          // the pose estimate's fitness
  float distance_m = 0.0F;       // camera to marker
  float lateral_error_m = 0.0F;  // the probe off the docking axis
  // Why the estimate is not trusted, as estimator::NotOkReason's id: 0 ok (or nothing seen: see
  // rov_fit), 1 partial view, 2 not refined, 3 error bound over the limit.
  float not_ok_reason = 0.0F;
  bool failsafe = false;  // HEARTBEAT reports MAV_STATE_CRITICAL while tripped
};

struct GcsStatusCounters {
  std::uint64_t heartbeats = 0;
  std::uint64_t values = 0;  // NAMED_VALUE_FLOAT frames
  std::uint64_t texts = 0;
  std::uint64_t texts_dropped = 0;  // the queue was full
};

class GcsStatus {
 public:
  // The names of the NAMED_VALUE_FLOATs, in the order they are sent (each <= 10 chars).
  static constexpr std::array<const char*, 5> kValueNames = {"rov_state", "rov_fit", "rov_dist_m",
                                                             "rov_lat_m", "rov_notok"};
  static constexpr std::uint8_t kMavTypeOnboardController = 18;
  static constexpr std::uint8_t kMavAutopilotInvalid = 8;

  explicit GcsStatus(const GcsStatusParams& params);
  GcsStatus(const GcsStatus&) = delete;
  GcsStatus& operator=(const GcsStatus&) = delete;

  // The tick (one writer): no allocation, no lock, never waits.
  void post_values(const GcsValues& values) noexcept;
  // One non-real-time producer (the event logger): the text is cut to STATUSTEXT's 50 chars;
  // false (and counted) when the queue is full.
  bool post_text(std::uint8_t severity, std::string_view text) noexcept;

  // The link's owner (one consumer): the next frame due at `now` into `out` (its length), 0 when
  // none is due. Queued texts first, then the HEARTBEAT and the values when their periods have
  // passed. `now` is any monotonic time; the first call starts both periods.
  std::size_t next_frame(std::chrono::nanoseconds now, std::span<std::uint8_t> out);

  const GcsStatusCounters& counters() const { return counters_; }
  std::uint8_t system_id() const { return writer_.system_id(); }
  std::uint8_t component_id() const { return writer_.component_id(); }

 private:
  struct Text {
    std::uint8_t severity = 0;
    std::array<char, 50> text{};
  };

  GcsStatusParams params_;
  mavlink::FrameWriter writer_;
  app::LatestSlot<GcsValues> values_;
  app::SpscRing<Text> texts_{32};
  bool started_ = false;
  std::chrono::nanoseconds start_{0};
  std::chrono::nanoseconds next_heartbeat_{0};
  std::chrono::nanoseconds next_values_{0};
  std::size_t values_pending_ = 0;  // of kValueNames still to send this period
  GcsValues sending_;               // the values of this period, fixed while it is sent
  GcsStatusCounters counters_;
  std::atomic<std::uint64_t> texts_dropped_{0};
};

}  // namespace rovctl::drivers
