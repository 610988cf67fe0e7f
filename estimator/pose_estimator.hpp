// Per-frame orchestration of the estimator: segment both images, evolve the RM-GA population
// carried over from the last frame within the frame budget, and (improved mode) seed it from
// colour blobs and refine the elite.
#pragma once

#include <Eigen/Geometry>
#include <chrono>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "estimator/blob_seeder.hpp"
#include "estimator/estimator_params.hpp"
#include "estimator/gene_codec.hpp"
#include "estimator/hue_segmenter.hpp"
#include "estimator/marker_fitness.hpp"
#include "estimator/pose_refiner.hpp"
#include "estimator/rmga.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

struct PoseEstimate {
  bool recognised = false;  // fitness >= recognition threshold (paper: 0.6)
  // Null, or why there is no estimate this frame (a static string: e.g. an image whose size
  // disagrees with the calibration). Never thrown: the estimator runs inside the tick.
  const char* input_error = nullptr;
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  double fitness = 0.0;  // best individual's fitness in [0, 1]
  int generations = 0;   // generations run this frame
  std::chrono::nanoseconds compute_time{0};
};

class PoseEstimator {
 public:
  // Throws std::invalid_argument when the params are inconsistent (EstimatorParams::validate).
  PoseEstimator(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                const EstimatorParams& params, std::uint64_t seed);
  PoseEstimator(const PoseEstimator&) = delete;
  PoseEstimator& operator=(const PoseEstimator&) = delete;

  // One frame: segment() then estimate(). Allocates nothing after construction.
  PoseEstimate update(const cv::Mat& left_bgr, const cv::Mat& right_bgr);
  // The two stages of a frame, timed apart by the tick. segment() labels both images; false
  // (and the next estimate() says why) when an image's size or type disagrees with the rig.
  bool segment(const cv::Mat& left_bgr, const cv::Mat& right_bgr);
  // Evolves the carried-over population on the last segmented pair within the frame budget,
  // which counts from the start of segment().
  PoseEstimate estimate();
  void reset();  // fresh random population (marker lost / new search)

  const EstimatorParams& params() const { return params_; }
  const cv::Mat& labels(int view) const { return labels_[view]; }
  const MarkerFitness& fitness() const { return fitness_; }
  const GeneCodec& codec() const { return codec_; }
  long fitness_evaluations() const { return ga_.evaluations() + extra_evaluations_; }

 private:
  hal::StereoRig rig_;
  EstimatorParams params_;
  HueSegmenter segmenter_;
  GeneCodec codec_;
  MarkerFitness fitness_;
  Rmga ga_;
  BlobSeeder blobs_;
  PoseRefiner refiner_;
  cv::Mat labels_[2];
  long extra_evaluations_ = 0;
  std::chrono::steady_clock::time_point frame_start_{};
  const char* input_error_ = nullptr;
};

}  // namespace rovctl::estimator
