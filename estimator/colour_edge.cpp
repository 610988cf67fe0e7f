// The two walks along a ray for the colour's last edge; the far end's stops early, the inside's
// also works where the ray leaves the image.
#include "estimator/colour_edge.hpp"

#include <array>

namespace rovctl::estimator {
namespace {

bool inside(const cv::Mat& labels, const Eigen::Vector2d& centre_px, const Eigen::Vector2d& d_px,
            double t) {
  const double x = centre_px.x() + t * d_px.x(), y = centre_px.y() + t * d_px.y();
  return !(x <= -0.5 || y <= -0.5 || x >= labels.cols - 0.5 || y >= labels.rows - 0.5);
}

bool hit(const cv::Mat& labels, const Eigen::Vector2d& centre_px, const Eigen::Vector2d& d_px,
         double t, std::uint8_t colour) {
  const double x = centre_px.x() + t * d_px.x(), y = centre_px.y() + t * d_px.y();
  // Rounded half away from zero as std::lround does, which costs a library call here.
  const int u = static_cast<int>(x + 0.5), v = static_cast<int>(y + 0.5);
  return labels.ptr<std::uint8_t>(v)[u] == colour;
}

}  // namespace

double colour_edge_t_from_inside(const cv::Mat& labels, const Eigen::Vector2d& centre_px,
                                 const Eigen::Vector2d& d_px, double t_from, double t_to,
                                 std::uint8_t colour) {
  double edge_t = -1.0;
  int run = 0;  // consecutive colour samples
  for (double t = t_from; t <= t_to; t += kColourEdgeStepPx) {
    if (!inside(labels, centre_px, d_px, t)) {
      // Colour up to the border: the rim is outside the image; any edge before it is inner.
      return run > 0 ? -1.0 : edge_t;
    }
    if (hit(labels, centre_px, d_px, t, colour)) {
      ++run;
    } else {
      if (run >= 2) edge_t = t - 0.5 * kColourEdgeStepPx;
      run = 0;
    }
  }
  return run > 0 ? -1.0 : edge_t;
}

double colour_edge_t_from_far_end(const cv::Mat& labels, const Eigen::Vector2d& centre_px,
                                  const Eigen::Vector2d& d_px, double t_from, double t_to,
                                  std::uint8_t colour) {
  // The samples' t as the inside walk accumulates them, so both walks read the same pixels.
  std::array<double, kColourEdgeMaxSamples> sample_t;
  int samples = 0;
  for (double t = t_from; t <= t_to; t += kColourEdgeStepPx) {
    if (samples == kColourEdgeMaxSamples) return -2.0;
    sample_t[samples++] = t;
  }
  if (samples == 0) return -1.0;
  // A sample's position is monotonic in t, so inside at both ends is inside all along.
  if (!inside(labels, centre_px, d_px, sample_t[0]) ||
      !inside(labels, centre_px, d_px, sample_t[samples - 1])) {
    return -2.0;
  }
  if (hit(labels, centre_px, d_px, sample_t[samples - 1], colour)) return -1.0;
  int run = 0;
  for (int k = samples - 2; k >= 0; --k) {
    if (!hit(labels, centre_px, d_px, sample_t[k], colour)) {
      run = 0;
    } else if (++run == 2) {
      return sample_t[k + 2] - 0.5 * kColourEdgeStepPx;
    }
  }
  return -1.0;
}

double colour_edge_t(const cv::Mat& labels, const Eigen::Vector2d& centre_px,
                     const Eigen::Vector2d& d_px, double t_from, double t_to, std::uint8_t colour) {
  const double t = colour_edge_t_from_far_end(labels, centre_px, d_px, t_from, t_to, colour);
  return t > -2.0 ? t : colour_edge_t_from_inside(labels, centre_px, d_px, t_from, t_to, colour);
}

}  // namespace rovctl::estimator
