// Colour -> class label (none/red/green/blue) per pixel by hue with saturation and value floors,
// through a lookup table indexed by the quantised BGR colour: no per-pixel branching.
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "hal/model/marker_model.hpp"

namespace rovctl::estimator {

class HueSegmenter {
 public:
  // Builds the table from each sphere's hue window and S/V floors.
  explicit HueSegmenter(const hal::MarkerModel& marker);

  // labels: CV_8UC1 of ColourClass values; (re)allocated only if its size or type differs.
  void segment(const cv::Mat& bgr, cv::Mat& labels) const;

  hal::ColourClass classify(std::uint8_t b, std::uint8_t g, std::uint8_t r) const {
    return static_cast<hal::ColourClass>(lut_[index(b, g, r)]);
  }

  // The class a colour gets from the exact HSV rule (the table holds it per 6-bit cell).
  static hal::ColourClass classify_exact(const hal::MarkerModel& marker, double b, double g,
                                         double r);

 private:
  static std::uint32_t index(std::uint8_t b, std::uint8_t g, std::uint8_t r) {
    return (static_cast<std::uint32_t>(b >> 2) << 12) | (static_cast<std::uint32_t>(g >> 2) << 6) |
           static_cast<std::uint32_t>(r >> 2);
  }
  std::vector<std::uint8_t> lut_;  // 2^18 entries, 6 bits per channel
};

}  // namespace rovctl::estimator
