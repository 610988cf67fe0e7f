// One estimator frame. The faithful mode is the paper's loop; the improved mode adds, each
// switchable: motion prediction before, blob seeding during and elite refinement after evolution.
#include "estimator/pose_estimator.hpp"

#include <stdexcept>
#include <string>

namespace rovctl::estimator {
namespace {

const EstimatorParams& validated(const EstimatorParams& p) {
  p.validate();
  return p;
}

void check_image(const cv::Mat& image, const hal::CameraModel& camera, const char* which) {
  if (image.type() != CV_8UC3 || image.cols != camera.width_px || image.rows != camera.height_px) {
    throw std::invalid_argument(
        std::string(which) + " image is " + std::to_string(image.cols) + "x" +
        std::to_string(image.rows) + " (" + std::to_string(image.channels()) +
        " channels) but the calibration says " + std::to_string(camera.width_px) + "x" +
        std::to_string(camera.height_px) + " colour");
  }
}

}  // namespace

PoseEstimator::PoseEstimator(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                             const EstimatorParams& params, std::uint64_t seed)
    : rig_(rig),
      params_(validated(params)),
      segmenter_(marker),
      codec_(params_.search),
      fitness_(rig, marker, params_.fitness),
      ga_(params_.ga, codec_, fitness_, seed),
      blobs_(rig, marker),
      refiner_(rig, marker) {
  labels_[0].create(rig.left.height_px, rig.left.width_px, CV_8UC1);
  labels_[1].create(rig.right.height_px, rig.right.width_px, CV_8UC1);
  labels_[0].setTo(0);
  labels_[1].setTo(0);
  fitness_.set_labels(labels_[0], labels_[1]);
}

void PoseEstimator::reset() { ga_.randomise(); }

PoseEstimate PoseEstimator::update(const cv::Mat& left_bgr, const cv::Mat& right_bgr,
                                   const Eigen::Isometry3d* T_clnow_clprev) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  check_image(left_bgr, rig_.left, "left");
  check_image(right_bgr, rig_.right, "right");
  segmenter_.segment(left_bgr, labels_[0]);
  segmenter_.segment(right_bgr, labels_[1]);

  const bool improved = params_.improved();
  if (improved && params_.motion_prediction && T_clnow_clprev != nullptr) {
    ga_.transform(*T_clnow_clprev);
  }
  ga_.evaluate_all();

  const bool use_blobs = improved && (params_.blob_seeding || params_.refine_elite);
  if (use_blobs) {
    blobs_.find(0, labels_[0]);
    blobs_.find(1, labels_[1]);
  }
  if (improved && params_.blob_seeding) {
    Eigen::Isometry3d T_seed;
    if (blobs_.seed(T_seed)) {
      if (params_.refine_elite) refiner_.refine(blobs_.blobs(), T_seed);
      Gene gene;
      codec_.encode(T_seed, gene);
      ga_.insert(gene, fitness_.evaluate(codec_.decode(gene)));
      ++extra_evaluations_;
    }
  }

  PoseEstimate estimate;
  if (params_.budget == "time") {
    const auto budget = std::chrono::duration<double, std::milli>(params_.time_budget_ms);
    do {
      ga_.generation();
      ++estimate.generations;
    } while (Clock::now() - start < budget);
  } else {
    for (int g = 0; g < params_.generations_per_frame; ++g) ga_.generation();
    estimate.generations = params_.generations_per_frame;
  }

  estimate.T_cl_marker = codec_.decode(ga_.best().gene);
  estimate.fitness = ga_.best().fitness;
  if (improved && params_.refine_elite) {
    // The elite refined on the blob centroids is continuous (not 12-bit) and sub-pixel; it is
    // taken unless it scores clearly worse, which means the blobs were not the marker.
    Eigen::Isometry3d T = estimate.T_cl_marker;
    if (refiner_.refine(blobs_.blobs(), T)) {
      const double f = fitness_.evaluate(T);
      ++extra_evaluations_;
      if (f >= estimate.fitness - 0.05) {
        estimate.T_cl_marker = T;
        estimate.fitness = f;
        Gene gene;
        codec_.encode(T, gene);
        ga_.insert(gene, fitness_.evaluate(codec_.decode(gene)));
        ++extra_evaluations_;
      }
    }
  }
  estimate.recognised = estimate.fitness >= params_.recognition_threshold;
  estimate.compute_time = Clock::now() - start;
  return estimate;
}

}  // namespace rovctl::estimator
