// One estimator frame. The faithful mode is the paper's loop; the improved mode adds, each
// switchable: blob seeding during and elite refinement after evolution.
#include "estimator/pose_estimator.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "estimator/error_bound.hpp"
#include "estimator/motion_smear.hpp"
#include "estimator/tilt_ambiguity.hpp"
#include "hal/model/pose.hpp"

namespace rovctl::estimator {
namespace {

const EstimatorParams& validated(const EstimatorParams& p) {
  p.validate();
  return p;
}

// Null when the image is what the calibration says; else why not.
const char* image_error(const cv::Mat& image, const hal::CameraModel& camera) {
  if (image.type() != CV_8UC3) return "image is not 8-bit colour";
  if (image.cols != camera.width_px || image.rows != camera.height_px) {
    return "image size differs from the calibration";
  }
  return nullptr;
}

// A rim fit's error bound. Measured (rim_bound measured): on the first look the rims' own misfit
// sets it: a rim off in radius or centre shows it. The water-corrected look moves every rim's edge
// alike (backscatter taken off), a bias its misfit cannot show, so it counts independent points and
// keeps the trace's 3 sigma, as the centroids do. The denoised look takes the wider of the two: a
// median rounds a small sphere off alike (the count's part), and in turbid water at 1.35 m its
// rims fitted 10 deg off with a misfit that said 5-10 deg where 3 sigma said 2 (the measured part).
// Counted: the quantile only for sharp rims off the first two looks. A 5 px median rounds a 14 px
// sphere's rim off by a bias its covariance does not know (a noise + JPEG pair fitted 39 deg off
// inside a 3.5 deg quantile), and so do JPEG's chroma blocks on a rim that fits loosely.
ErrorBound rim_bound(const EstimatorParams& p, bool measured_bound, bool first_look, bool denoised,
                     const RimFit& fit) {
  if (measured_bound) {
    const ErrorBound counted = error_bound_3_sigma(fit.covariance);
    if (!fit.measured) return counted;
    const ErrorBound measured = error_bound_99(fit.covariance_measured);
    if (first_look) return measured;
    if (!denoised) return counted;
    return ErrorBound{std::max(measured.m, counted.m), std::max(measured.deg, counted.deg)};
  }
  const bool sharp = !denoised && fit.rms_px <= p.rim_quantile_rms_px;
  return sharp ? error_bound_99(fit.covariance) : error_bound_3_sigma(fit.covariance);
}

// How far a bound is over the ok limits (1: at the limit).
double over_ok_limits(const ErrorBound& bound, const EstimatorParams& p) {
  return std::max(bound.m * 1000.0 / p.ok_bound_mm, bound.deg / p.ok_bound_deg);
}

}  // namespace

const char* to_string(NotOkReason reason) {
  switch (reason) {
    case NotOkReason::none:
      return "none";
    case NotOkReason::partial_view:
      return "partial_view";
    case NotOkReason::not_refined:
      return "not_refined";
    case NotOkReason::bound_over_limit:
      return "bound_over_limit";
    case NotOkReason::unconfirmed:
      return "unconfirmed";
  }
  return "unknown";
}

bool from_string(std::string_view text, NotOkReason& reason) {
  for (const NotOkReason r :
       {NotOkReason::none, NotOkReason::partial_view, NotOkReason::not_refined,
        NotOkReason::bound_over_limit, NotOkReason::unconfirmed}) {
    if (text == to_string(r)) {
      reason = r;
      return true;
    }
  }
  return false;
}

PoseEstimator::PoseEstimator(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                             const EstimatorParams& params, std::uint64_t seed)
    : rig_(rig),
      marker_(marker),
      params_(validated(params)),
      measured_bound_(params_.rim_bound == "measured"),
      segmenter_(marker, params_.improved() ? params_.water_correction : 0.0),
      codec_(params_.search, params_.ga_reading().coding == "gray"),
      fitness_(rig, marker, params_.fitness),
      ga_(params_.ga, codec_, fitness_, seed, params_.ga_reading()),
      blobs_(rig, marker),
      refiner_(rig, marker),
      rim_(rig, marker,
           measured_bound_ ? RimRefiner::Misfit::measured : RimRefiner::Misfit::ignored) {
  if (params_.improved() && params_.water_retry > 0.0) {
    water_segmenter_.emplace(marker, params_.water_retry);
  }
  labels_[0].create(rig.left.height_px, rig.left.width_px, CV_8UC1);
  labels_[1].create(rig.right.height_px, rig.right.width_px, CV_8UC1);
  if (params_.improved() && params_.denoise_retry_px > 0) {
    denoised_[0].create(rig.left.height_px, rig.left.width_px, CV_8UC3);
    denoised_[1].create(rig.right.height_px, rig.right.width_px, CV_8UC3);
  }
  labels_[0].setTo(0);
  labels_[1].setTo(0);
  fitness_.set_labels(labels_[0], labels_[1]);
  if (params_.far_field_fitness) fitness_.enable_far_field();
  if (params_.improved()) fitness_.enable_border_occluder();
}

void PoseEstimator::reset() {
  ga_.randomise();
  frames_unconfirmed_ = 0;
}

PoseEstimate PoseEstimator::update(const cv::Mat& left_bgr, const cv::Mat& right_bgr, Looks looks) {
  segment(left_bgr, right_bgr);
  return estimate(looks);
}

bool PoseEstimator::segment(const cv::Mat& left_bgr, const cv::Mat& right_bgr) {
  frame_start_ = std::chrono::steady_clock::now();
  input_error_ = image_error(left_bgr, rig_.left);
  if (input_error_ == nullptr) input_error_ = image_error(right_bgr, rig_.right);
  if (input_error_ != nullptr) return false;
  images_[0] = &left_bgr;
  images_[1] = &right_bgr;
  segmenter_.segment(left_bgr, labels_[0]);
  segmenter_.segment(right_bgr, labels_[1]);
  fitness_.update_far_field();
  return true;
}

PoseEstimate PoseEstimator::estimate(Looks looks) {
  if (input_error_ != nullptr) return estimate_on_labels(Look::first);
  // A population settled off the marker (beside a sphere cut by the image edge, 30-80 deg off)
  // is where neither refinement can start from, and elitism keeps it there: draw it afresh.
  const bool restart = params_.improved() && params_.ga_restart_frames > 0 &&
                       frames_unconfirmed_ >= params_.ga_restart_frames;
  if (restart) {
    ga_.randomise();
    frames_unconfirmed_ = 0;
  }
  PoseEstimate first = estimate_on_labels(Look::first);
  const bool later = !first.ok && later_looks_needed(first, looks);
  PoseEstimate e = later ? later_looks(first) : first;
  remember_looks(e, later);
  e.ga_restarted = restart;
  frames_unconfirmed_ = e.refined || e.rim_refined ? 0 : frames_unconfirmed_ + 1;
  return e;
}

bool PoseEstimator::later_looks_needed(const PoseEstimate& first, Looks looks) const {
  if (looks == Looks::all) return true;
  // Skipped for a sphere or the marker gone from a first look that has been seeing it, while
  // the later looks missed their last retry_misses tries, but tried again every
  // retry_pause_frames such frames: what the water needs can change, and a look never tried
  // would never be found needed again. A loose fit (smear, noise) is what they are for.
  const bool seeing = frames_since_first_ok_ < params_.retry_memory_frames;
  const bool hidden = !first.recognised || first.not_ok_reason == NotOkReason::partial_view;
  return !(seeing && hidden && retry_misses_ >= params_.retry_misses &&
           declined_since_retry_ < params_.retry_pause_frames);
}

void PoseEstimator::remember_looks(const PoseEstimate& e, bool later_tried) {
  const bool first_ok = e.ok && !e.water_corrected && !e.denoised;
  frames_since_first_ok_ = first_ok ? 0 : std::min(frames_since_first_ok_ + 1, kNever);
  if (later_tried) {
    declined_since_retry_ = 0;
    retry_misses_ = e.ok ? 0 : std::min(retry_misses_ + 1, kNever);
  } else if (!e.ok) {
    declined_since_retry_ = std::min(declined_since_retry_ + 1, kNever);
  }
}

PoseEstimate PoseEstimator::later_looks(PoseEstimate first) {
  int generations = first.generations;
  if (water_segmenter_) {
    // Water takes red first: far out in coastal water the red sphere is a greyish brown under
    // the hue windows. Balanced to the scene's cast it is red again, but the same balance moves
    // clear water's colours, so it is a second look for a frame the first could not vouch for,
    // and its estimate is taken only if it earns its own ok.
    water_segmenter_->segment(*images_[0], labels_[0]);
    water_segmenter_->segment(*images_[1], labels_[1]);
    fitness_.update_far_field();
    PoseEstimate second = estimate_on_labels(Look::water);
    if (second.ok) {
      second.water_corrected = true;
      second.generations += generations;
      return second;
    }
    generations += second.generations;
    first.compute_time = second.compute_time;
  }
  if (!params_.improved() || params_.denoise_retry_px <= 0) return first;
  // Sensor noise and JPEG's blocks break a small sphere's rim into specks: its rim fit then
  // fails the sharpness gate and the centroids' bound is loose, though the pose is right. A
  // median keeps edges where they are, so the rims it leaves can be fitted.
  for (int v = 0; v < 2; ++v) {
    cv::medianBlur(*images_[v], denoised_[v], params_.denoise_retry_px);
    segmenter_.segment(denoised_[v], labels_[v]);
  }
  fitness_.update_far_field();
  PoseEstimate third = estimate_on_labels(Look::denoised);
  if (!third.ok) {
    first.compute_time = third.compute_time;
    return first;
  }
  third.denoised = true;
  third.generations += generations;
  return third;
}

void PoseEstimator::widen_to_mirror(const Eigen::Isometry3d& T, const Eigen::Isometry3d& T_mirror,
                                    PoseEstimate& estimate) {
  ++extra_evaluations_;
  if (fitness_.evaluate_swept(T_mirror) < params_.recognition_threshold) return;
  const double apart_deg = hal::rotation_angle_rad(T.linear(), T_mirror.linear()) * 180.0 / M_PI;
  const double apart_m = (T.translation() - T_mirror.translation()).norm();
  if (apart_deg <= estimate.error_bound_deg && apart_m <= estimate.error_bound_m) return;
  estimate.error_bound_deg = std::max(estimate.error_bound_deg, apart_deg);
  estimate.error_bound_m = std::max(estimate.error_bound_m, apart_m);
  estimate.mirror_fits = true;
}

double PoseEstimator::weakest_support(const RimFit& fit) const {
  double weakest = 1.0;
  for (int v = 0; v < 2; ++v) {
    for (std::size_t s = 0; s < fitness_.sphere_count() && s < 3; ++s) {
      weakest = std::min(weakest, fit.support[v][s]);
    }
  }
  return weakest;
}

PoseEstimate PoseEstimator::estimate_on_labels(Look look) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = frame_start_;
  if (input_error_ != nullptr) {
    PoseEstimate none;
    none.input_error = input_error_;
    none.T_cl_marker = codec_.decode(ga_.best().gene);
    none.compute_time = Clock::now() - start;
    return none;
  }
  const bool improved = params_.improved();
  const bool use_blobs = improved && (params_.blob_seeding || params_.refine_elite);
  if (use_blobs) {
    blobs_.find(0, labels_[0]);
    blobs_.find(1, labels_[1]);
    // The fitness sweeps a smeared sphere along the view's smear (motion blur); a blob the
    // border cuts measures none.
    for (int v = 0; v < 2; ++v) {
      std::array<BlobSmear, hal::kColourClassCount> smears{};
      for (int c = 1; c < hal::kColourClassCount; ++c) {
        const Blob& b = blobs_.blobs()[v][c];
        if (b.valid && !b.touches_border) smears[c] = {b.smear_u_px, b.smear_v_px, b.width_px};
      }
      fitness_.set_smear(v, shared_smear(smears));
    }
  }
  ga_.evaluate_all();
  if (improved && params_.blob_seeding) {
    Eigen::Isometry3d T_seed;
    if (blobs_.seed(T_seed)) {
      if (params_.refine_elite) refiner_.refine(blobs_.blobs(), T_seed);
      Gene gene;
      codec_.encode(T_seed, gene);
      ga_.insert(gene, fitness_.search_score(codec_.decode(gene)));
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
  if (fitness_.far_field() || fitness_.smeared()) {
    // The GA ranked by the search score, or by the disc where the swept model judges: the
    // estimate reports the paper's fitness, swept where the view is smeared.
    estimate.fitness = fitness_.evaluate_swept(estimate.T_cl_marker);
    ++extra_evaluations_;
  }
  if (improved && params_.refine_elite) {
    // The elite refined on the blob centroids is continuous (not 12-bit) and sub-pixel; it is
    // taken unless it scores clearly worse, which means the blobs were not the marker.
    Eigen::Isometry3d T = estimate.T_cl_marker;
    RefineReport report;
    if (refiner_.refine(blobs_.blobs(), T, 1.5, &report)) {
      const double f = fitness_.evaluate_swept(T);
      ++extra_evaluations_;
      if (f >= estimate.fitness - 0.05) {
        estimate.T_cl_marker = T;
        estimate.fitness = f;
        estimate.refined = true;
        estimate.refine_rms_px = report.rms_px;
        // The centroids' scatter understates their shading bias: the trace's 3 sigma, not a
        // quantile. Their fit has the triangle's tilt ambiguity as the rims' does (below).
        // Measured: the centroids' noise over the coordinates the pose leaves free.
        const double scale = measured_bound_ ? report.sigma_free_px / report.sigma_px : 1.0;
        const ErrorBound bound = error_bound_3_sigma(scale * scale * report.covariance);
        estimate.error_bound_deg = bound.deg;
        estimate.error_bound_m = bound.m;
        Eigen::Isometry3d T_mirror = mirrored_tilt(T, marker_);
        RefineReport mirror;
        if (refiner_.refine(blobs_.blobs(), T_mirror, 1.5, &mirror)) {
          const double sigma = measured_bound_ ? report.sigma_free_px : report.sigma_px;
          const double sigma2 = sigma * sigma;
          if (fits_as_well(report.centroids * report.rms_px * report.rms_px / sigma2,
                           mirror.centroids * mirror.rms_px * mirror.rms_px / sigma2)) {
            widen_to_mirror(T, T_mirror, estimate);
          }
        }
        Gene gene;
        codec_.encode(T, gene);
        ga_.insert(gene, fitness_.search_score(codec_.decode(gene)));
        ++extra_evaluations_;
      }
    }
  }
  if (improved && params_.refine_elite && estimate.fitness >= params_.recognition_threshold) {
    // Then on the rims, from wherever the centroids (or the GA) left it: a hidden or shaded part
    // of a sphere moves its centroid, not the rest of its rim.
    Eigen::Isometry3d T = estimate.T_cl_marker;
    RimFit fit;
    if (rim_.refine(labels_[0], labels_[1], T, &fit)) {
      // Trusted only when every sphere's rim is confirmed in both views over enough of its
      // length: a blurred or faded edge is no rim, and then the centroids' pose stands.
      const double weakest = weakest_support(fit);
      const double f = fitness_.evaluate_swept(T);
      ++extra_evaluations_;
      // A sphere whose colour spills onto its ring around the fitted rims is smeared: its rims
      // lean the pose along the smear even when they fit well enough to pass the rms.
      MarkerFitness::SphereScores at_rims, ring_at_rims;
      fitness_.disc_sphere_scores(T, at_rims, &ring_at_rims);
      double spill = 0.0;
      for (const auto& view : ring_at_rims) {
        for (double r : view) spill = std::max(spill, r);
      }
      const ErrorBound bound =
          rim_bound(params_, measured_bound_, look == Look::first, look == Look::denoised, fit);
      // Measured: a rim fit looser than sharp (JPEG blocks, a faded edge) replaces the centroids'
      // pose only where it knows the pose better than they do.
      const bool sharp = fit.rms_px <= params_.rim_sharp_rms_px;
      const double loosest = measured_bound_ ? params_.rim_loose_rms_px : params_.rim_sharp_rms_px;
      const auto known_better = [&] {
        const ErrorBound centroids{estimate.error_bound_m, estimate.error_bound_deg};
        return !estimate.refined || !std::isfinite(centroids.m) || !std::isfinite(centroids.deg) ||
               over_ok_limits(bound, params_) < over_ok_limits(centroids, params_);
      };
      if (weakest >= params_.rim_support && fit.rms_px <= loosest && (sharp || known_better()) &&
          spill <= params_.rim_ring_max && f >= params_.recognition_threshold &&
          f >= estimate.fitness - 0.15) {
        estimate.T_cl_marker = T;
        estimate.fitness = f;
        estimate.rim_refined = true;
        estimate.rim_rms_px = fit.rms_px;
        estimate.error_bound_deg = bound.deg;
        estimate.error_bound_m = bound.m;
        estimate.mirror_fits = false;
        // The covariance is local: it cannot see the triangle's other tilt about the line of
        // sight, which at range the rims may fit as well (a flatter, or steeper, marker).
        Eigen::Isometry3d T_mirror = mirrored_tilt(T, marker_);
        RimFit mirror;
        if (rim_.refine(labels_[0], labels_[1], T_mirror, &mirror) &&
            weakest_support(mirror) >= params_.rim_support && mirror.rms_px <= loosest) {
          const double sigma2 = std::pow(std::max(fit.rms_px, RimRefiner::kEdgeNoisePx), 2);
          if (fits_as_well(fit.independent_points * fit.rms_px * fit.rms_px / sigma2,
                           mirror.independent_points * mirror.rms_px * mirror.rms_px / sigma2)) {
            widen_to_mirror(T, T_mirror, estimate);
          }
        }
      }
      estimate.rim_support = fit.support;
      estimate.rims_sharp = fit.rms_px <= params_.rim_sharp_rms_px;
      estimate.T_cl_marker_rims = T;
    }
  }
  estimate.recognised = estimate.fitness >= params_.recognition_threshold;
  MarkerFitness::SphereScores& scores = estimate.sphere_scores;
  fitness_.sphere_scores(estimate.T_cl_marker, scores, &estimate.sphere_ring_hits);
  const int spheres = static_cast<int>(fitness_.sphere_count());
  for (int v = 0; v < 2; ++v) {
    for (int s = 0; s < spheres && s < 3; ++s) {
      // Whole and in colour, or partly hidden with its visible rim where the pose puts it.
      const bool whole = scores[v][s] >= params_.sphere_support;
      const double ring = estimate.sphere_ring_hits[v][s];
      const bool smeared = improved && scores[v][s] + ring >= params_.smear_inner_min &&
                           ring <= params_.smear_ring_max;
      const bool rim = estimate.rim_refined && estimate.rim_support[v][s] >= params_.rim_support &&
                       scores[v][s] > 0.0;
      if (whole || rim || smeared) ++estimate.spheres_seen[v];
    }
  }
  // Improved mode also asks the geometry: one rigid marker through the blobs' centroids or the
  // spheres' rims (a refinement accepted).
  // And the fit must be sure enough: a blurred or noisy rim fits loosely, and its bound says so.
  const bool refined = estimate.refined || estimate.rim_refined;
  const bool bounded = estimate.error_bound_m * 1000.0 <= params_.ok_bound_mm &&
                       estimate.error_bound_deg <= params_.ok_bound_deg;
  const bool fit_needed = improved && params_.refine_elite;
  if (!estimate.recognised) {
    estimate.not_ok_reason = NotOkReason::none;
  } else if (estimate.spheres_seen[0] != spheres || estimate.spheres_seen[1] != spheres) {
    estimate.not_ok_reason = NotOkReason::partial_view;
  } else if (fit_needed && !refined) {
    estimate.not_ok_reason = NotOkReason::not_refined;
  } else if (fit_needed && !bounded) {
    estimate.not_ok_reason = NotOkReason::bound_over_limit;
  } else {
    estimate.not_ok_reason = NotOkReason::none;
  }
  estimate.ok = estimate.recognised && estimate.not_ok_reason == NotOkReason::none;
  estimate.compute_time = Clock::now() - start;
  return estimate;
}

}  // namespace rovctl::estimator
