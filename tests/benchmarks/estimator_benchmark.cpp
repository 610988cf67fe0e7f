// Micro-benchmarks of the estimator's per-frame pieces and of the scene renderer.
#include <benchmark/benchmark.h>

#include <random>

#include "app/runtime/app_config.hpp"
#include "estimator/hue_segmenter.hpp"
#include "estimator/pose_estimator.hpp"
#include "estimator/rim_refiner.hpp"
#include "estimator/stereo_calibration.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/model/pose.hpp"

namespace {

using namespace rovctl;

struct Scene {
  hal::StereoRig rig = estimator::load_stereo_calibration(std::string(ROVCTL_SOURCE_DIR) +
                                                          "/deploy/config/stereo_calibration.yaml");
  hal::MarkerModel marker = hal::MarkerModel::standard();
  hal::mock::SceneRenderer left{rig.left, marker, {}};
  hal::mock::SceneRenderer right{rig.right, marker, {}};
  Eigen::Isometry3d truth = hal::make_pose({0.05, 0.0, 0.5}, Eigen::Quaterniond::Identity());
  cv::Mat l, r;
  Scene() { hal::mock::render_stereo(left, right, rig, truth, 1, l, r); }
};

Scene& scene() {
  static Scene s;
  return s;
}

void BM_RenderView(benchmark::State& state) {
  Scene& s = scene();
  cv::Mat out;
  std::uint64_t seed = 0;
  for (auto _ : state) s.left.render(s.truth, ++seed, out);
}
BENCHMARK(BM_RenderView)->Unit(benchmark::kMillisecond);

void BM_Segment(benchmark::State& state) {
  Scene& s = scene();
  estimator::HueSegmenter seg(s.marker);
  cv::Mat labels;
  for (auto _ : state) seg.segment(s.l, labels);
}
BENCHMARK(BM_Segment)->Unit(benchmark::kMillisecond);

void BM_Fitness(benchmark::State& state) {
  Scene& s = scene();
  estimator::PoseEstimator est(s.rig, s.marker, estimator::EstimatorParams{}, 1);
  est.update(s.l, s.r);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> n(0.0, 0.01);
  std::vector<Eigen::Isometry3d> poses(1024, s.truth);
  for (auto& T : poses) T.translation() += Eigen::Vector3d(n(rng), n(rng), n(rng));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(est.fitness().evaluate(poses[i++ & 1023]));
}
BENCHMARK(BM_Fitness);

// The rim refinement alone, from a pose 5 mm and 2 deg off (where the GA or the centroids leave
// it): its share of the frame.
void BM_RimRefine(benchmark::State& state) {
  Scene& s = scene();
  estimator::HueSegmenter seg(s.marker);
  cv::Mat left_labels, right_labels;
  seg.segment(s.l, left_labels);
  seg.segment(s.r, right_labels);
  estimator::RimRefiner rims(s.rig, s.marker);
  Eigen::Isometry3d start = s.truth;
  start.translation() += Eigen::Vector3d(0.003, -0.002, 0.004);
  start.linear() =
      Eigen::AngleAxisd(0.035, Eigen::Vector3d(1, 2, -1).normalized()) * start.linear();
  for (auto _ : state) {
    Eigen::Isometry3d T = start;
    benchmark::DoNotOptimize(rims.refine(left_labels, right_labels, T));
  }
}
BENCHMARK(BM_RimRefine)->Unit(benchmark::kMillisecond);

void BM_EstimatorFrame(benchmark::State& state) {
  Scene& s = scene();
  estimator::EstimatorParams p;
  p.mode = state.range(0) ? "improved" : "faithful";
  estimator::PoseEstimator est(s.rig, s.marker, p, 1);
  for (auto _ : state) benchmark::DoNotOptimize(est.update(s.l, s.r));
}
BENCHMARK(BM_EstimatorFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A frame from a fresh population, as `rovctl bench` times its cold starts: the GA's whole
// search, then the refinements. The steady frame above starts beside the answer.
void BM_EstimatorColdFrame(benchmark::State& state) {
  Scene& s = scene();
  estimator::PoseEstimator est(s.rig, s.marker, estimator::EstimatorParams{}, 1);
  for (auto _ : state) {
    est.reset();
    benchmark::DoNotOptimize(est.update(s.l, s.r));
  }
}
BENCHMARK(BM_EstimatorColdFrame)->Unit(benchmark::kMillisecond);

}  // namespace
