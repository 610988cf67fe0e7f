// Colour -> class label (none/red/green/blue) per pixel by hue with saturation and value floors,
// through a lookup table indexed by the quantised BGR colour: no per-pixel branching. Optionally
// corrected first for the water's colour, as a diver's white balance is: water takes red first,
// so a red sphere a metre away is a greyish brown until the cast of the scene is divided out.
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "hal/model/marker_model.hpp"

namespace rovctl::estimator {

class HueSegmenter {
 public:
  // Builds the table from each sphere's hue window and S/V floors. `water_correction` in [0, 1]:
  // 0 classifies the colours as they are; 1 divides each channel by the scene's median (von
  // Kries white balance to the water's colour); between, that gain raised to the power.
  explicit HueSegmenter(const hal::MarkerModel& marker, double water_correction = 0.0);

  // labels: CV_8UC1 of ColourClass values; (re)allocated only if its size or type differs.
  void segment(const cv::Mat& bgr, cv::Mat& labels);

  // The per-channel gains (B, G, R) the last segment() applied.
  const std::array<double, 3>& gains() const { return gains_; }

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
  void update_gains(const cv::Mat& bgr);
  void set_index_bits();

  std::vector<std::uint8_t> lut_;  // 2^18 entries, 6 bits per channel
  double water_correction_ = 0.0;
  std::array<double, 3> gains_{1.0, 1.0, 1.0};
  std::array<std::array<std::uint32_t, 256>, 3> histogram_{};
  // Per channel: v -> min(255, gain v)'s six bits, in their place in the table's index.
  std::array<std::array<std::uint32_t, 256>, 3> index_bits_{};
};

}  // namespace rovctl::estimator
