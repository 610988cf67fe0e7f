// Stereo pairing by capture stamp: tolerance, newest pair only, unpaired counts, token return.
#include "drivers/v4l2/frame_pairing.hpp"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace rovctl::drivers {
namespace {

using std::chrono::milliseconds;

std::vector<int> released(FramePairing& p, Side want) {
  std::vector<int> tokens;
  Side side{};
  int token = 0;
  std::vector<std::pair<Side, int>> all;
  while (p.pop_released(side, token)) all.emplace_back(side, token);
  for (const auto& [s, t] : all) {
    if (s == want) tokens.push_back(t);
  }
  return tokens;
}

TEST(FramePairing, PairsFramesWithinTolerance) {
  FramePairing p(milliseconds(5), 2);
  p.add(Side::left, milliseconds(100), 1);
  EXPECT_FALSE(p.take_newest_pair());
  p.add(Side::right, milliseconds(104), 7);
  const auto pair = p.take_newest_pair();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->left.token, 1);
  EXPECT_EQ(pair->right.token, 7);
  EXPECT_EQ(pair->left.stamp, milliseconds(100));
  EXPECT_EQ(pair->right.stamp, milliseconds(104));
  EXPECT_EQ(p.held(Side::left), 0U);
  EXPECT_EQ(p.held(Side::right), 0U);
  EXPECT_EQ(p.stats().pairs, 1U);
}

TEST(FramePairing, RejectsFramesFartherApartThanTolerance) {
  FramePairing p(milliseconds(5), 2);
  p.add(Side::left, milliseconds(100), 1);
  p.add(Side::right, milliseconds(106), 2);
  EXPECT_FALSE(p.take_newest_pair());
  // The right frame waits: a later left frame pairs with it.
  p.add(Side::left, milliseconds(107), 3);
  const auto pair = p.take_newest_pair();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->left.token, 3);
  EXPECT_EQ(pair->right.token, 2);
  // The orphaned left frame is released and counted as unpaired.
  EXPECT_EQ(released(p, Side::left), std::vector<int>{1});
  EXPECT_EQ(p.stats().unpaired, 1U);
  EXPECT_EQ(p.stats().superseded, 0U);
}

TEST(FramePairing, TakesOnlyTheNewestPairAndDropsTheBacklog) {
  FramePairing p(milliseconds(3), 4);
  // Three frame periods queued up on both sides (a slow consumer).
  for (int i = 0; i < 3; ++i) {
    p.add(Side::left, milliseconds(100 + 33 * i), 10 + i);
    p.add(Side::right, milliseconds(101 + 33 * i), 20 + i);
  }
  const auto pair = p.take_newest_pair();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->left.token, 12);
  EXPECT_EQ(pair->right.token, 22);
  EXPECT_EQ(p.held(Side::left), 0U);
  EXPECT_EQ(p.held(Side::right), 0U);
  Side side{};
  int token = 0;
  std::set<int> back;
  while (p.pop_released(side, token)) back.insert(token);
  EXPECT_EQ(back, (std::set<int>{10, 11, 20, 21}));
  // They had partners: superseded, not unpaired.
  EXPECT_EQ(p.stats().superseded, 4U);
  EXPECT_EQ(p.stats().unpaired, 0U);
  EXPECT_FALSE(p.take_newest_pair());
}

TEST(FramePairing, KeepsNewerFramesWaitingForTheirPartner) {
  FramePairing p(milliseconds(3), 3);
  p.add(Side::left, milliseconds(100), 1);
  p.add(Side::left, milliseconds(133), 2);
  p.add(Side::right, milliseconds(101), 5);
  const auto pair = p.take_newest_pair();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->left.token, 1);
  EXPECT_EQ(p.held(Side::left), 1U);  // 133 ms waits for its right partner
  p.add(Side::right, milliseconds(134), 6);
  const auto next = p.take_newest_pair();
  ASSERT_TRUE(next);
  EXPECT_EQ(next->left.token, 2);
  EXPECT_EQ(next->right.token, 6);
}

TEST(FramePairing, FullSideReleasesItsOldestFrame) {
  FramePairing p(milliseconds(2), 2);
  p.add(Side::left, milliseconds(0), 1);
  p.add(Side::left, milliseconds(33), 2);
  p.add(Side::left, milliseconds(66), 3);  // right camera stalled
  EXPECT_EQ(p.held(Side::left), 2U);
  EXPECT_EQ(released(p, Side::left), std::vector<int>{1});
  EXPECT_EQ(p.stats().unpaired, 1U);
}

TEST(FramePairing, PrefersTheCloserOfTwoEquallyNewPairs) {
  FramePairing p(milliseconds(10), 3);
  p.add(Side::left, milliseconds(100), 1);
  p.add(Side::right, milliseconds(100), 5);
  p.add(Side::right, milliseconds(108), 6);
  const auto pair = p.take_newest_pair();
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->right.token, 5);
  EXPECT_EQ(p.held(Side::right), 1U);  // the newer right frame may pair with a newer left one
}

TEST(FramePairing, ClearReleasesEverythingUncounted) {
  FramePairing p(milliseconds(1), 3);
  p.add(Side::left, milliseconds(0), 1);
  p.add(Side::right, milliseconds(50), 2);
  p.clear();
  EXPECT_EQ(p.held(Side::left), 0U);
  EXPECT_EQ(p.held(Side::right), 0U);
  Side side{};
  int token = 0;
  int n = 0;
  while (p.pop_released(side, token)) ++n;
  EXPECT_EQ(n, 2);
  EXPECT_EQ(p.stats().unpaired, 0U);
}

TEST(FramePairing, EveryTokenComesBackExactlyOnce) {
  // Two free-running cameras with drifting phase: nothing is lost or duplicated.
  FramePairing p(milliseconds(4), 2);
  std::multiset<int> outstanding;
  int token = 0;
  for (int i = 0; i < 300; ++i) {
    const Side s = (i % 2 == 0) ? Side::left : Side::right;
    const auto stamp = std::chrono::microseconds(16667 * (i / 2) + (s == Side::left ? 0 : 37 * i));
    p.add(s, stamp, token);
    outstanding.insert(token++);
    if (const auto pair = p.take_newest_pair()) {
      outstanding.erase(outstanding.find(pair->left.token));
      outstanding.erase(outstanding.find(pair->right.token));
    }
    Side side{};
    int t = 0;
    while (p.pop_released(side, t)) {
      ASSERT_NE(outstanding.find(t), outstanding.end()) << t;
      outstanding.erase(outstanding.find(t));
    }
    EXPECT_EQ(outstanding.size(), p.held(Side::left) + p.held(Side::right));
  }
  const PairingStats& st = p.stats();
  EXPECT_GT(st.pairs, 0U);
  EXPECT_GT(st.unpaired, 0U);
  EXPECT_EQ(2 * st.pairs + st.unpaired + st.superseded + outstanding.size(), 300U);
}

TEST(FramePairing, RejectsBadCapacity) {
  EXPECT_THROW(FramePairing(milliseconds(1), 0), std::invalid_argument);
  EXPECT_THROW(FramePairing(milliseconds(1), FramePairing::kMaxHeldPerSide + 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::drivers
