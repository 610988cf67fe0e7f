// Blob finding on an 8x8-cell grid of class counts (flood fill from the fullest cell), then exact
// row spans inside the blob's box; triangulation by the midpoint of the two viewing rays.
#include "estimator/blob_seeder.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace rovctl::estimator {

BlobSeeder::BlobSeeder(const hal::StereoRig& rig, const hal::MarkerModel& marker)
    : rig_(rig), marker_(marker) {
  const int w = std::max(rig.left.width_px, rig.right.width_px);
  const int h = std::max(rig.left.height_px, rig.right.height_px);
  cells_x_ = (w + kCell - 1) / kCell;
  cells_y_ = (h + kCell - 1) / kCell;
  const std::size_t cells = static_cast<std::size_t>(cells_x_) * cells_y_;
  counts_.assign(cells * hal::kColourClassCount, 0);
  visited_.assign(cells, 0);
  stack_.assign(cells, 0);
}

void BlobSeeder::find(int view, const cv::Mat& labels) {
  const std::size_t cells = static_cast<std::size_t>(cells_x_) * cells_y_;
  std::fill(counts_.begin(), counts_.end(), 0);
  const int w = std::min(labels.cols, cells_x_ * kCell);
  const int h = std::min(labels.rows, cells_y_ * kCell);
  static_assert(kCell == sizeof(std::uint64_t), "one cell's row is read as one word");
  for (int v = 0; v < h; ++v) {
    const std::uint8_t* row = labels.ptr<std::uint8_t>(v);
    const int cell_row = (v / kCell) * cells_x_;
    for (int u = 0; u < w; u += kCell) {
      // Most of a frame is no colour: a cell's row of eight labels is skipped as one zero word.
      std::uint64_t word = 0;
      const int n = std::min(kCell, w - u);
      std::memcpy(&word, row + u, static_cast<std::size_t>(n));
      if (word == 0) continue;
      std::uint16_t* cell = counts_.data() + cell_row + u / kCell;
      for (int i = 0; i < n; ++i) {
        const std::uint8_t c = row[u + i];
        if (c != 0 && c < hal::kColourClassCount) ++cell[c * cells];
      }
    }
  }
  for (int c = 0; c < hal::kColourClassCount; ++c) {
    Blob& blob = blobs_[view][c];
    blob = Blob{};
    if (c == 0) continue;
    const std::uint16_t* count = counts_.data() + c * cells;
    const auto best = std::max_element(count, count + cells);
    if (*best < 3) continue;
    // Flood the 8-connected cells that hold this class, from the fullest one.
    std::fill(visited_.begin(), visited_.end(), 0);
    int top = 0;
    const int start = static_cast<int>(best - count);
    stack_[top++] = start;
    visited_[start] = 1;
    int cx0 = cells_x_, cx1 = -1, cy0 = cells_y_, cy1 = -1;
    while (top > 0) {
      const int cell = stack_[--top];
      const int cx = cell % cells_x_, cy = cell / cells_x_;
      cx0 = std::min(cx0, cx);
      cx1 = std::max(cx1, cx);
      cy0 = std::min(cy0, cy);
      cy1 = std::max(cy1, cy);
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = cx + dx, ny = cy + dy;
          if (nx < 0 || ny < 0 || nx >= cells_x_ || ny >= cells_y_) continue;
          const int n = ny * cells_x_ + nx;
          if (visited_[n] || count[n] == 0) continue;
          visited_[n] = 1;
          stack_[top++] = n;
        }
      }
    }
    // Row spans between the first and last pixel of the class: the silhouette with its holes
    // (highlights) filled, as spheres project to convex ellipses.
    const int x0 = cx0 * kCell, x1 = std::min(w, (cx1 + 1) * kCell) - 1;
    const int y0 = cy0 * kCell, y1 = std::min(h, (cy1 + 1) * kCell) - 1;
    double area = 0.0, su = 0.0, sv = 0.0, suu = 0.0, suv = 0.0, svv = 0.0;
    // Sum of k^2 for k = 0..n.
    auto squares = [](double n) { return n * (n + 1.0) * (2.0 * n + 1.0) / 6.0; };
    int u_min = w, u_max = -1, v_min = h, v_max = -1;
    for (int v = y0; v <= y1; ++v) {
      const std::uint8_t* row = labels.ptr<std::uint8_t>(v);
      int l = x0;
      while (l <= x1 && row[l] != c) ++l;
      if (l > x1) continue;
      int r = x1;
      while (row[r] != c) --r;
      const double n = r - l + 1;
      area += n;
      const double row_u = n * 0.5 * (l + r);
      su += row_u;
      sv += n * v;
      suu += squares(r) - squares(l - 1.0);
      suv += row_u * v;
      svv += n * static_cast<double>(v) * v;
      u_min = std::min(u_min, l);
      u_max = std::max(u_max, r);
      v_min = std::min(v_min, v);
      v_max = std::max(v_max, v);
    }
    if (area < 12.0) continue;
    blob.valid = true;
    blob.area_px = area;
    blob.u_px = su / area;
    blob.v_px = sv / area;
    const double cuu = suu / area - blob.u_px * blob.u_px;
    const double cvv = svv / area - blob.v_px * blob.v_px;
    const double cuv = suv / area - blob.u_px * blob.v_px;
    const double half_gap = std::sqrt(0.25 * (cuu - cvv) * (cuu - cvv) + cuv * cuv);
    const double across = std::max(0.0, 0.5 * (cuu + cvv) - half_gap);
    const double smear = std::sqrt(12.0 * 2.0 * half_gap);
    const double angle = 0.5 * std::atan2(2.0 * cuv, cuu - cvv);
    blob.width_px = 4.0 * std::sqrt(across);
    blob.smear_u_px = smear * std::cos(angle);
    blob.smear_v_px = smear * std::sin(angle);
    blob.touches_border =
        u_min <= 0 || v_min <= 0 || u_max >= labels.cols - 1 || v_max >= labels.rows - 1;
  }
}

bool BlobSeeder::seed(Eigen::Isometry3d& T_cl_marker) const {
  const int n = static_cast<int>(std::min<std::size_t>(marker_.spheres.size(), 3));
  if (n < 3) return false;
  Eigen::Matrix3d model, measured;  // columns: sphere centres in marker / left camera frame
  const Eigen::Isometry3d T_cl_cr = rig_.T_cr_cl.inverse();
  for (int i = 0; i < n; ++i) {
    const hal::MarkerSphere& s = marker_.spheres[i];
    const Blob& bl = blobs_[0][static_cast<int>(s.colour)];
    const Blob& br = blobs_[1][static_cast<int>(s.colour)];
    if (!bl.valid || !br.valid || bl.touches_border || br.touches_border) return false;
    const Eigen::Vector3d dl = rig_.left.unproject({bl.u_px, bl.v_px}).normalized();
    const Eigen::Vector3d dr =
        T_cl_cr.linear() * rig_.right.unproject({br.u_px, br.v_px}).normalized();
    const Eigen::Vector3d o = T_cl_cr.translation();
    // Closest points of the rays s*dl and o + t*dr.
    const double b = dl.dot(dr), d = dl.dot(o), e = dr.dot(o);
    const double denom = 1.0 - b * b;
    if (denom < 1e-9) return false;
    const double sl = (d - b * e) / denom;
    const double tr = (b * d - e) / denom;
    if (sl <= 0.0 || tr <= 0.0) return false;
    measured.col(i) = 0.5 * (sl * dl + o + tr * dr);
    model.col(i) = s.centre_marker_m;
  }
  const Eigen::Matrix4d T = Eigen::umeyama(model, measured, false);
  if (!T.allFinite()) return false;
  T_cl_marker.matrix() = T;
  return true;
}

}  // namespace rovctl::estimator
