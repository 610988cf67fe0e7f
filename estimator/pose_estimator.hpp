// Per-frame orchestration of the estimator: segment both images, evolve the RM-GA population
// carried over from the last frame within the frame budget, and (improved mode) seed it from
// colour blobs, refine the elite and predict it forward with the camera's motion.
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
#include "hal/marker_model.hpp"
#include "hal/stereo_rig.hpp"

namespace rovctl::estimator {

struct PoseEstimate {
  bool recognised = false;  // fitness >= recognition threshold (paper: 0.6)
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

  // One frame: segment both images, evolve the carried-over population within the frame budget.
  // Allocates nothing after construction. Optional T_clnow_clprev (camera motion since the last
  // frame, e.g. from the vehicle's odometry) predicts the population forward when the mode uses
  // prediction. Throws std::invalid_argument if an image's size or type disagrees with the rig.
  PoseEstimate update(const cv::Mat& left_bgr, const cv::Mat& right_bgr,
                      const Eigen::Isometry3d* T_clnow_clprev = nullptr);
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
};

}  // namespace rovctl::estimator
