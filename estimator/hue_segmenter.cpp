// The lookup table is filled once from the marker's hue windows; segmenting is one load per pixel.
#include "estimator/hue_segmenter.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

namespace rovctl::estimator {

hal::ColourClass HueSegmenter::classify_exact(const hal::MarkerModel& marker, double b, double g,
                                              double r) {
  const double mx = std::max({r, g, b});
  const double mn = std::min({r, g, b});
  const double value = mx / 255.0;
  const double chroma = mx - mn;
  if (mx <= 0.0 || chroma <= 0.0) return hal::ColourClass::none;
  const double saturation = chroma / mx;
  double hue;
  if (mx == r) {
    hue = 60.0 * std::fmod((g - b) / chroma + 6.0, 6.0);
  } else if (mx == g) {
    hue = 60.0 * ((b - r) / chroma + 2.0);
  } else {
    hue = 60.0 * ((r - g) / chroma + 4.0);
  }
  for (const hal::MarkerSphere& s : marker.spheres) {
    if (saturation < s.saturation_min || value < s.value_min) continue;
    const bool inside = s.hue_min_deg <= s.hue_max_deg
                            ? (hue >= s.hue_min_deg && hue <= s.hue_max_deg)
                            : (hue >= s.hue_min_deg || hue <= s.hue_max_deg);  // wraps through 0
    if (inside) return s.colour;
  }
  return hal::ColourClass::none;
}

HueSegmenter::HueSegmenter(const hal::MarkerModel& marker, double water_correction)
    : lut_(1u << 18), water_correction_(std::clamp(water_correction, 0.0, 1.0)) {
  for (int c = 0; c < 3; ++c) {
    for (int v = 0; v < 256; ++v) gain_table_[c][v] = static_cast<std::uint8_t>(v);
  }
  // Each 6-bit cell is classified by its centre colour (the 4 grey levels it spans average to
  // +1.5).
  for (int b = 0; b < 64; ++b) {
    for (int g = 0; g < 64; ++g) {
      for (int r = 0; r < 64; ++r) {
        lut_[(b << 12) | (g << 6) | r] = static_cast<std::uint8_t>(
            classify_exact(marker, b * 4 + 1.5, g * 4 + 1.5, r * 4 + 1.5));
      }
    }
  }
}

namespace {
constexpr double kMaxGain = 2.0;
}  // namespace

void HueSegmenter::update_gains(const cv::Mat& bgr) {
  // The scene's median per channel, on a sparse grid: mostly water, backplate and sea floor,
  // all under the same cast; the spheres are too small to move it.
  constexpr int kStep = 4;
  for (auto& h : histogram_) h.fill(0);
  std::uint32_t n = 0;
  for (int v = kStep / 2; v < bgr.rows; v += kStep) {
    const std::uint8_t* in = bgr.ptr<std::uint8_t>(v);
    for (int u = kStep / 2; u < bgr.cols; u += kStep, ++n) {
      const std::uint8_t* p = in + 3 * u;
      ++histogram_[0][p[0]];
      ++histogram_[1][p[1]];
      ++histogram_[2][p[2]];
    }
  }
  std::array<double, 3> median{};
  for (int c = 0; c < 3; ++c) {
    std::uint32_t sum = 0;
    int v = 0;
    while (v < 255 && (sum += histogram_[c][v]) < n / 2) ++v;
    median[c] = std::max(8.0, static_cast<double>(v));
  }
  // Normalised to the mean of the three so that brightness is left to the value floors.
  const double mean = (median[0] + median[1] + median[2]) / 3.0;
  for (int c = 0; c < 3; ++c) {
    // Bounded: in dark, deep-blue water a near-empty red channel would otherwise be multiplied
    // into noise.
    gains_[c] = std::clamp(std::pow(mean / median[c], water_correction_), 1.0 / kMaxGain, kMaxGain);
    for (int v = 0; v < 256; ++v) {
      gain_table_[c][v] = static_cast<std::uint8_t>(std::min(255.0, std::round(gains_[c] * v)));
    }
  }
}

void HueSegmenter::segment(const cv::Mat& bgr, cv::Mat& labels) {
  CV_Assert(bgr.type() == CV_8UC3);
  labels.create(bgr.rows, bgr.cols, CV_8UC1);
  const std::uint8_t* lut = lut_.data();
  if (water_correction_ <= 0.0) {
    for (int v = 0; v < bgr.rows; ++v) {
      const std::uint8_t* in = bgr.ptr<std::uint8_t>(v);
      std::uint8_t* out = labels.ptr<std::uint8_t>(v);
      for (int u = 0; u < bgr.cols; ++u, in += 3) out[u] = lut[index(in[0], in[1], in[2])];
    }
    return;
  }
  update_gains(bgr);
  const std::uint8_t* gb = gain_table_[0].data();
  const std::uint8_t* gg = gain_table_[1].data();
  const std::uint8_t* gr = gain_table_[2].data();
  for (int v = 0; v < bgr.rows; ++v) {
    const std::uint8_t* in = bgr.ptr<std::uint8_t>(v);
    std::uint8_t* out = labels.ptr<std::uint8_t>(v);
    for (int u = 0; u < bgr.cols; ++u, in += 3) {
      out[u] = lut[index(gb[in[0]], gg[in[1]], gr[in[2]])];
    }
  }
}

}  // namespace rovctl::estimator
