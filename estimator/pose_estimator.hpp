// Per-frame orchestration of the estimator: segment both images, evolve the RM-GA population
// carried over from the last frame within the frame budget, and (improved mode) seed it from
// colour blobs and refine the elite.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string_view>

#include "estimator/blob_seeder.hpp"
#include "estimator/estimator_params.hpp"
#include "estimator/gene_codec.hpp"
#include "estimator/hue_segmenter.hpp"
#include "estimator/marker_fitness.hpp"
#include "estimator/pose_refiner.hpp"
#include "estimator/rim_refiner.hpp"
#include "estimator/rmga.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

// Why a recognised estimate is not ok: the first of these that holds. The numbers go out as they
// are (the ground station's rov_notok, the telemetry record), so each is fixed here.
enum class NotOkReason : std::uint8_t {
  none = 0,              // ok, or not recognised at all
  partial_view = 1,      // a sphere not seen in one view or both (spheres_seen)
  not_refined = 2,       // improved mode: no refinement accepted, so no error bound
  bound_over_limit = 3,  // improved mode: the fit's error bound over ok_bound_mm or ok_bound_deg
  unconfirmed = 4,       // in the loop: the frame before had no ok pose, or one it disagrees with
};
const char* to_string(NotOkReason reason);
// The inverse of to_string (a telemetry file read back); false for any other text.
bool from_string(std::string_view text, NotOkReason& reason);

struct PoseEstimate {
  bool recognised = false;  // fitness >= recognition threshold (paper: 0.6)
  // Null, or why there is no estimate this frame (a static string: e.g. an image whose size
  // disagrees with the calibration). Never thrown: the estimator runs inside the tick.
  const char* input_error = nullptr;
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  double fitness = 0.0;  // best individual's fitness in [0, 1]
  // How sure: the spheres each view supports at this pose (score(v, s) >= the support
  // threshold), and ok only when every sphere is supported in both views. A partial view
  // (recognised, not ok) is good enough to approach on, never to dock on.
  std::array<int, 2> spheres_seen{0, 0};
  std::array<std::array<double, 3>, 2> sphere_scores{};     // score(v, s) at this pose
  std::array<std::array<double, 3>, 2> sphere_ring_hits{};  // each ring's share on colour
  // Improved mode: the pose was refined on the blobs' centroids (all spheres' blobs agree with one
  // rigid marker within the refiner's residual gate), with an error bound from that fit: 3 sigma
  // of the centroids' (whose shading bias the scatter understates), 99 % of the rims' where they
  // fit sharply (below).
  // NaN bounds when not refined (faithful mode: the fitness alone, no bound).
  bool refined = false;
  double refine_rms_px = std::numeric_limits<double>::quiet_NaN();
  double error_bound_m = std::numeric_limits<double>::quiet_NaN();
  double error_bound_deg = std::numeric_limits<double>::quiet_NaN();
  // Improved mode: then refined on the spheres' visible rims, which a partial view still shows
  // truly; per view and sphere the fraction of the predicted rim the images confirm.
  bool rim_refined = false;
  double rim_rms_px = std::numeric_limits<double>::quiet_NaN();
  std::array<std::array<double, 3>, 2> rim_support{};
  // Improved mode: the rims' fit whether or not it was taken (a partial view's is not: a hidden
  // sphere's rim is not there to confirm it), when it fit sharply (rim_sharp_rms_px). The spheres
  // whose rims it confirms in both views are placed as truly as the rims show them, which is how
  // the tracker rides through a hidden sphere.
  bool rims_sharp = false;
  Eigen::Isometry3d T_cl_marker_rims = Eigen::Isometry3d::Identity();
  // Improved mode: the centroids or the rims fit the triangle's other tilt about the line of sight
  // as well (estimator/tilt_ambiguity), further off than the fit's own bound, which then reaches
  // to that pose.
  bool mirror_fits = false;
  // Improved mode: this estimate came from the second look, the pair segmented again white-
  // balanced to the water's cast (EstimatorParams::water_retry), after the first was not ok.
  bool water_corrected = false;
  // Improved mode: this estimate came from the third look, the pair median-filtered
  // (EstimatorParams::denoise_retry_px), after the first two were not ok.
  bool denoised = false;
  // Improved mode: this frame's GA started from a fresh population, the last
  // EstimatorParams::ga_restart_frames frames having had no refinement accepted.
  bool ga_restarted = false;
  bool ok = false;
  NotOkReason not_ok_reason = NotOkReason::none;
  int generations = 0;  // generations run this frame
  std::chrono::nanoseconds compute_time{0};
};

// How far a frame looks past a first look that is not ok.
enum class Looks : std::uint8_t {
  all,  // the second look, then the third, until one is ok
  // For a caller that carries the pose through a frame the first look declines (the tracker):
  // while the first look has been seeing the marker (ok within
  // EstimatorParams::retry_memory_frames), a frame it declines for a partial view or no marker
  // at all gets the second and third looks only if they have been earning their keep: after
  // EstimatorParams::retry_misses tries in a row that none made ok, one try per
  // EstimatorParams::retry_pause_frames such frames. Those frames mostly have a bar or a hidden
  // sphere in them, which is not what the looks are for, and the looks were most of a frame's
  // time behind the sim's bars; a loose fit (smear, noise) always gets them.
  as_needed,
};

class PoseEstimator {
 public:
  // Throws std::invalid_argument when the params are inconsistent (EstimatorParams::validate).
  PoseEstimator(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                const EstimatorParams& params, std::uint64_t seed);
  PoseEstimator(const PoseEstimator&) = delete;
  PoseEstimator& operator=(const PoseEstimator&) = delete;

  // One frame: segment() then estimate(). Allocates nothing after construction.
  PoseEstimate update(const cv::Mat& left_bgr, const cv::Mat& right_bgr, Looks looks = Looks::all);
  // The two stages of a frame, timed apart by the tick. segment() labels both images; false
  // (and the next estimate() says why) when an image's size or type disagrees with the rig.
  // The images are referenced, not copied: they must outlive the estimate() that follows.
  bool segment(const cv::Mat& left_bgr, const cv::Mat& right_bgr);
  // Evolves the carried-over population on the last segmented pair within the frame budget,
  // which counts from the start of segment(); then, if that is not ok and water_retry is on,
  // once more on the pair segmented in the water's colour, and if that is not ok either and
  // denoise_retry_px is on, once more on the median-filtered pair.
  // Looks::as_needed: the second and third only where the scene has needed them (below).
  PoseEstimate estimate(Looks looks = Looks::all);
  void reset();  // fresh random population (marker lost / new search)

  const EstimatorParams& params() const { return params_; }
  const cv::Mat& labels(int view) const { return labels_[view]; }
  const MarkerFitness& fitness() const { return fitness_; }
  const GeneCodec& codec() const { return codec_; }
  long fitness_evaluations() const { return ga_.evaluations() + extra_evaluations_; }

 private:
  hal::StereoRig rig_;
  hal::MarkerModel marker_;
  EstimatorParams params_;
  bool measured_bound_ = false;  // params_.rim_bound is "measured"
  HueSegmenter segmenter_;
  std::optional<HueSegmenter> water_segmenter_;  // improved mode with water_retry > 0
  GeneCodec codec_;
  MarkerFitness fitness_;
  Rmga ga_;
  BlobSeeder blobs_;
  PoseRefiner refiner_;
  RimRefiner rim_;
  // Whether a first look that was not ok gets the second and third (always, with Looks::all).
  bool later_looks_needed(const PoseEstimate& first, Looks looks) const;
  // Looks::as_needed's memory, from the frame's estimate and whether the later looks were tried.
  void remember_looks(const PoseEstimate& e, bool later_tried);
  // The second look, then the third, after a first that was not ok.
  PoseEstimate later_looks(PoseEstimate first);
  enum class Look { first, water, denoised };  // which labels estimate_on_labels sees
  PoseEstimate estimate_on_labels(Look look);
  // When T_mirror, the triangle's other tilt, fits the data as well as T and is recognised, the
  // estimate's error bound reaches to it.
  void widen_to_mirror(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_mirror,
                       PoseEstimate& estimate);
  // The least rim support of any sphere in either view.
  double weakest_support(const RimFit& fit) const;

  cv::Mat labels_[2];
  cv::Mat denoised_[2];  // the third look's median-filtered pair, allocated at construction
  const cv::Mat* images_[2] = {nullptr, nullptr};  // the last segment()'s, for the second look
  long extra_evaluations_ = 0;
  int frames_unconfirmed_ = 0;  // frames in a row with no refinement accepted
  // Looks::as_needed's memory (saturating counts).
  static constexpr int kNever = 1 << 30;
  int frames_since_first_ok_ = kNever;
  int retry_misses_ = 0;          // tries of the later looks in a row that none made ok
  int declined_since_retry_ = 0;  // declined frames since the later looks were last tried
  std::chrono::steady_clock::time_point frame_start_{};
  const char* input_error_ = nullptr;
};

}  // namespace rovctl::estimator
