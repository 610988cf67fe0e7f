// Improvement beyond the paper: refines a pose on the spheres' visible rims in the label images.
// A rim point sits where the sphere truly ends; a centroid moves when part of a sphere is hidden,
// shaded or cut by the image border, so the rims are what a partial view can still be trusted on.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

// What the rims say about a refined pose.
struct RimFit {
  int inliers = 0;      // rim points within the inlier band at the end
  double rms_px = 0.0;  // of the inliers, radial
  // Per view and sphere (marker order): the fraction of the rays cast around the predicted
  // silhouette's part inside the image whose colour edge lies on it. A whole sphere ~1; half
  // hidden ~0.5; absent, or less than kMinVisibleRays of its rim inside the image, 0.
  std::array<std::array<double, 3>, 2> support{};
  // The independent points the covariance counts: kIndependentPerSilhouette per rim seen.
  double independent_points = 0.0;
  // Covariance of the pose's error, rotation vector (rad) then translation (m).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  // The same with the rims' own misfit in place of the count of independent points: each
  // silhouette's residuals resolved into a radius (their mean) and a centre (their first
  // harmonic), these components' variances measured over the silhouettes seen and carried through
  // the fit (a sandwich, A^-1 M A^-1). A rim off in radius or centre widens it; white noise along
  // a rim averages out of it. Set (`measured`) when kMinMeasuredSilhouettes rims had
  // kMinVisibleRays inliers each, by a refiner built to measure it. A sphere's centre moved alike
  // in both views leaves no misfit, so that is credited kSharedCentreBiasPx.
  bool measured = false;
  Eigen::Matrix<double, 6, 6> covariance_measured = Eigen::Matrix<double, 6, 6>::Zero();
};

class RimRefiner {
 public:
  // Whether a fit also measures RimFit::covariance_measured (a pass over its rim points and a
  // sandwich), which only the measured error bound reads.
  enum class Misfit { ignored, measured };

  RimRefiner(const hal::StereoRig& rig, const hal::MarkerModel& marker,
             Misfit misfit = Misfit::ignored);

  // Refines T_cl_marker in place on the label images (CV_8UC1 of ColourClass, each its camera's
  // size). False (pose unchanged) when too few rim points agree or the fit does not converge.
  // Allocates nothing.
  bool refine(const cv::Mat& left_labels, const cv::Mat& right_labels,
              Eigen::Isometry3d& T_cl_marker, RimFit* fit = nullptr) const;

  static constexpr int kRays = 48;     // per sphere and view
  static constexpr int kPolygon = 32;  // vertices of a predicted silhouette
  static constexpr double kInlierPx = 1.5;
  // The image border is a known occluder: a sphere cut by it is judged on the part of its rim
  // inside the image, if that is at least a quarter of the rim (90 deg of arc).
  static constexpr int kMinVisibleRays = kRays / 4;
  static constexpr double kBorderMarginPx = 2.0;  // a rim closer to the border shows no edge
  // Neighbouring rim points share pixels and the segmenter's bias, so they are not independent:
  // the covariance counts about this many independent points per silhouette.
  static constexpr double kIndependentPerSilhouette = 8.0;
  static constexpr double kEdgeNoisePx = 0.3;  // the least noise a rim point is credited with
  // The measured covariance: the silhouettes it needs, the least misfit a component is credited
  // with, and the factor on the measured variances, which a handful of silhouettes estimate.
  static constexpr int kMinMeasuredSilhouettes = 4;
  static constexpr double kMisfitFloorPx = 0.05;
  static constexpr double kMisfitInflation = 1.5;
  // The least bias credited to a sphere's centre moved alike in both views: the side of a sphere
  // away from the light, or a colour fading into the water, ends its silhouette early in both
  // views. In murky water the measured covariance's rotation bound without it was 0.7-1.0 deg at
  // 0.8 m against errors of 0.8-1.3 deg; 0.15 px covers them and keeps the shipped camera's
  // 1.0-1.5 m pairs under the ok limits.
  static constexpr double kSharedCentreBiasPx = 0.15;

 private:
  static constexpr int kSpheres = 3;
  static constexpr int kMaxPoints = 2 * kSpheres * kRays;

  // A predicted silhouette: its centre and its outline about it, counter-clockwise from the
  // vertex of smallest angle.
  struct Silhouette {
    bool valid = false;
    Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
    // Monotonic in the vertex's angle about the centre (see angle_order in the .cpp), not radians.
    std::array<double, kPolygon> pseudo_angle{};
    std::array<Eigen::Vector2d, kPolygon> offset_px{};
    // Distance from the centre to the outline along the direction d (not normalised). hint: the
    // outline segment the last direction crossed (0..kPolygon), tried first; updated.
    double radius_along(const Eigen::Vector2d& d, int& hint) const;
  };
  using Silhouettes = std::array<std::array<Silhouette, kSpheres>, 2>;

  struct EdgePoint {
    Eigen::Vector2d uv_px;
    std::uint8_t view = 0, sphere = 0;
  };
  struct Edges {
    std::array<EdgePoint, kMaxPoints> points;
    int count = 0;
    std::array<std::array<int, kSpheres + 1>, 2> first{};     // [view][sphere]: points' range
    std::array<std::array<int, kSpheres>, 2> visible_rays{};  // predicted rim inside the image
  };
  using Residuals = Eigen::Matrix<double, kMaxPoints, 1>;
  using Jacobian = Eigen::Matrix<double, kMaxPoints, 6>;
  using Vector7 = Eigen::Matrix<double, 7, 1>;  // (rotation vector, translation, edge offset)
  using Matrix7 = Eigen::Matrix<double, 7, 7>;

  // The sphere's centre in one camera's frame at pose T.
  Eigen::Vector3d centre_in_view(const Eigen::Isometry3d& T, int view, int sphere) const;
  bool predict_one(int view, int sphere, const Eigen::Vector3d& centre_cam_m,
                   Silhouette& out) const;
  void predict(const Eigen::Isometry3d& T, Silhouettes& out) const;
  void find_edges(const cv::Mat* labels[2], const Silhouettes& predicted, Edges& edges) const;
  // Signed radial distance of one silhouette's edge points from it (outside > 0).
  void silhouette_residuals(const Edges& edges, int view, int sphere, const Silhouette& sil,
                            Residuals& r) const;
  bool residuals(const Edges& edges, const Eigen::Isometry3d& T, Residuals& r) const;
  // d residual / d (rotation vector, translation), through each sphere's centre: a silhouette
  // depends on its sphere's centre alone, so three differences per silhouette suffice, each from
  // rb, residuals() at T.
  bool jacobian(const Edges& edges, const Eigen::Isometry3d& T, const Residuals& rb,
                Jacobian& J) const;
  // RimFit::covariance_measured of the final fit: the silhouettes it was seen from, J and the
  // weights w at it, r its residuals after the offset, A its normal equations (with the offset's
  // prior), white_px the noise of one rim point. False when too few silhouettes measure it.
  bool measured_covariance(const Edges& edges, const Silhouettes& sil, const Jacobian& J,
                           const Residuals& r, const Residuals& w, double white_px,
                           const Matrix7& A, Eigen::Matrix<double, 6, 6>& covariance) const;

  hal::StereoRig rig_;
  hal::MarkerModel marker_;
  int spheres_ = 0;
  Misfit misfit_ = Misfit::ignored;
};

}  // namespace rovctl::estimator
