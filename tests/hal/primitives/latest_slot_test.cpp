// The latest-value mailbox: newest wins, nothing is torn, and the reader never blocks the writer.
#include "hal/primitives/latest_slot.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace rovctl::app {
namespace {

struct Pair {
  std::uint64_t a = 0;
  std::uint64_t b = 0;
};

TEST(LatestSlot, NothingBeforeTheFirstPublish) {
  LatestSlot<int> slot;
  EXPECT_EQ(slot.take(), nullptr);
  EXPECT_EQ(slot.current(), nullptr);
}

TEST(LatestSlot, TheReaderGetsTheNewestAndOnlyOnce) {
  LatestSlot<int> slot;
  for (int v : {1, 2, 3}) {
    slot.back() = v;
    slot.publish();
  }
  const int* got = slot.take();
  ASSERT_NE(got, nullptr);
  EXPECT_EQ(*got, 3);
  EXPECT_EQ(slot.take(), nullptr) << "nothing new since";
  EXPECT_EQ(*slot.current(), 3);
  slot.back() = 4;
  slot.publish();
  EXPECT_EQ(*slot.take(), 4);
  EXPECT_EQ(slot.published(), 4u);
}

TEST(LatestSlot, ConcurrentValuesAreWholeAndNeverGoBack) {
  LatestSlot<Pair> slot;
  std::atomic<bool> done{false};
  constexpr std::uint64_t kWrites = 200000;
  std::thread writer([&] {
    for (std::uint64_t i = 1; i <= kWrites; ++i) {
      Pair& p = slot.back();
      p.a = i;
      p.b = ~i;
      slot.publish();
    }
    done = true;
  });
  std::uint64_t last = 0, reads = 0, torn = 0, backwards = 0;
  const auto read = [&] {
    const Pair* p = slot.take();
    if (p == nullptr) return;
    ++reads;
    if (p->b != ~p->a) ++torn;
    if (p->a <= last) ++backwards;
    last = p->a;
  };
  while (!done) read();
  writer.join();
  read();  // whatever was published last, if the loop had not taken it yet
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(backwards, 0u);
  EXPECT_GT(reads, 0u);
  EXPECT_EQ(last, kWrites) << "the final value is the last one written";
}

}  // namespace
}  // namespace rovctl::app
