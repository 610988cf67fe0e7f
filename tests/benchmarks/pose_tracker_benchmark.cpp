// Micro-benchmarks of what the tracker adds to a frame: the attitude filter's read and the
// tracker's update, fused and coasting (the per-frame budget is the estimator's).
#include <benchmark/benchmark.h>

#include <chrono>

#include "control/attitude_filter.hpp"
#include "control/pose_tracker.hpp"

namespace {

using namespace rovctl;
using namespace std::chrono_literals;

// A marker 0.8 m ahead approached at 0.1 m/s, the vehicle turning at 2 deg/s.
control::PoseMeasurement frame(int i, Eigen::Quaterniond& q_world_body) {
  const double t_s = i * 0.033;
  q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(0.035 * t_s, Eigen::Vector3d::UnitZ()));
  control::PoseMeasurement m;
  m.sound = true;
  m.T_cl_marker.translation() = Eigen::Vector3d(0.02, 0.0, 0.8 - 0.1 * t_s);
  m.bound_m = 0.003;
  m.bound_deg = 1.0;
  return m;
}

void BM_PoseTrackerUpdate(benchmark::State& state) {
  const bool coasting = state.range(0) != 0;
  control::PoseTracker tracker({}, Eigen::Isometry3d::Identity(), 0.010, 5.0);
  Eigen::Quaterniond q;
  int i = 0;
  for (; i < 10; ++i) tracker.update(i * 33ms, q, true, frame(i, q));
  for (auto _ : state) {
    control::PoseMeasurement m = frame(i, q);
    m.sound = !coasting;
    benchmark::DoNotOptimize(tracker.update(i * 33ms, q, true, m));
    // Keep the track alive and the history full: fuse every frame, coast from a fresh track.
    if (coasting && (i % 8) == 0) tracker.update(i * 33ms, q, true, frame(i, q));
    ++i;
  }
}
BENCHMARK(BM_PoseTrackerUpdate)->Arg(0)->Arg(1)->ArgNames({"coasting"});

void BM_AttitudeFilterUpdate(benchmark::State& state) {
  control::AttitudeFilter filter(2.0, 250ms);
  const Eigen::Vector3d omega(0.0, 0.0, 0.035);
  int i = 0;
  for (auto _ : state) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.035 * i * 0.033, Eigen::Vector3d::UnitZ()));
    filter.update(i * 33ms, true, q, omega);
    benchmark::DoNotOptimize(filter.q_world_body_at(i * 33ms - 10ms));
    ++i;
  }
}
BENCHMARK(BM_AttitudeFilterUpdate);

}  // namespace
