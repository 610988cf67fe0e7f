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

HueSegmenter::HueSegmenter(const hal::MarkerModel& marker) : lut_(1u << 18) {
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

void HueSegmenter::segment(const cv::Mat& bgr, cv::Mat& labels) const {
  CV_Assert(bgr.type() == CV_8UC3);
  labels.create(bgr.rows, bgr.cols, CV_8UC1);
  const std::uint8_t* lut = lut_.data();
  for (int v = 0; v < bgr.rows; ++v) {
    const std::uint8_t* in = bgr.ptr<std::uint8_t>(v);
    std::uint8_t* out = labels.ptr<std::uint8_t>(v);
    for (int u = 0; u < bgr.cols; ++u, in += 3) out[u] = lut[index(in[0], in[1], in[2])];
  }
}

}  // namespace rovctl::estimator
