// The veil shows most on the background: it follows each ray's distance to the background plane,
// through a transmittance table rather than three exp per pixel.
#include "hal/mock/water_optics.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, TurbidWater& w) {
  v.param("attenuation_rgb_per_m", w.attenuation_rgb_per_m,
          {"1/m", 0.0, 10.0,
           "beam attenuation c of red, green and blue light (Jerlov coastal water: red most)"});
  v.param("veil_rgb", w.veil_rgb,
          {"-", 0.0, 1.0, "backscatter (veiling light) at infinite range, linear RGB"});
  v.param("background_behind_marker_m", w.background_behind_marker_m,
          {"m", 0.0, 50.0, "the background plane (station face, floor) behind the marker"});
  v.param("open_water_m", w.open_water_m,
          {"m", 0.1, 100.0, "range seen by rays that miss the background plane"});
}

WaterOptics::WaterOptics(const TurbidWater& water)
    : water_(water),
      c_per_m_(water.attenuation_rgb_per_m.cast<float>()),
      veil_(water.veil_rgb.cast<float>()) {
  step_m_ = static_cast<float>(water_.open_water_m / (kSteps - 1));
  for (int i = 0; i < kSteps; ++i) {
    const float d = step_m_ * static_cast<float>(i);
    for (int ch = 0; ch < 3; ++ch) transmittance_[i][ch] = std::exp(-c_per_m_[ch] * d);
  }
}

Eigen::Vector3f WaterOptics::through(const Eigen::Vector3f& rgb, float distance_m) const {
  Eigen::Vector3f out;
  for (int ch = 0; ch < 3; ++ch) {
    const float t = std::exp(-c_per_m_[ch] * distance_m);
    out[ch] = rgb[ch] * t + veil_[ch] * (1.0f - t);
  }
  return out;
}

void WaterOptics::draw_background(const Eigen::Isometry3d& T_cam_marker,
                                  const Eigen::Vector3f* rays, const Eigen::Vector3f* row_rgb,
                                  const std::uint8_t* to_srgb8, cv::Mat& out_bgr) const {
  // The plane z_marker = behind, in the camera frame: n . p = n . p0.
  const Eigen::Vector3f n = T_cam_marker.linear().col(2).cast<float>();
  const float n_p0 = static_cast<float>(n.cast<double>().dot(
      T_cam_marker * Eigen::Vector3d(0.0, 0.0, water_.background_behind_marker_m)));
  const float max_m = static_cast<float>(water_.open_water_m);
  const float inv_step = 1.0f / step_m_;
  const int w = out_bgr.cols;
  auto quantise = [to_srgb8](float x) {
    const int i = static_cast<int>(x * 4095.0f + 0.5f);
    return to_srgb8[std::clamp(i, 0, 4095)];
  };
  // The veil and the background are smooth: one colour per 2x2 pixels (a fraction of a grey
  // level apart) costs a quarter of the per-pixel work.
  const int h = out_bgr.rows;
  for (int v = 0; v < h; v += 2) {
    cv::Vec3b* row0 = out_bgr.ptr<cv::Vec3b>(v);
    cv::Vec3b* row1 = out_bgr.ptr<cv::Vec3b>(std::min(v + 1, h - 1));
    const Eigen::Vector3f* ray = rays + static_cast<std::size_t>(v) * w;
    const Eigen::Vector3f own = row_rgb[v];
    // Along the unit-z ray the plane is at depth t; behind the camera or parallel: open water
    // (returned as a negative distance).
    auto plane_m = [&](int u) {
      const float n_d = n.dot(ray[u]);
      const float t = n_d != 0.0f ? n_p0 / n_d : -1.0f;
      const float dist = t * ray[u].norm();
      return t > 0.0f && dist < max_m ? dist : -1.0f;
    };
    for (int u = 0; u < w; u += 2) {
      float dist = plane_m(u);
      if (dist < 0.0f) dist = max_m;
      const Eigen::Vector3f& tr =
          transmittance_[std::min(kSteps - 1, static_cast<int>(dist * inv_step + 0.5f))];
      const cv::Vec3b bgr(quantise(own.z() * tr.z() + veil_.z() * (1.0f - tr.z())),
                          quantise(own.y() * tr.y() + veil_.y() * (1.0f - tr.y())),
                          quantise(own.x() * tr.x() + veil_.x() * (1.0f - tr.x())));
      const int u1 = std::min(u + 1, w - 1);
      row0[u] = row0[u1] = row1[u] = row1[u1] = bgr;
    }
  }
}

}  // namespace rovctl::hal::mock
