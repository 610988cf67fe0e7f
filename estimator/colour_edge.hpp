// Where a sphere's colour ends along a ray cast outward from its predicted centre: the rim
// refiner's edge points, found by one of two walks that agree wherever both can run.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core/mat.hpp>

namespace rovctl::estimator {

// The ray is centre_px + t d_px, sampled at t = t_from, t_from + kColourEdgeStepPx, ... (sums,
// as a walk accumulates them) up to t_to, each at its nearest pixel of the label image. The edge
// is halfway between the end of the last run of two or more samples of `colour` and the sample
// after it. A lone sample is a speck, not the sphere; colour up to the far end or the image
// border means the rim is beyond the ray, so there is no edge.
inline constexpr double kColourEdgeStepPx = 0.5;

// t of the edge, or -1 for none. Walks from the far end where the whole ray is inside the image
// (about half the samples: it stops at the first edge it meets), from the inside otherwise.
double colour_edge_t(const cv::Mat& labels, const Eigen::Vector2d& centre_px,
                     const Eigen::Vector2d& d_px, double t_from, double t_to, std::uint8_t colour);

// The two walks, for the test that they agree: from the inside outward, stopping at the border;
// and from the far end inward, which needs the ray inside the image at both ends and at most
// kColourEdgeMaxSamples samples (else -2, and colour_edge_t walks from the inside).
inline constexpr int kColourEdgeMaxSamples = 1024;
double colour_edge_t_from_inside(const cv::Mat& labels, const Eigen::Vector2d& centre_px,
                                 const Eigen::Vector2d& d_px, double t_from, double t_to,
                                 std::uint8_t colour);
double colour_edge_t_from_far_end(const cv::Mat& labels, const Eigen::Vector2d& centre_px,
                                  const Eigen::Vector2d& d_px, double t_from, double t_to,
                                  std::uint8_t colour);

}  // namespace rovctl::estimator
