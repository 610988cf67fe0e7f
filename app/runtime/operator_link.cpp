// The tick's side of the operator view: plain copies into slots sized at start-up.
#include "app/runtime/operator_link.hpp"

#include <opencv2/core.hpp>
#include <thread>

namespace rovctl::app {

OperatorLink::OperatorLink(const hal::StereoRig& rig, std::chrono::nanoseconds image_period)
    : frames_([&rig](OperatorFrame& f) {
        f.left_bgr.create(rig.left.height_px, rig.left.width_px, CV_8UC3);
        f.right_bgr.create(rig.right.height_px, rig.right.width_px, CV_8UC3);
        f.left_bgr.setTo(cv::Scalar::all(0));
        f.right_bgr.setTo(cv::Scalar::all(0));
      }),
      image_period_(image_period) {}

void OperatorLink::publish(const TelemetryRecord& record, const hal::StereoFrame* frame,
                           std::chrono::nanoseconds now) noexcept {
  records_.back() = record;
  records_.publish();
  last_tick_.store(record.tick, std::memory_order_relaxed);
  // A clock that went back (the next simulated trial starts at 0) starts the period afresh.
  if (frame == nullptr ||
      (last_image_.count() >= 0 && now >= last_image_ && now - last_image_ < image_period_)) {
    return;
  }
  OperatorFrame& out = frames_.back();
  // copyTo into a Mat of the same size and type reuses its buffer; any other size is skipped
  // rather than reallocated on the tick.
  if (frame->left_bgr.size() != out.left_bgr.size() ||
      frame->right_bgr.size() != out.right_bgr.size() || frame->left_bgr.type() != CV_8UC3 ||
      frame->right_bgr.type() != CV_8UC3) {
    return;
  }
  frame->left_bgr.copyTo(out.left_bgr);
  frame->right_bgr.copyTo(out.right_bgr);
  out.record = record;
  frames_.publish();
  last_image_ = now;
}

namespace {

std::int64_t steady_ns(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

}  // namespace

bool OperatorLink::take(Request& r) noexcept {
  const std::uint64_t id = r.pending.exchange(0, std::memory_order_acq_rel);
  if (id == 0) return false;
  // The deadline was stored before the id was published (release), so it is this request's.
  if (steady_ns(std::chrono::steady_clock::now()) > r.deadline_ns.load(std::memory_order_relaxed)) {
    stale_dropped_.fetch_add(1, std::memory_order_relaxed);
    r.dropped.store(id, std::memory_order_release);
    return false;
  }
  // This tick publishes its record after taking: its number is the last published one plus one.
  r.taken_tick.store(last_tick_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  r.taken.store(id, std::memory_order_release);
  return true;
}

std::uint64_t OperatorLink::post(Request& r,
                                 std::chrono::steady_clock::time_point deadline) noexcept {
  const std::uint64_t id = next_id_.fetch_add(1, std::memory_order_relaxed) + 1;
  r.deadline_ns.store(steady_ns(deadline), std::memory_order_relaxed);
  r.pending.store(id, std::memory_order_release);
  return id;
}

OperatorCommandResult OperatorLink::submit(OperatorCommand command,
                                           std::chrono::steady_clock::time_point deadline,
                                           std::chrono::microseconds poll) {
  std::lock_guard<std::mutex> lock(submit_mutex_);
  Request& r = request(command);
  const std::uint64_t id = post(r, deadline);
  for (;;) {
    if (r.taken.load(std::memory_order_acquire) == id) {
      return {true, r.taken_tick.load(std::memory_order_relaxed)};
    }
    if (r.dropped.load(std::memory_order_acquire) == id) return {};
    if (std::chrono::steady_clock::now() >= deadline) {
      std::uint64_t expected = id;
      // Withdrawn before any tick saw it: from here on no tick can take it.
      if (r.pending.compare_exchange_strong(expected, 0, std::memory_order_acq_rel)) return {};
      // A tick holds it right now and answers within a few instructions: keep polling briefly.
      std::this_thread::yield();
      continue;
    }
    std::this_thread::sleep_for(poll);
  }
}

std::uint64_t OperatorLink::request_abort(std::chrono::milliseconds max_age) noexcept {
  post(abort_, std::chrono::steady_clock::now() + max_age);
  return last_tick();
}

std::uint64_t OperatorLink::request_start(std::chrono::milliseconds max_age) noexcept {
  post(start_, std::chrono::steady_clock::now() + max_age);
  return last_tick();
}

}  // namespace rovctl::app
