// Fitness evaluation: per sphere and view, one distorted projection and its Jacobian, then the
// precomputed unit-disc sample offsets are mapped to pixels and looked up in the label image.
#include "estimator/marker_fitness.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace rovctl::estimator {

MarkerFitness::MarkerFitness(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                             const FitnessParams& params) {
  views_[0].camera = rig.left;
  views_[0].R_v_cl = Eigen::Matrix3d::Identity();
  views_[0].t_v_cl = Eigen::Vector3d::Zero();
  views_[1].camera = rig.right;
  views_[1].R_v_cl = rig.T_cr_cl.linear();
  views_[1].t_v_cl = rig.T_cr_cl.translation();
  for (const hal::MarkerSphere& s : marker.spheres) {
    spheres_.push_back({s.centre_marker_m, s.radius_m, static_cast<std::uint8_t>(s.colour)});
  }
  if (spheres_.empty()) throw std::invalid_argument("MarkerFitness: the marker has no spheres");
  // Inner points on a sunflower (Vogel) spiral: even cover of the disc for any count.
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < params.inner_points; ++k) {
    const double rho = params.inner_radius_fraction * std::sqrt((k + 0.5) / params.inner_points);
    inner_xy_.push_back(static_cast<float>(rho * std::cos(k * golden)));
    inner_xy_.push_back(static_cast<float>(rho * std::sin(k * golden)));
  }
  for (int k = 0; k < params.outer_points; ++k) {
    const double phi = 2.0 * M_PI * (k + 0.5) / params.outer_points;
    outer_xy_.push_back(static_cast<float>(params.outer_radius_fraction * std::cos(phi)));
    outer_xy_.push_back(static_cast<float>(params.outer_radius_fraction * std::sin(phi)));
  }
  far_weight_ = params.far_field_weight;
  far_reach_px_ = params.far_field_reach_px;
  far_cell_px_ = std::max(1, params.far_field_cell_px);
  inv_inner_ = 1.0f / params.inner_points;
  inv_outer_ = 1.0f / params.outer_points;
}

void MarkerFitness::set_labels(const cv::Mat& left, const cv::Mat& right) {
  const cv::Mat* m[2] = {&left, &right};
  for (int i = 0; i < 2; ++i) {
    const hal::CameraModel& c = views_[i].camera;
    if (m[i]->type() != CV_8UC1 || m[i]->cols != c.width_px || m[i]->rows != c.height_px) {
      throw std::invalid_argument("MarkerFitness: label image size differs from the calibration");
    }
    views_[i].labels = m[i]->ptr<std::uint8_t>(0);
    views_[i].stride = static_cast<int>(m[i]->step[0]);
  }
}

void MarkerFitness::set_smear(int view, const SharedSmear& smear) {
  if (view >= 0 && view < 2) views_[view].smear = smear;
}

bool MarkerFitness::sweeps(const SharedSmear& smear, float diameter_px) {
  return smear.min_length_px >= kSmearMinLength * diameter_px &&
         smear.min_width_px >= kSmearMinWidth * diameter_px &&
         smear.max_width_px <= kSmearMaxWidth * diameter_px;
}

double MarkerFitness::score_view(const View& view, const Eigen::Vector3d& c, const Sphere& s,
                                 double* ring_hits, bool swept) const {
  const double r = s.radius_m;
  const double d2 = c.squaredNorm();
  if (c.z() <= r * 1.01 || d2 <= r * r * 1.0201) return 0.0;
  const double x = c.x() / c.z(), y = c.y() / c.z();
  double u0, v0, ux, vx, uy, vy;
  constexpr double h = 1e-4;
  view.camera.distort(x, y, u0, v0);
  view.camera.distort(x + h, y, ux, vx);
  view.camera.distort(x, y + h, uy, vy);
  // Apparent radius on the normalised image plane: tan of the half-angle, stretched by 1/cos of
  // the angle off the optical axis.
  const double rn = r / std::sqrt(d2 - r * r) * std::sqrt(d2) / c.z();
  const double k = rn / h;
  const float a00 = static_cast<float>((ux - u0) * k), a01 = static_cast<float>((uy - u0) * k);
  const float a10 = static_cast<float>((vx - v0) * k), a11 = static_cast<float>((vy - v0) * k);
  // +0.5 so that truncation rounds to the nearest pixel centre.
  const float cu = static_cast<float>(u0) + 0.5f, cv = static_cast<float>(v0) + 0.5f;
  const unsigned w = static_cast<unsigned>(view.camera.width_px);
  const unsigned hgt = static_cast<unsigned>(view.camera.height_px);
  const std::uint8_t* labels = view.labels;
  const int stride = view.stride;
  const std::uint8_t colour = s.colour;
  int in_image = 0;  // of the samples
  // A sample at pixel (pu, pv), +0.5 included: on the sphere's colour, counted if in the image.
  auto hit_px = [&](float pu, float pv) -> int {
    if (!(pu >= 0.0f && pv >= 0.0f)) return 0;
    const unsigned iu = static_cast<unsigned>(pu), iv = static_cast<unsigned>(pv);
    if (iu >= w || iv >= hgt) return 0;
    ++in_image;
    return labels[static_cast<std::size_t>(iv) * stride + iu] == colour;
  };
  // A sample at (ox, oy) on the unit disc about the sphere's image.
  auto hit = [&](float ox, float oy) -> int {
    return hit_px(cu + a00 * ox + a01 * oy, cv + a10 * ox + a11 * oy);
  };
  // in_image holds the ring's samples inside the image when this is called.
  auto finish = [&](int inside, int inner_in_image, int outside) -> double {
    const int inner_total = static_cast<int>(inner_xy_.size() / 2);
    if (border_occluder_ && inner_in_image < inner_total && 4 * inner_in_image >= inner_total &&
        in_image > 0) {
      // Both rings scored on their samples inside the image only.
      if (ring_hits != nullptr) *ring_hits = static_cast<double>(outside) / in_image;
      return static_cast<double>(inside) / inner_in_image - static_cast<double>(outside) / in_image;
    }
    if (ring_hits != nullptr) *ring_hits = outside * inv_outer_;
    return inside * inv_inner_ - outside * inv_outer_;
  };
  int inside = 0, outside = 0;
  const SharedSmear& smear = view.smear;
  if (swept && smear.valid && sweeps(smear, 2.0f * std::sqrt(std::abs(a00 * a11 - a01 * a10)))) {
    // Inner samples spread over the smear (five stations along it), the ring's halves moved to
    // its two ends: the stadium a disc sweeps.
    const float bu = static_cast<float>(smear.u_px), bv = static_cast<float>(smear.v_px);
    const float* p = inner_xy_.data();
    for (std::size_t i = 0; i < inner_xy_.size(); i += 2) {
      const float t = kSmearReach * (0.5f * static_cast<float>((i / 2) % 5) - 1.0f);
      const float ox = kSmearCore * p[i], oy = kSmearCore * p[i + 1];
      inside += hit_px(cu + (a00 * ox + a01 * oy + t * bu), cv + (a10 * ox + a11 * oy + t * bv));
    }
    const int inner_in_image = in_image;
    in_image = 0;
    p = outer_xy_.data();
    for (std::size_t i = 0; i < outer_xy_.size(); i += 2) {
      const float du = a00 * p[i] + a01 * p[i + 1], dv = a10 * p[i] + a11 * p[i + 1];
      const float t = du * bu + dv * bv >= 0.0f ? 0.5f : -0.5f;
      outside += hit_px(cu + (du + t * bu), cv + (dv + t * bv));
    }
    return finish(inside, inner_in_image, outside);
  }
  const float* p = inner_xy_.data();
  for (std::size_t i = 0; i < inner_xy_.size(); i += 2) inside += hit(p[i], p[i + 1]);
  const int inner_in_image = in_image;
  in_image = 0;
  p = outer_xy_.data();
  for (std::size_t i = 0; i < outer_xy_.size(); i += 2) outside += hit(p[i], p[i + 1]);
  return finish(inside, inner_in_image, outside);
}

void MarkerFitness::sphere_scores(const Eigen::Isometry3d& T_cl_marker, SphereScores& scores,
                                  SphereScores* ring_hits) const {
  scores_at(T_cl_marker, scores, ring_hits, true);
}

void MarkerFitness::disc_sphere_scores(const Eigen::Isometry3d& T_cl_marker, SphereScores& scores,
                                       SphereScores* ring_hits) const {
  scores_at(T_cl_marker, scores, ring_hits, false);
}

void MarkerFitness::scores_at(const Eigen::Isometry3d& T_cl_marker, SphereScores& scores,
                              SphereScores* ring_hits, bool swept) const {
  scores = {};
  SphereScores ring{};
  if (views_[0].labels != nullptr) {
    for (std::size_t i = 0; i < spheres_.size() && i < 3; ++i) {
      const Eigen::Vector3d c_cl = T_cl_marker * spheres_[i].centre_marker_m;
      scores[0][i] = score_view(views_[0], c_cl, spheres_[i], &ring[0][i], swept);
      scores[1][i] = score_view(views_[1], views_[1].R_v_cl * c_cl + views_[1].t_v_cl, spheres_[i],
                                &ring[1][i], swept);
    }
  }
  if (ring_hits != nullptr) *ring_hits = ring;
}

double MarkerFitness::evaluate(const Eigen::Isometry3d& T_cl_marker) const {
  return evaluate_as(T_cl_marker, false);
}

double MarkerFitness::evaluate_swept(const Eigen::Isometry3d& T_cl_marker) const {
  return evaluate_as(T_cl_marker, true);
}

double MarkerFitness::evaluate_as(const Eigen::Isometry3d& T_cl_marker, bool swept) const {
  if (views_[0].labels == nullptr) return 0.0;
  double sum = 0.0;
  for (const Sphere& s : spheres_) {
    const Eigen::Vector3d c_cl = T_cl_marker * s.centre_marker_m;
    sum += score_view(views_[0], c_cl, s, nullptr, swept);
    sum += score_view(views_[1], views_[1].R_v_cl * c_cl + views_[1].t_v_cl, s, nullptr, swept);
  }
  const double f = sum / (2.0 * static_cast<double>(spheres_.size()));
  return std::isfinite(f) ? std::clamp(f, 0.0, 1.0) : 0.0;
}

}  // namespace rovctl::estimator

namespace rovctl::estimator {

void MarkerFitness::enable_far_field() {
  far_field_ = true;
  for (int v = 0; v < 2; ++v) {
    const int rows = (views_[v].camera.height_px + far_cell_px_ - 1) / far_cell_px_;
    const int cols = (views_[v].camera.width_px + far_cell_px_ - 1) / far_cell_px_;
    for (const Sphere& s : spheres_) {
      far_mask_[v][s.colour].create(rows, cols, CV_8UC1);
      far_count_[v][s.colour].create(rows, cols, CV_32SC1);
      far_distance_cells_[v][s.colour].create(rows, cols, CV_32FC1);
      far_distance_cells_[v][s.colour].setTo(1e6f);
    }
  }
}

void MarkerFitness::update_far_field() {
  if (!far_field_ || views_[0].labels == nullptr) return;
  // A cell holds a colour when a sixteenth of its pixels carry it: lone noise pixels do not.
  const int min_pixels = std::max(1, far_cell_px_ * far_cell_px_ / 16);
  for (int v = 0; v < 2; ++v) {
    const View& view = views_[v];
    for (const Sphere& s : spheres_) far_count_[v][s.colour].setTo(0);
    for (int y = 0; y < view.camera.height_px; ++y) {
      const std::uint8_t* row = view.labels + static_cast<std::size_t>(y) * view.stride;
      for (int x = 0; x < view.camera.width_px; ++x) {
        const std::uint8_t c = row[x];
        if (c == 0 || c >= far_count_[v].size() || far_count_[v][c].empty()) continue;
        ++far_count_[v][c].at<int>(y / far_cell_px_, x / far_cell_px_);
      }
    }
    for (const Sphere& s : spheres_) {
      cv::Mat& mask = far_mask_[v][s.colour];
      const cv::Mat& count = far_count_[v][s.colour];
      for (int r = 0; r < mask.rows; ++r) {
        for (int c = 0; c < mask.cols; ++c) {
          mask.at<std::uint8_t>(r, c) = count.at<int>(r, c) >= min_pixels ? 0 : 255;
        }
      }
      // Distance to the nearest zero (colour) cell; with no such cell every entry is large.
      cv::distanceTransform(mask, far_distance_cells_[v][s.colour], cv::DIST_L2, cv::DIST_MASK_3);
    }
  }
}

double MarkerFitness::nearness(int v, const Eigen::Vector3d& c, std::uint8_t colour) const {
  const View& view = views_[v];
  if (c.z() <= 1e-3) return 0.0;
  // The distortion polynomial runs away far outside the lens's field: clamp the direction to
  // a little beyond it (the distance there is past the reach anyway).
  constexpr double kMaxTan = 1.5;
  const double x = std::clamp(c.x() / c.z(), -kMaxTan, kMaxTan);
  const double y = std::clamp(c.y() / c.z(), -kMaxTan, kMaxTan);
  double u = 0.0, w = 0.0;
  view.camera.distort(x, y, u, w);
  const cv::Mat& dist = far_distance_cells_[v][colour];
  const double cu = u / far_cell_px_, cw = w / far_cell_px_;
  const double ku = std::clamp(cu, 0.0, dist.cols - 1.0), kw = std::clamp(cw, 0.0, dist.rows - 1.0);
  const double d_cells =
      dist.at<float>(static_cast<int>(kw), static_cast<int>(ku)) + std::hypot(cu - ku, cw - kw);
  return std::max(0.0, 1.0 - d_cells * far_cell_px_ / far_reach_px_);
}

double MarkerFitness::far_field_nearness(const Eigen::Isometry3d& T_cl_marker) const {
  if (!far_field_ || views_[0].labels == nullptr) return 0.0;
  double sum = 0.0;
  for (const Sphere& s : spheres_) {
    const Eigen::Vector3d c_cl = T_cl_marker * s.centre_marker_m;
    sum += nearness(0, c_cl, s.colour);
    sum += nearness(1, views_[1].R_v_cl * c_cl + views_[1].t_v_cl, s.colour);
  }
  return sum / (2.0 * static_cast<double>(spheres_.size()));
}

double MarkerFitness::search_score(const Eigen::Isometry3d& T_cl_marker) const {
  const double f = evaluate(T_cl_marker);
  return far_field_ ? f + far_weight_ * far_field_nearness(T_cl_marker) : f;
}

}  // namespace rovctl::estimator
