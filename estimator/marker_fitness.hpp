// The RM-GA's fitness: how well the three-sphere model at a candidate pose matches the segmented
// left and right images (the paper's Sec. 2.2 and Fig. 4), with lens distortion.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "estimator/estimator_params.hpp"
#include "estimator/motion_smear.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

// For each view v in {left, right} and each sphere s (S spheres), project the sphere with the
// candidate pose; r is its projected radius. Sample N_in points inside the disc (within
// inner_radius_fraction * r) and N_out points on a ring at outer_radius_fraction * r around it,
// each mapped through the local Jacobian of the distorted projection. With c_s the sphere's colour
// class and L_v(p) the label of pixel p (points outside the image are `none`):
//
//   score(v, s) = #{ i : L_v(p_i) = c_s } / N_in  -  #{ j : L_v(q_j) = c_s } / N_out
//   F = max(0, sum_{v, s} score(v, s) / (2 S))                      (F in [0, 1])
//
// A sphere behind a camera scores 0 in that view. The true pose scores ~1 (all inner points on
// the sphere's colour, none of the ring); a pose one radius off scores ~0.5.
class MarkerFitness {
 public:
  MarkerFitness(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                const FitnessParams& params);

  // The current frame's label images (CV_8UC1, each its camera's size), referenced, not copied:
  // they must outlive the evaluations.
  void set_labels(const cv::Mat& left_labels, const cv::Mat& right_labels);

  // The disc model: what the GA ranks by (search_score).
  double evaluate(const Eigen::Isometry3d& T_cl_marker) const;
  // The same with smeared spheres swept (set_smear); evaluate() where nothing is smeared.
  double evaluate_swept(const Eigen::Isometry3d& T_cl_marker) const;

  // Not in the paper. The paper's F is 0 on about 90 % of the search volume (no sample point on
  // a sphere's colour), which leaves the GA blind there. The far field orders those poses: per
  // view and sphere, how near the projected centre lies to the nearest pixels of the sphere's
  // colour, on a coarse grid (FitnessParams::far_field_cell_px), 1 on them falling linearly to 0
  // at far_field_reach_px. Where every centre lies on its colour the far field is 1 and F alone
  // ranks; its weight (far_field_weight) sets how many pixels of centre distance one unit of F is
  // worth elsewhere (FitnessParams says why 50).
  // enable_far_field() allocates; update_far_field() rebuilds the grids from the current labels
  // (once per frame, after segmenting).
  void enable_far_field();
  // Improved mode: the image border is a known occluder, so a sphere's samples beyond it are
  // neither hits nor misses; a sphere is scored on its samples inside the image (at least a
  // quarter of them, else as the paper does). The truth then outscores poses that pull a sphere
  // cut by the border back into the image.
  void enable_border_occluder() { border_occluder_ = true; }
  void update_far_field();
  bool far_field() const { return far_field_; }
  double far_field_weight() const { return far_weight_; }
  // The mean nearness in [0, 1] over both views and all spheres (0 without the far field).
  double far_field_nearness(const Eigen::Isometry3d& T_cl_marker) const;
  // What the GA ranks by: evaluate(), plus far_field_weight * far_field_nearness() when the far
  // field is enabled.
  double search_score(const Eigen::Isometry3d& T_cl_marker) const;

  // score(v, s) of every sphere in both views at one pose (spheres in the marker's order; unused
  // entries 0): which spheres the images support, for the estimate's honesty, not the search.
  using SphereScores = std::array<std::array<double, 3>, 2>;
  // ring_hits, if given: the share of each ring's samples on the sphere's colour (score + ring
  // is the inner disc's share), which tells a smear from a pose that is off.
  void sphere_scores(const Eigen::Isometry3d& T_cl_marker, SphereScores& scores,
                     SphereScores* ring_hits = nullptr) const;
  std::size_t sphere_count() const { return spheres_.size(); }

  // Improved mode, motion blur: a sphere that moved during the exposure is a disc swept along a
  // line, and the disc model scores its true pose low (the smear spills onto the ring) and a pose
  // at one end of the smear as high. Given the view's smear (shared_smear of its blobs), the swept
  // model sweeps each sphere's samples along it: the inner ones over the smear's core, the ring's
  // halves pushed out to its ends. Only where the smear is at least kSmearMinLength of the
  // sphere's diameter at the candidate pose long and its blobs kSmearMinWidth to kSmearMaxWidth of
  // it wide: a shaded or half-hidden sphere is elongated too, but narrower than the sphere, and a
  // sphere merged with something of its colour wider (a smeared one reads up to 1.2 diameters
  // across on the validation set and in the mock's render). It judges (the estimate's
  // fitness and sphere scores) and does not search: its core samples leave a plateau along the
  // smear that the GA wanders on (a blurred pair's population settled 35 deg off, scoring 0.948
  // above the truth's 0.885).
  void set_smear(int view, const SharedSmear& smear);
  bool smeared() const { return views_[0].smear.valid || views_[1].smear.valid; }
  // A sharp sphere off the optical axis images as an ellipse, which reads as a smear of up to 0.9
  // diameters at 45 deg off axis.
  static constexpr float kSmearMinLength = 1.0f;
  static constexpr float kSmearMinWidth = 0.7f;
  static constexpr float kSmearMaxWidth = 1.5f;
  // A smear is the sphere's colour diluted by the background in proportion to how long each
  // pixel saw the sphere: along the smear it fades over a diameter at each end, across it as the
  // sphere's chord shortens. A dim sphere (red at range) is labelled in the smear's core only, so
  // the inner samples keep to it: kSmearCore of the disc's inner radius across (there the colour
  // is 88 % of the middle's), kSmearReach of the smear's length either way along.
  static constexpr float kSmearCore = 0.6f;
  static constexpr float kSmearReach = 0.2f;
  // sphere_scores() with the disc unswept: whether a refined pose's rims sit inside a smear.
  void disc_sphere_scores(const Eigen::Isometry3d& T_cl_marker, SphereScores& scores,
                          SphereScores* ring_hits = nullptr) const;

 private:
  struct View {
    hal::CameraModel camera;
    Eigen::Matrix3d R_v_cl;
    Eigen::Vector3d t_v_cl;
    const std::uint8_t* labels = nullptr;
    int stride = 0;
    SharedSmear smear{};
  };
  struct Sphere {
    Eigen::Vector3d centre_marker_m;
    double radius_m;
    std::uint8_t colour;
  };
  double score_view(const View& view, const Eigen::Vector3d& centre_m, const Sphere& s,
                    double* ring_hits, bool swept) const;
  double evaluate_as(const Eigen::Isometry3d& T_cl_marker, bool swept) const;
  // Whether the view's smear fits a sphere imaged diameter_px across (the gate above).
  static bool sweeps(const SharedSmear& smear, float diameter_px);
  void scores_at(const Eigen::Isometry3d& T_cl_marker, SphereScores& scores,
                 SphereScores* ring_hits, bool swept) const;
  double nearness(int view, const Eigen::Vector3d& centre_m, std::uint8_t colour) const;

  std::array<View, 2> views_;
  std::vector<Sphere> spheres_;
  std::vector<float> inner_xy_, outer_xy_;  // offsets on the unit disc, interleaved x, y
  float inv_inner_ = 1.0f, inv_outer_ = 1.0f;
  // Far field: per view, per colour class, the distance in grid cells from each cell to the
  // nearest cell holding that colour (CV_32F), and the scratch mask it is computed from.
  bool far_field_ = false;
  bool border_occluder_ = false;
  double far_weight_ = 16.0;
  double far_reach_px_ = 800.0;
  int far_cell_px_ = 8;
  std::array<std::array<cv::Mat, 4>, 2> far_distance_cells_;
  std::array<std::array<cv::Mat, 4>, 2> far_mask_;
  std::array<std::array<cv::Mat, 4>, 2> far_count_;
};

}  // namespace rovctl::estimator
