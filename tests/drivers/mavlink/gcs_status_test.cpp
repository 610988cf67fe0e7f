// rovctl's ground-station status in virtual time: the frames decode with the right ids, lengths
// and names; HEARTBEAT at 1 Hz and the four values at 4 Hz counted over a minute; queued
// STATUSTEXTs first; the tick's side allocates nothing.
#include "drivers/mavlink/gcs_status.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "drivers/mavlink/mavlink_messages.hpp"
#define ROVCTL_MALLOC_HOOKS_ELSEWHERE 1
#include "malloc_counter.hpp"

namespace rovctl::drivers {
namespace {

using namespace std::chrono_literals;
namespace mav = mavlink;

// Drains what is due at `now` and decodes it with rovctl's parser (checks length and CRC_EXTRA).
std::vector<mav::Frame> drain(GcsStatus& gcs, std::chrono::nanoseconds now) {
  std::vector<mav::Frame> frames;
  std::array<std::uint8_t, mav::kMaxFrameBytes> out{};
  for (std::size_t n = gcs.next_frame(now, out); n > 0; n = gcs.next_frame(now, out)) {
    mav::FrameParser parser;
    EXPECT_EQ(parser.feed(std::span<const std::uint8_t>(out.data(), n)), n);
    mav::Frame f;
    EXPECT_TRUE(parser.next(f));
    const mav::MessageInfo* info = mav::find_message(f.header.message_id);
    EXPECT_NE(info, nullptr);
    if (info != nullptr) {
      EXPECT_LE(f.wire_length, info->max_length);
    }
    EXPECT_EQ(parser.buffered(), 0U) << "one frame per call";
    frames.push_back(f);
  }
  return frames;
}

TEST(GcsStatus, HeartbeatAtOneHertzAndFiveValuesAtFourHertzInVirtualTime) {
  GcsStatusParams p;
  GcsStatus gcs(p);
  GcsValues v;
  v.mission_state = 2.0F;
  v.fitness = 0.75F;
  v.distance_m = 1.5F;
  v.lateral_error_m = -0.02F;
  v.not_ok_reason = 3.0F;  // the bound over the limit
  gcs.post_values(v);
  std::map<std::string, int> values;
  int heartbeats = 0;
  // 60 s polled every 33 ms, as the bus's I/O thread does with each command.
  for (std::chrono::nanoseconds t = 1000s; t < 1060s; t += 33ms) {
    for (const mav::Frame& f : drain(gcs, t)) {
      EXPECT_EQ(f.header.system_id, 1);
      EXPECT_EQ(f.header.component_id, 191);
      mav::Heartbeat hb;
      mav::NamedValueFloat nv;
      if (mav::unpack(f, hb)) {
        ++heartbeats;
        EXPECT_EQ(hb.type, 18);      // MAV_TYPE_ONBOARD_CONTROLLER
        EXPECT_EQ(hb.autopilot, 8);  // MAV_AUTOPILOT_INVALID
        EXPECT_EQ(hb.system_status, 4);
      } else if (mav::unpack(f, nv)) {
        const std::string name(mav::text_of(nv.name));
        EXPECT_LE(name.size(), 10U);
        ++values[name];
        const std::map<std::string, float> want = {{"rov_state", 2.0F},
                                                   {"rov_fit", 0.75F},
                                                   {"rov_dist_m", 1.5F},
                                                   {"rov_lat_m", -0.02F},
                                                   {"rov_notok", 3.0F}};
        ASSERT_EQ(want.count(name), 1U) << name;
        EXPECT_EQ(nv.value, want.at(name)) << name;
      } else {
        ADD_FAILURE() << "unexpected message " << f.header.message_id;
      }
    }
  }
  EXPECT_NEAR(heartbeats, 60, 1);
  ASSERT_EQ(values.size(), 5U);
  for (const auto& [name, n] : values) EXPECT_NEAR(n, 240, 2) << name;
  EXPECT_EQ(gcs.counters().heartbeats, static_cast<std::uint64_t>(heartbeats));
}

TEST(GcsStatus, TextsGoFirstCutToFiftyCharsAndFailsafeShowsCritical) {
  GcsStatusParams p;
  p.system_id = 7;
  p.component_id = 192;
  GcsStatus gcs(p);
  (void)drain(gcs, 0s);  // the first beat (no values yet: none sent)
  GcsValues v;
  v.failsafe = true;
  gcs.post_values(v);
  ASSERT_TRUE(gcs.post_text(gcs_severity::warning, "rovctl: search -> approach: marker seen"));
  ASSERT_TRUE(gcs.post_text(gcs_severity::critical, std::string(80, 'x')));
  const std::vector<mav::Frame> frames = drain(gcs, 1s);
  ASSERT_GE(frames.size(), 3U);
  mav::StatusText st;
  ASSERT_TRUE(mav::unpack(frames[0], st));
  EXPECT_EQ(frames[0].header.system_id, 7);
  EXPECT_EQ(frames[0].header.component_id, 192);
  EXPECT_EQ(st.severity, 4);
  EXPECT_EQ(mav::text_of(st.text), "rovctl: search -> approach: marker seen");
  ASSERT_TRUE(mav::unpack(frames[1], st));
  EXPECT_EQ(st.severity, 2);
  EXPECT_EQ(mav::text_of(st.text), std::string(50, 'x'));
  mav::Heartbeat hb;
  ASSERT_TRUE(mav::unpack(frames[2], hb));
  EXPECT_EQ(hb.system_status, 5);  // MAV_STATE_CRITICAL while the failsafe is tripped
  EXPECT_EQ(gcs.counters().texts, 2U);
}

TEST(GcsStatus, AFullTextQueueDropsAndCounts) {
  GcsStatus gcs(GcsStatusParams{});
  int accepted = 0;
  for (int i = 0; i < 100; ++i) accepted += gcs.post_text(gcs_severity::info, "t") ? 1 : 0;
  EXPECT_LT(accepted, 100);
  (void)drain(gcs, 0s);
  EXPECT_EQ(gcs.counters().texts, static_cast<std::uint64_t>(accepted));
  EXPECT_EQ(gcs.counters().texts_dropped, static_cast<std::uint64_t>(100 - accepted));
}

TEST(GcsStatus, PostingValuesAndFramingAllocateNothing) {
  if (!rovctl::testing::malloc_hooks_installed()) GTEST_SKIP() << "no malloc hooks under ASan";
  GcsStatus gcs(GcsStatusParams{});
  std::array<std::uint8_t, mav::kMaxFrameBytes> out{};
  GcsValues v;
  const std::uint64_t before = rovctl::testing::t_allocations;
  std::size_t frames = 0;
  for (int i = 0; i < 300; ++i) {
    v.fitness = static_cast<float>(i);
    gcs.post_values(v);
    const auto now = std::chrono::nanoseconds(std::chrono::milliseconds(33 * i));
    while (gcs.next_frame(now, out) > 0) ++frames;
  }
  EXPECT_EQ(rovctl::testing::t_allocations - before, 0U);
  EXPECT_GT(frames, 100U);
}

}  // namespace
}  // namespace rovctl::drivers
