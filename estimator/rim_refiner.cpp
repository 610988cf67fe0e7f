// Rays cast outward from each predicted silhouette find the outermost edge of the sphere's colour;
// an iteratively reweighted, Levenberg-damped Gauss-Newton moves the pose until the silhouettes
// pass through those edges. Edges well inside a silhouette (a bar in front, a shadow, a bubble)
// get no weight: they say where the sphere is hidden, not where it ends.
#include "estimator/rim_refiner.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "estimator/colour_edge.hpp"
#include "hal/model/pose.hpp"
#include "hal/model/sphere_rim.hpp"
#include "hal/model/unit_circle.hpp"

namespace rovctl::estimator {
namespace {

// Inlier band per pass: wide while the start may be a few pixels off, then tight.
struct Band {
  double inside_px;   // edges further inside the silhouette are cuts (occluder, shadow)
  double outside_px;  // edges further outside are another object of the same colour
};
constexpr std::array<Band, 2> kBands{{{4.0, 4.0}, {2.0, 3.0}}};
constexpr double kHuberPx = 1.0;
constexpr int kMinInliers = 40;

// A number that orders directions as atan2 does, over (-2, 2] instead of (-pi, pi], without the
// arctangent: the outline's binary search runs for every rim point of every Jacobian column.
double angle_order(const Eigen::Vector2d& d) {
  const double p = d.y() / (std::abs(d.x()) + std::abs(d.y()));
  if (d.x() >= 0.0) return p;
  return d.y() >= 0.0 ? 2.0 - p : -2.0 - p;
}

// The silhouette's outline vertices and the rays cast across it, at fixed angles.
const hal::UnitCircle<RimRefiner::kPolygon>& outline_angles() {
  static const hal::UnitCircle<RimRefiner::kPolygon> circle;
  return circle;
}
const hal::UnitCircle<RimRefiner::kRays>& ray_directions() {
  static const hal::UnitCircle<RimRefiner::kRays> circle(-M_PI);
  return circle;
}

double weight(double r, const Band& band) {
  if (r < -band.inside_px || r > band.outside_px) return 0.0;
  const double a = std::abs(r);
  return a <= kHuberPx ? 1.0 : kHuberPx / a;
}

}  // namespace

double RimRefiner::Silhouette::radius_along(const Eigen::Vector2d& d, int& hint) const {
  const double angle = angle_order(d);
  // The outline's segment is std::upper_bound's answer, the one i with angle[i - 1] <= angle <
  // angle[i]. Rim points come in angle order, so the last point's segment or the next one mostly
  // is that i; the binary search is for the rest.
  auto is_answer = [&](int i) {
    return (i == 0 || pseudo_angle[i - 1] <= angle) && (i == kPolygon || angle < pseudo_angle[i]);
  };
  int hi = hint;
  if (!is_answer(hi)) {
    hi = hint < kPolygon && is_answer(hint + 1)
             ? hint + 1
             : static_cast<int>(std::upper_bound(pseudo_angle.begin(), pseudo_angle.end(), angle) -
                                pseudo_angle.begin());
  }
  hint = hi;
  const Eigen::Vector2d& pa = offset_px[(hi + kPolygon - 1) % kPolygon];
  const Eigen::Vector2d& pb = offset_px[hi % kPolygon];
  // Where the ray from the centre along d crosses the segment pa-pb.
  const Eigen::Vector2d e = pb - pa;
  const double den = d.x() * e.y() - d.y() * e.x();
  const double n = d.norm();
  if (std::abs(den) < 1e-12 * n) return 0.5 * (pa.norm() + pb.norm());
  return (pa.x() * e.y() - pa.y() * e.x()) / den * n;
}

RimRefiner::RimRefiner(const hal::StereoRig& rig, const hal::MarkerModel& marker, Misfit misfit)
    : rig_(rig),
      marker_(marker),
      spheres_(static_cast<int>(std::min<std::size_t>(marker.spheres.size(), kSpheres))),
      misfit_(misfit) {}

Eigen::Vector3d RimRefiner::centre_in_view(const Eigen::Isometry3d& T, int view, int sphere) const {
  const Eigen::Vector3d c = T * marker_.spheres[sphere].centre_marker_m;
  return view == 0 ? c : rig_.T_cr_cl * c;
}

bool RimRefiner::predict_one(int view, int sphere, const Eigen::Vector3d& c,
                             Silhouette& sil) const {
  sil.valid = false;
  const hal::CameraModel& cam = view == 0 ? rig_.left : rig_.right;
  hal::SphereRim rim;
  if (!hal::sphere_rim(c, marker_.spheres[sphere].radius_m, rim)) return false;
  const hal::UnitCircle<kPolygon>& around = outline_angles();
  std::array<Eigen::Vector2d, kPolygon> p;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (int k = 0; k < kPolygon; ++k) {
    if (!cam.project(rim.point(around[k].x(), around[k].y()), p[k])) return false;
    centre += p[k];
  }
  centre /= kPolygon;
  // Counter-clockwise in angle, starting at the smallest: radius_along's binary search.
  const Eigen::Vector2d a = p[0] - centre, b = p[1] - centre;
  const bool reverse = a.x() * b.y() - a.y() * b.x() < 0.0;
  std::array<double, kPolygon> angle;
  int first = 0;
  for (int k = 0; k < kPolygon; ++k) {
    angle[k] = angle_order(p[reverse ? kPolygon - 1 - k : k] - centre);
    if (angle[k] < angle[first]) first = k;
  }
  for (int k = 0; k < kPolygon; ++k) {
    const int step = (first + k) % kPolygon;
    sil.offset_px[k] = p[reverse ? kPolygon - 1 - step : step] - centre;
    sil.pseudo_angle[k] = angle[step];
  }
  // A silhouette wrapped onto itself (lens distortion far outside its range) is no ellipse.
  if (!std::is_sorted(sil.pseudo_angle.begin(), sil.pseudo_angle.end())) return false;
  sil.centre_px = centre;
  sil.valid = true;
  return true;
}

void RimRefiner::predict(const Eigen::Isometry3d& T, Silhouettes& out) const {
  for (int view = 0; view < 2; ++view) {
    for (int s = 0; s < spheres_; ++s)
      predict_one(view, s, centre_in_view(T, view, s), out[view][s]);
  }
}

void RimRefiner::find_edges(const cv::Mat* labels[2], const Silhouettes& predicted,
                            Edges& edges) const {
  edges.count = 0;
  for (int view = 0; view < 2; ++view) {
    const cv::Mat& image = *labels[view];
    for (int s = 0; s < spheres_; ++s) {
      edges.first[view][s] = edges.count;
      edges.first[view][s + 1] = edges.count;
      edges.visible_rays[view][s] = 0;
      const Silhouette& sil = predicted[view][s];
      if (!sil.valid) continue;
      const auto colour = static_cast<std::uint8_t>(marker_.spheres[s].colour);
      int hint = 0;
      for (int k = 0; k < kRays; ++k) {
        const double c = ray_directions()[k].x(), sn = ray_directions()[k].y();
        const double rho = sil.radius_along(Eigen::Vector2d(c, sn), hint);
        const Eigen::Vector2d rim_px = sil.centre_px + rho * Eigen::Vector2d(c, sn);
        if (rim_px.x() < kBorderMarginPx || rim_px.y() < kBorderMarginPx ||
            rim_px.x() > image.cols - 1 - kBorderMarginPx ||
            rim_px.y() > image.rows - 1 - kBorderMarginPx) {
          continue;  // the border hides this part of the rim: no evidence either way
        }
        ++edges.visible_rays[view][s];
        const double edge_t = colour_edge_t(image, sil.centre_px, Eigen::Vector2d(c, sn), 0.3 * rho,
                                            1.6 * rho + 2.0, colour);
        if (edge_t < 0.0) continue;
        EdgePoint& e = edges.points[edges.count++];
        e.uv_px = sil.centre_px + edge_t * Eigen::Vector2d(c, sn);
        e.view = static_cast<std::uint8_t>(view);
        e.sphere = static_cast<std::uint8_t>(s);
      }
      edges.first[view][s + 1] = edges.count;
    }
  }
}

void RimRefiner::silhouette_residuals(const Edges& edges, int view, int sphere,
                                      const Silhouette& sil, Residuals& r) const {
  int hint = 0;
  for (int i = edges.first[view][sphere]; i < edges.first[view][sphere + 1]; ++i) {
    const Eigen::Vector2d d = edges.points[i].uv_px - sil.centre_px;
    r(i) = d.norm() - sil.radius_along(d, hint);
  }
}

bool RimRefiner::residuals(const Edges& edges, const Eigen::Isometry3d& T, Residuals& r) const {
  r.head(edges.count).setZero();
  for (int view = 0; view < 2; ++view) {
    for (int s = 0; s < spheres_; ++s) {
      if (edges.first[view][s] == edges.first[view][s + 1]) continue;
      Silhouette sil;
      if (!predict_one(view, s, centre_in_view(T, view, s), sil)) return false;
      silhouette_residuals(edges, view, s, sil, r);
    }
  }
  return r.head(edges.count).allFinite();
}

bool RimRefiner::jacobian(const Edges& edges, const Eigen::Isometry3d& T, const Residuals& rb,
                          Jacobian& J) const {
  constexpr double h = 1e-6;  // m
  Residuals rk;
  for (int view = 0; view < 2; ++view) {
    // The centre in the view's frame c_v = R_v (exp(w) R p + t + dt) + t_v: dc_v/dw = -R_v [R p]x,
    // dc_v/dt = R_v.
    const Eigen::Matrix3d R_v =
        view == 0 ? Eigen::Matrix3d::Identity() : rig_.T_cr_cl.linear().eval();
    for (int s = 0; s < spheres_; ++s) {
      const int from = edges.first[view][s], to = edges.first[view][s + 1];
      if (from == to) continue;
      const Eigen::Vector3d c = centre_in_view(T, view, s);
      Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kRays, 3> dr_dc(to - from, 3);
      for (int k = 0; k < 3; ++k) {
        Silhouette sil;
        if (!predict_one(view, s, c + h * Eigen::Vector3d::Unit(k), sil)) return false;
        silhouette_residuals(edges, view, s, sil, rk);
        dr_dc.col(k) = (rk.segment(from, to - from) - rb.segment(from, to - from)) / h;
      }
      const Eigen::Vector3d Rp = T.linear() * marker_.spheres[s].centre_marker_m;
      Eigen::Matrix3d Rp_cross;
      Rp_cross << 0, -Rp.z(), Rp.y(), Rp.z(), 0, -Rp.x(), -Rp.y(), Rp.x(), 0;
      Eigen::Matrix<double, 3, 6> dc_dpose;
      dc_dpose.leftCols<3>() = -R_v * Rp_cross;
      dc_dpose.rightCols<3>() = R_v;
      J.block(from, 0, to - from, 6) = dr_dc * dc_dpose;
    }
  }
  return J.topRows(edges.count).allFinite();
}

bool RimRefiner::refine(const cv::Mat& left_labels, const cv::Mat& right_labels,
                        Eigen::Isometry3d& T_cl_marker, RimFit* fit) const {
  const cv::Mat* labels[2] = {&left_labels, &right_labels};
  Eigen::Isometry3d T = T_cl_marker;
  // Where the segmenter puts a colour edge depends on the contrast with the water (a faded edge
  // ends early, a bright one blooms), and a quarter pixel on every rim is millimetres in range
  // through the spheres' apparent size. One edge offset (px), estimated with the pose, leaves the
  // range to the stereo baseline.
  double offset_px = 0.0;
  constexpr double kOffsetPriorPx = 1.0;
  Edges edges;
  // raw0: r0 before the offset, at T; the Jacobian's differences are taken from it.
  Residuals r0, raw0, w;
  Jacobian J;
  auto full_residuals = [&](const Eigen::Isometry3d& at, double off, Residuals& raw, Residuals& r) {
    if (!residuals(edges, at, raw)) return false;
    r.head(edges.count) = raw.head(edges.count).array() - off;
    return true;
  };
  auto weighted_cost = [&](const Residuals& r, double off) {
    return (w.head(edges.count).array() * r.head(edges.count).array().square()).sum() +
           off * off / (kOffsetPriorPx * kOffsetPriorPx);
  };
  // Normal equations of the weighted problem in (rotation vector, translation, offset), with the
  // offset's prior.
  auto normal_equations = [&](const Eigen::Isometry3d& at, const Residuals& raw, const Residuals& r,
                              double off, Matrix7& A, Vector7& g) {
    if (!jacobian(edges, at, raw, J)) return false;
    A.setZero();
    g.setZero();
    for (int i = 0; i < edges.count; ++i) {
      Vector7 j;
      j.head<6>() = J.row(i).transpose();
      j(6) = -1.0;
      A.noalias() += w(i) * j * j.transpose();
      g.noalias() += w(i) * r(i) * j;
    }
    A(6, 6) += 1.0 / (kOffsetPriorPx * kOffsetPriorPx);
    g(6) += off / (kOffsetPriorPx * kOffsetPriorPx);
    return true;
  };
  for (const Band& band : kBands) {
    Silhouettes sil;
    predict(T, sil);
    find_edges(labels, sil, edges);
    if (edges.count < kMinInliers || !full_residuals(T, offset_px, raw0, r0)) return false;
    double lambda = 1e-3;
    Matrix7 A;
    Vector7 g;
    bool moved = true;
    for (int iter = 0; iter < 10; ++iter) {
      if (moved) {
        for (int i = 0; i < edges.count; ++i) w(i) = weight(r0(i), band);
        if (!normal_equations(T, raw0, r0, offset_px, A, g)) return false;
      }
      Matrix7 damped = A;
      damped.diagonal() *= 1.0 + lambda;
      damped.diagonal().array() += 1e-12;
      const Vector7 step = -damped.ldlt().solve(g);
      if (!step.allFinite()) return false;
      const Eigen::Isometry3d candidate = hal::perturbed(T, step.head<6>());
      Residuals raw1, r1;
      moved = full_residuals(candidate, offset_px + step(6), raw1, r1) &&
              weighted_cost(r1, offset_px + step(6)) < weighted_cost(r0, offset_px);
      if (moved) {
        T = candidate;
        offset_px += step(6);
        r0 = r1;
        raw0 = raw1;
        lambda = std::max(1e-6, lambda * 0.3);
        // 10 um and 10 urad: far below what the rims can tell.
        if (step.head<6>().norm() < 1e-5) break;
      } else {
        lambda *= 10.0;
        if (lambda > 1e6) break;
      }
    }
  }
  // The final edges, seen from the refined pose, decide support and the residual.
  const Band& tight = kBands.back();
  Silhouettes final_sil;
  predict(T, final_sil);
  find_edges(labels, final_sil, edges);
  if (!full_residuals(T, offset_px, raw0, r0)) return false;
  RimFit result;
  double sum2 = 0.0;
  for (int i = 0; i < edges.count; ++i) {
    w(i) = weight(r0(i), tight);
    if (std::abs(r0(i)) <= kInlierPx) {
      ++result.inliers;
      sum2 += r0(i) * r0(i);
      result.support[edges.points[i].view][edges.points[i].sphere] += 1.0;
    }
  }
  for (int view = 0; view < 2; ++view) {
    for (int s = 0; s < spheres_; ++s) {
      const int visible = edges.visible_rays[view][s];
      double& support = result.support[view][s];
      support = visible >= kMinVisibleRays ? support / visible : 0.0;
    }
  }
  if (result.inliers < kMinInliers) return false;
  result.rms_px = std::sqrt(sum2 / result.inliers);
  if (fit != nullptr) {
    int silhouettes = 0;
    for (const auto& view : result.support) {
      for (double s : view) silhouettes += s > 0.0 ? 1 : 0;
    }
    result.independent_points = kIndependentPerSilhouette * silhouettes;
    const double white_px = std::max(result.rms_px, kEdgeNoisePx);
    const double sigma_px = white_px * std::sqrt(result.inliers / result.independent_points);
    Matrix7 A;
    Vector7 g;
    if (normal_equations(T, raw0, r0, offset_px, A, g)) {
      // The pose's marginal covariance: the offset is a nuisance parameter.
      const Matrix7 cov = sigma_px * sigma_px * A.ldlt().solve(Matrix7::Identity());
      result.covariance = cov.topLeftCorner<6, 6>();
      result.measured =
          misfit_ == Misfit::measured &&
          measured_covariance(edges, final_sil, J, r0, w, white_px, A, result.covariance_measured);
    }
    *fit = result;
  }
  T_cl_marker = T;
  return true;
}

bool RimRefiner::measured_covariance(const Edges& edges, const Silhouettes& sil, const Jacobian& J,
                                     const Residuals& r, const Residuals& w, double white_px,
                                     const Matrix7& A,
                                     Eigen::Matrix<double, 6, 6>& covariance) const {
  // M, the covariance of the fit's gradient: every point's own noise, then per silhouette its
  // radius and centre misfit, which all of its points share.
  Matrix7 M = Matrix7::Zero();
  std::array<Eigen::Matrix<double, 3, 7>, 2 * kSpheres> G;  // gradient per unit of (a, b, c)
  // Per sphere, the gradient of its centre moved alike in both views (per unit of b and c).
  std::array<Eigen::Matrix<double, 2, 7>, kSpheres> shared{};
  for (auto& g : shared) g.setZero();
  double radius2 = 0.0, centre2 = 0.0;
  int seen = 0;
  for (int view = 0; view < 2; ++view) {
    for (int s = 0; s < spheres_; ++s) {
      Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      Eigen::Matrix<double, 3, 7> Gs = Eigen::Matrix<double, 3, 7>::Zero();
      int n = 0;
      for (int i = edges.first[view][s]; i < edges.first[view][s + 1]; ++i) {
        Vector7 j;
        j.head<6>() = J.row(i).transpose();
        j(6) = -1.0;
        M.noalias() += (w(i) * w(i) * white_px * white_px) * j * j.transpose();
        if (std::abs(r(i)) > kInlierPx) continue;
        // r ~ a + b cos(theta) + c sin(theta) about the silhouette's centre.
        const Eigen::Vector2d d = edges.points[i].uv_px - sil[view][s].centre_px;
        const double theta = std::atan2(d.y(), d.x());
        const Eigen::Vector3d phi(1.0, std::cos(theta), std::sin(theta));
        P.noalias() += phi * phi.transpose();
        b += r(i) * phi;
        Gs.noalias() += w(i) * phi * j.transpose();
        ++n;
      }
      shared[s] += Gs.bottomRows<2>();
      if (n < kMinVisibleRays) continue;
      const Eigen::Vector3d abc = P.ldlt().solve(b);
      if (!abc.allFinite()) continue;
      G[seen++] = Gs;
      radius2 += abc(0) * abc(0);
      centre2 += abc(1) * abc(1) + abc(2) * abc(2);
    }
  }
  if (seen < kMinMeasuredSilhouettes) return false;
  // What is left after the fit: its seven parameters explain about two of the radii (range and
  // the edge offset) and five of the centres' coordinates.
  const double floor2 = kMisfitFloorPx * kMisfitFloorPx;
  const double radius_var = kMisfitInflation * std::max(radius2 / (seen - 2), floor2);
  const double centre_var = kMisfitInflation * std::max(centre2 / (2 * seen - 5), floor2);
  const Eigen::Vector3d v(radius_var, centre_var, centre_var);
  for (int k = 0; k < seen; ++k) M.noalias() += G[k].transpose() * v.asDiagonal() * G[k];
  // A sphere's centre moved alike in both views is a move of the sphere, which the pose takes up
  // and leaves no misfit for: the misfit cannot measure it, so it is credited at a floor.
  const double bias2 = kSharedCentreBiasPx * kSharedCentreBiasPx;
  for (int s = 0; s < spheres_; ++s) M.noalias() += bias2 * shared[s].transpose() * shared[s];
  const Matrix7 A_inverse = A.ldlt().solve(Matrix7::Identity());
  covariance = (A_inverse * M * A_inverse).topLeftCorner<6, 6>();
  return covariance.allFinite();
}

}  // namespace rovctl::estimator
