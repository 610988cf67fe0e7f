// Improvement beyond the paper: finds each colour's blob in both label images, triangulates the
// sphere centres and fits the marker model to them (Umeyama) to seed the GA with a pose.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

// One colour's largest blob in one image: the centroid of its silhouette (row spans, so the
// specular highlight's hole is filled) in distorted pixel coordinates.
struct Blob {
  bool valid = false;
  bool touches_border = false;
  double u_px = 0.0, v_px = 0.0;
  double area_px = 0.0;
  // The silhouette's second moments read as a disc smeared along a line (motion blur): a disc of
  // diameter D has variance D^2 / 16 along every axis, and a smear of length L adds L^2 / 12
  // along it. width_px = 4 sigma across the long axis; smear = sqrt(12 (var_long - var_across))
  // along it, whichever way (sign-free). A sharp disc reads a smear of a pixel or two; a
  // uniformly labelled stadium about its length plus 0.8 D; a blurred sphere, labelled where its
  // colour is strong, close to its smear (32-33 px for 30 px on the validation set).
  double width_px = 0.0;
  double smear_u_px = 0.0, smear_v_px = 0.0;
};

// [view 0 = left, 1 = right][colour class]
using BlobSet = std::array<std::array<Blob, hal::kColourClassCount>, 2>;

class BlobSeeder {
 public:
  BlobSeeder(const hal::StereoRig& rig, const hal::MarkerModel& marker);

  // Finds the blobs of one view (0 left, 1 right). Allocates nothing.
  void find(int view, const cv::Mat& labels);
  const BlobSet& blobs() const { return blobs_; }

  // The marker pose from the sphere centres triangulated from whole blobs seen in both views;
  // false when a sphere is missing or cut by the image border.
  bool seed(Eigen::Isometry3d& T_cl_marker) const;

 private:
  static constexpr int kCell = 8;
  hal::StereoRig rig_;
  hal::MarkerModel marker_;
  BlobSet blobs_{};
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<std::uint16_t> counts_;  // [class][cell] pixels of that class per 8x8 cell
  std::vector<std::uint8_t> visited_;
  std::vector<int> stack_;
};

}  // namespace rovctl::estimator
