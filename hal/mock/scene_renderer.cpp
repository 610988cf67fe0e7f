// Ray-cast renderer of the marker scene. The per-pixel rays, the background and a noise texture
// are computed once, so a frame costs a copy, the spheres' bounding boxes and two saturating adds.
#include "hal/mock/scene_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "hal/model/sphere_rim.hpp"

namespace rovctl::hal::mock {
namespace {

constexpr int kNoiseMargin = 64;  // the noise texture is this much larger than the image

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Pixel bounding box of a sphere's silhouette, from points on its rim (distortion included).
bool silhouette_box(const CameraModel& cam, const Eigen::Vector3d& c, double r, cv::Rect& box) {
  SphereRim rim;
  if (!sphere_rim(c, r, rim)) return false;
  double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
  for (int k = 0; k < 24; ++k) {
    Eigen::Vector2d uv;
    if (!cam.project(rim.point(2.0 * M_PI * k / 24.0), uv)) return false;
    u0 = std::min(u0, uv.x());
    u1 = std::max(u1, uv.x());
    v0 = std::min(v0, uv.y());
    v1 = std::max(v1, uv.y());
  }
  // The polygon through 24 rim points lies inside the ellipse; a margin covers the rest.
  const double margin = 0.02 * std::max(u1 - u0, v1 - v0) + 2.0;
  const int x0 = std::max(0, static_cast<int>(std::floor(u0 - margin)));
  const int y0 = std::max(0, static_cast<int>(std::floor(v0 - margin)));
  const int x1 = std::min(cam.width_px - 1, static_cast<int>(std::ceil(u1 + margin)));
  const int y1 = std::min(cam.height_px - 1, static_cast<int>(std::ceil(v1 + margin)));
  if (x1 < x0 || y1 < y0) return false;
  box = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  return true;
}

}  // namespace

void describe(ParamVisitor& v, RenderOptions& o) {
  v.param("background_top_rgb", o.background_top_rgb,
          {"-", 0.0, 1.0, "background colour at the top of the image, linear RGB"});
  v.param("background_bottom_rgb", o.background_bottom_rgb,
          {"-", 0.0, 1.0, "background colour at the bottom of the image, linear RGB"});
  v.param("water_attenuation_per_m", o.water_attenuation_per_m,
          {"1/m", 0.0, 5.0, "attenuation of red light by the water (green, blue less); 0 = clear"});
  v.param("noise_sigma", o.noise_sigma,
          {"grey levels", 0.0, 50.0, "sensor noise standard deviation in 8-bit grey levels"});
  v.param("ambient", o.ambient, {"-", 0.0, 1.0, "ambient fraction of the sphere lighting"});
  v.param("highlights", o.highlights, "specular highlights on the spheres");
}

SceneRenderer::SceneRenderer(const CameraModel& camera, const MarkerModel& marker,
                             const RenderOptions& options)
    : camera_(camera), marker_(marker), options_(options) {
  const int w = camera_.width_px, h = camera_.height_px;
  if (w <= 0 || h <= 0) throw std::invalid_argument("SceneRenderer: empty camera image size");
  rays_.resize(static_cast<std::size_t>(w) * h);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      rays_[static_cast<std::size_t>(v) * w + u] =
          camera_.unproject(Eigen::Vector2d(u, v)).cast<float>();
    }
  }
  to_srgb8_.resize(4096);
  for (int i = 0; i < 4096; ++i) {
    const double x = i / 4095.0;
    const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    to_srgb8_[i] = static_cast<std::uint8_t>(std::clamp(std::lround(s * 255.0), 0L, 255L));
  }
  auto srgb = [this](double x) {
    return to_srgb8_[std::clamp(std::lround(x * 4095.0), 0L, 4095L)];
  };
  background_bgr_.create(h, w, CV_8UC3);
  for (int v = 0; v < h; ++v) {
    const double a = h > 1 ? static_cast<double>(v) / (h - 1) : 0.0;
    const Eigen::Vector3d rgb =
        (1.0 - a) * options_.background_top_rgb + a * options_.background_bottom_rgb;
    const cv::Vec3b bgr(srgb(rgb.z()), srgb(rgb.y()), srgb(rgb.x()));
    for (int u = 0; u < w; ++u) background_bgr_.at<cv::Vec3b>(v, u) = bgr;
  }
  water_rgb_ = 0.5 * (options_.background_top_rgb + options_.background_bottom_rgb);
  if (options_.noise_sigma > 0.0) {
    cv::Mat noise(h + kNoiseMargin, w + kNoiseMargin, CV_32FC3);
    cv::RNG rng(0x5EED);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options_.noise_sigma);
    noise.convertTo(noise_plus_, CV_8UC3);  // saturates negatives to 0
    cv::Mat negated = -noise;
    negated.convertTo(noise_minus_, CV_8UC3);
  }
}

void SceneRenderer::shade_sphere(const MarkerSphere& sphere, const Eigen::Vector3d& centre_cam_m,
                                 cv::Mat& out_bgr) const {
  cv::Rect box;
  if (!silhouette_box(camera_, centre_cam_m, sphere.radius_m, box)) return;
  const Eigen::Vector3f c = centre_cam_m.cast<float>();
  const float r = static_cast<float>(sphere.radius_m);
  const float cc = c.squaredNorm() - r * r;
  // Light from above and behind the camera (a lamp over the rig), so one side is in shade.
  const Eigen::Vector3f light = Eigen::Vector3f(0.35f, -0.8f, -0.5f).normalized();
  const float ambient = static_cast<float>(options_.ambient);
  const Eigen::Vector3f albedo = sphere.albedo_rgb.cast<float>();
  const Eigen::Vector3f water = water_rgb_.cast<float>();
  const float att = static_cast<float>(options_.water_attenuation_per_m);
  // Red is absorbed most, then green, then blue: the blue-green cast of water.
  const Eigen::Vector3f k_rgb(att, 0.3f * att, 0.2f * att);
  const int w = camera_.width_px;
  for (int v = box.y; v < box.y + box.height; ++v) {
    cv::Vec3b* row = out_bgr.ptr<cv::Vec3b>(v);
    const Eigen::Vector3f* rays = rays_.data() + static_cast<std::size_t>(v) * w;
    for (int u = box.x; u < box.x + box.width; ++u) {
      const Eigen::Vector3f& d = rays[u];
      const float a = d.squaredNorm();
      const float b = d.dot(c);
      const float disc = b * b - a * cc;
      if (disc <= 0.0f) continue;
      const float t = (b - std::sqrt(disc)) / a;
      const Eigen::Vector3f p = t * d;
      const Eigen::Vector3f n = (p - c) / r;
      const float diffuse = std::max(0.0f, n.dot(light));
      Eigen::Vector3f rgb = albedo * (ambient + (1.0f - ambient) * diffuse);
      const float dist = p.norm();
      if (options_.highlights) {
        const Eigen::Vector3f half = (light - p / dist).normalized();
        const float s = std::max(0.0f, n.dot(half));
        const float s2 = s * s, s4 = s2 * s2, s8 = s4 * s4, s16 = s8 * s8, s32 = s16 * s16;
        rgb.array() += 0.8f * s32 * s16;  // a tight white highlight (Blinn-Phong, exponent 48)
      }
      if (att > 0.0f) {
        for (int i = 0; i < 3; ++i) {
          const float f = std::exp(-k_rgb[i] * dist);
          rgb[i] = rgb[i] * f + water[i] * (1.0f - f);
        }
      }
      auto q = [this](float x) {
        const int i = static_cast<int>(x * 4095.0f + 0.5f);
        return to_srgb8_[static_cast<std::size_t>(std::clamp(i, 0, 4095))];
      };
      row[u] = cv::Vec3b(q(rgb.z()), q(rgb.y()), q(rgb.x()));
    }
  }
}

void SceneRenderer::render(const Eigen::Isometry3d& T_cam_marker, std::uint64_t noise_seed,
                           cv::Mat& out_bgr) const {
  out_bgr.create(camera_.height_px, camera_.width_px, CV_8UC3);
  background_bgr_.copyTo(out_bgr);
  // Far spheres first, so nearer ones cover them.
  std::array<std::pair<double, int>, 8> order{};
  const int n = static_cast<int>(std::min<std::size_t>(marker_.spheres.size(), order.size()));
  for (int i = 0; i < n; ++i) {
    order[i] = {(T_cam_marker * marker_.spheres[i].centre_marker_m).norm(), i};
  }
  for (int i = 1; i < n; ++i) {  // insertion sort, farthest first (n <= 3)
    for (int j = i; j > 0 && order[j - 1].first < order[j].first; --j) {
      std::swap(order[j - 1], order[j]);
    }
  }
  for (int k = 0; k < n; ++k) {
    const MarkerSphere& s = marker_.spheres[order[k].second];
    shade_sphere(s, T_cam_marker * s.centre_marker_m, out_bgr);
  }
  if (!noise_plus_.empty()) {
    const std::uint64_t h = splitmix64(noise_seed);
    const cv::Rect roi(static_cast<int>(h % kNoiseMargin),
                       static_cast<int>((h >> 16) % kNoiseMargin), camera_.width_px,
                       camera_.height_px);
    cv::add(out_bgr, noise_plus_(roi), out_bgr);
    cv::subtract(out_bgr, noise_minus_(roi), out_bgr);
  }
}

void render_stereo(const SceneRenderer& left, const SceneRenderer& right, const StereoRig& rig,
                   const Eigen::Isometry3d& T_cl_marker, std::uint64_t noise_seed,
                   cv::Mat& left_bgr, cv::Mat& right_bgr) {
  left.render(T_cl_marker, noise_seed, left_bgr);
  right.render(rig.T_cr_cl * T_cl_marker, splitmix64(noise_seed ^ 0xA5A5A5A5ull), right_bgr);
}

}  // namespace rovctl::hal::mock
