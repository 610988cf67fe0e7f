// Ray-cast renderer of the marker scene. The per-pixel rays, the background and a noise texture
// are computed once, so a clear frame costs a copy, the spheres' bounding boxes and two saturating
// adds; a scenario adds its objects to one far-to-near draw list and its camera effects after.
#include "hal/mock/scene_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "hal/mock/passing_bar.hpp"
#include "hal/model/sphere_rim.hpp"

namespace rovctl::hal::mock {
namespace {

constexpr int kNoiseMargin = 64;  // the noise texture is this much larger than the image
constexpr int kMaxSpheres = 8;
static_assert(kMaxSpheres <= kMaxShadowCasters, "every sphere casts a shadow in the side light");

// Everything a frame draws, painted far to near so that nearer things cover farther ones.
enum class ItemKind : std::uint8_t { sphere, bubble, particle, bar, strut };
struct DrawItem {
  double depth_m;
  Eigen::Vector3d centre_cam_m;
  double radius_m;
  ItemKind kind;
  int index;
};
constexpr int kMaxDrawItems = kMaxSpheres + kMaxBubbles + kMaxParticles + 2;

// Farthest first; ties in a fixed order, so the spheres alone come out as the stable
// farthest-first sort they always had.
bool farther(const DrawItem& a, const DrawItem& b) {
  if (a.depth_m != b.depth_m) return a.depth_m > b.depth_m;
  if (a.kind != b.kind) return a.kind < b.kind;
  return a.index < b.index;
}

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

// The light a frame's surfaces see: the clear scene's lamp over the rig, or the side light; and
// the water they are seen through, when turbid.
struct SceneRenderer::FrameLighting {
  bool side = false;
  SideLighting side_light;
  const WaterOptics* water = nullptr;
};

SceneRenderer::SceneRenderer(const CameraModel& camera, const MarkerModel& marker,
                             const RenderOptions& options)
    : SceneRenderer(camera, marker, options, SceneConditions{}) {}

SceneRenderer::SceneRenderer(const CameraModel& camera, const MarkerModel& marker,
                             const RenderOptions& options, const SceneConditions& scene)
    : camera_(camera), marker_(marker), options_(options), scene_(scene) {
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
  const ScenarioParams& sp = scene_.params;
  // A camera at high gain: the same noise texture, scaled.
  const double noise_sigma = scene_.scenario == Scenario::noisy
                                 ? options_.noise_sigma * sp.noisy.noise_gain
                                 : options_.noise_sigma;
  if (noise_sigma > 0.0) {
    cv::Mat noise(h + kNoiseMargin, w + kNoiseMargin, CV_32FC3);
    cv::RNG rng(0x5EED);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, noise_sigma);
    noise.convertTo(noise_plus_, CV_8UC3);  // saturates negatives to 0
    cv::Mat negated = -noise;
    negated.convertTo(noise_minus_, CV_8UC3);
  }
  switch (scene_.scenario) {
    case Scenario::turbid:
      turbid_.emplace(sp.turbid);
      background_row_rgb_.resize(static_cast<std::size_t>(h));
      for (int v = 0; v < h; ++v) {
        const double a = h > 1 ? static_cast<double>(v) / (h - 1) : 0.0;
        background_row_rgb_[static_cast<std::size_t>(v)] =
            ((1.0 - a) * options_.background_top_rgb + a * options_.background_bottom_rgb)
                .cast<float>();
      }
      break;
    case Scenario::bubbles:
      bubbles_.emplace(sp.bubbles, scene_.seed);
      break;
    case Scenario::noisy:
      compression_.emplace(sp.noisy.jpeg_quality, sp.noisy.chroma_subsampling);
      break;
    case Scenario::exposure:
      exposure_.emplace();
      break;
    case Scenario::clear:
    case Scenario::side_light:
    case Scenario::occluders:
      break;
  }
}

void SceneRenderer::shade_sphere(const MarkerSphere& sphere, const Eigen::Vector3d& centre_cam_m,
                                 const FrameLighting& lighting, int self, cv::Mat& out_bgr) const {
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
  const SideLighting& side = lighting.side_light;
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
      Eigen::Vector3f rgb;
      const float dist = p.norm();
      if (!lighting.side) {
        const float diffuse = std::max(0.0f, n.dot(light));
        rgb = albedo * (ambient + (1.0f - ambient) * diffuse);
        if (options_.highlights) {
          const Eigen::Vector3f half = (light - p / dist).normalized();
          const float s = std::max(0.0f, n.dot(half));
          const float s2 = s * s, s4 = s2 * s2, s8 = s4 * s4, s16 = s8 * s8, s32 = s16 * s16;
          rgb.array() += 0.8f * s32 * s16;  // a tight white highlight (Blinn-Phong, exponent 48)
        }
      } else {
        // Only the light that the strut and the other spheres let through reaches p.
        const float diffuse = std::max(0.0f, n.dot(side.to_light));
        const bool lit = diffuse > 0.0f && !side.shadowed(p, self);
        rgb = albedo * (side.ambient + (lit ? side.intensity * diffuse : 0.0f));
        if (options_.highlights && lit) {
          const Eigen::Vector3f half = (side.to_light - p / dist).normalized();
          const float s = std::max(0.0f, n.dot(half));
          const float s2 = s * s, s4 = s2 * s2, s8 = s4 * s4, s16 = s8 * s8, s32 = s16 * s16;
          rgb.array() += 0.8f * side.intensity * s32 * s16;
        }
      }
      if (att > 0.0f) {
        for (int i = 0; i < 3; ++i) {
          const float f = std::exp(-k_rgb[i] * dist);
          rgb[i] = rgb[i] * f + water[i] * (1.0f - f);
        }
      }
      if (lighting.water != nullptr) rgb = lighting.water->through(rgb, dist);
      auto q = [this](float x) {
        const int i = static_cast<int>(x * 4095.0f + 0.5f);
        return to_srgb8_[static_cast<std::size_t>(std::clamp(i, 0, 4095))];
      };
      row[u] = cv::Vec3b(q(rgb.z()), q(rgb.y()), q(rgb.x()));
    }
  }
}

void SceneRenderer::shade_rod(const Rod& rod, const Eigen::Vector3f& albedo,
                              const FrameLighting& lighting, cv::Mat& out_bgr) const {
  const Eigen::Vector3f light = lighting.side ? lighting.side_light.to_light
                                              : Eigen::Vector3f(0.35f, -0.8f, -0.5f).normalized();
  const float ambient =
      lighting.side ? lighting.side_light.ambient : static_cast<float>(options_.ambient);
  const float direct = lighting.side ? lighting.side_light.intensity : 1.0f - ambient;
  const int w = camera_.width_px, h = camera_.height_px;
  auto q = [this](float x) {
    const int i = static_cast<int>(x * 4095.0f + 0.5f);
    return to_srgb8_[static_cast<std::size_t>(std::clamp(i, 0, 4095))];
  };
  // A long rod crosses the image anywhere, so tiles are culled first: a tile's rays lie within
  // tile_angle of its centre ray (twice the pixel pitch, for lens distortion), so its distance
  // from the rod's axis can shrink by at most tile_angle times the farthest reach of the rod.
  constexpr int kTile = 8;
  const float tile_angle =
      2.0f * kTile * 0.7072f / static_cast<float>(std::min(camera_.fx_px, camera_.fy_px));
  const float margin = rod.radius_m + tile_angle * (rod.centre_m.norm() + rod.half_length_m);
  for (int v0 = 0; v0 < h; v0 += kTile) {
    const int v1 = std::min(v0 + kTile, h);
    for (int u0 = 0; u0 < w; u0 += kTile) {
      const int u1 = std::min(u0 + kTile, w);
      const Eigen::Vector3f d =
          rays_[static_cast<std::size_t>((v0 + v1) / 2) * w + (u0 + u1) / 2].normalized();
      const Eigen::Vector3f across = d.cross(rod.axis);
      const float sine = across.norm();
      if (sine > 1e-4f && std::abs(rod.centre_m.dot(across)) > margin * sine) continue;
      for (int v = v0; v < v1; ++v) {
        cv::Vec3b* row = out_bgr.ptr<cv::Vec3b>(v);
        const Eigen::Vector3f* rays = rays_.data() + static_cast<std::size_t>(v) * w;
        for (int u = u0; u < u1; ++u) {
          float t = 0.0f;
          Eigen::Vector3f n;
          if (!intersect(rod, rays[u], t, n)) continue;
          Eigen::Vector3f rgb = albedo * (ambient + direct * std::max(0.0f, n.dot(light)));
          if (lighting.water != nullptr) rgb = lighting.water->through(rgb, t * rays[u].norm());
          row[u] = cv::Vec3b(q(rgb.z()), q(rgb.y()), q(rgb.x()));
        }
      }
    }
  }
}

void SceneRenderer::render(const Eigen::Isometry3d& T_cam_marker, std::uint64_t noise_seed,
                           double time_s, cv::Mat& out_bgr) const {
  draw_scene(T_cam_marker, time_s, out_bgr);
  sense(noise_seed, time_s, out_bgr);
}

void SceneRenderer::render_exposed(const Eigen::Isometry3d* T_cam_marker, int count,
                                   std::uint64_t noise_seed, double time_s, cv::Mat& out_bgr,
                                   ExposureScratch& scratch) const {
  if (count <= 1) {
    render(T_cam_marker[0], noise_seed, time_s, out_bgr);
    return;
  }
  // Averaged in 8-bit sRGB rather than linear light: a smeared sphere's colour fades a little
  // faster along the smear than a real sensor's would, which errs against the estimator.
  // Plain loops: OpenCV's add and convertTo allocated on every call here.
  const int h = camera_.height_px, n = camera_.width_px * 3;
  scratch.accumulator.create(h, camera_.width_px, CV_32FC3);
  for (int v = 0; v < h; ++v) {
    float* a = scratch.accumulator.ptr<float>(v);
    std::fill(a, a + n, 0.0f);
  }
  for (int k = 0; k < count; ++k) {
    draw_scene(T_cam_marker[k], time_s, scratch.view);
    for (int v = 0; v < h; ++v) {
      float* a = scratch.accumulator.ptr<float>(v);
      const std::uint8_t* p = scratch.view.ptr<std::uint8_t>(v);
      for (int i = 0; i < n; ++i) a[i] += p[i];
    }
  }
  out_bgr.create(h, camera_.width_px, CV_8UC3);
  const float scale = 1.0f / static_cast<float>(count);
  for (int v = 0; v < h; ++v) {
    const float* a = scratch.accumulator.ptr<float>(v);
    std::uint8_t* o = out_bgr.ptr<std::uint8_t>(v);
    for (int i = 0; i < n; ++i) o[i] = static_cast<std::uint8_t>(a[i] * scale + 0.5f);
  }
  sense(noise_seed, time_s, out_bgr);
}

void SceneRenderer::draw_scene(const Eigen::Isometry3d& T_cam_marker, double time_s,
                               cv::Mat& out_bgr) const {
  out_bgr.create(camera_.height_px, camera_.width_px, CV_8UC3);
  FrameLighting lighting;
  if (turbid_) {
    lighting.water = &*turbid_;
    turbid_->draw_background(T_cam_marker, rays_.data(), background_row_rgb_.data(),
                             to_srgb8_.data(), out_bgr);
  } else {
    background_bgr_.copyTo(out_bgr);
  }
  const ScenarioParams& sp = scene_.params;
  std::array<DrawItem, kMaxDrawItems> items;
  int n = 0;
  const int spheres = static_cast<int>(std::min<std::size_t>(marker_.spheres.size(), kMaxSpheres));
  for (int i = 0; i < spheres; ++i) {
    const Eigen::Vector3d c = T_cam_marker * marker_.spheres[i].centre_marker_m;
    items[n++] = {c.norm(), c, marker_.spheres[i].radius_m, ItemKind::sphere, i};
  }
  Rod bar, strut;
  if (scene_.scenario == Scenario::side_light) {
    lighting.side = true;
    lighting.side_light = side_lighting(sp.side_light, T_cam_marker);
    lighting.side_light.sphere_count = spheres;
    for (int i = 0; i < spheres; ++i) {
      lighting.side_light.sphere_centre_m[i] = items[i].centre_cam_m.cast<float>();
      lighting.side_light.sphere_radius_m[i] = static_cast<float>(items[i].radius_m);
    }
    strut = lighting.side_light.strut;
    if (strut.radius_m > 0.0f) {
      items[n++] = {rod_depth_m(strut), Eigen::Vector3d::Zero(), 0.0, ItemKind::strut, 0};
    }
  }
  if (scene_.scenario == Scenario::occluders && sp.occluders.radius_m > 0.0) {
    bar = bar_in_camera(sp.occluders, T_cam_marker, time_s);
    items[n++] = {rod_depth_m(bar), Eigen::Vector3d::Zero(), 0.0, ItemKind::bar, 0};
  }
  if (bubbles_) {
    for (int i = 0; i < bubbles_->bubble_count(); ++i) {
      const Speck s = bubbles_->bubble(i, time_s);
      const Eigen::Vector3d c = T_cam_marker * s.centre_marker_m;
      if (c.z() > 0.05) items[n++] = {c.norm(), c, s.radius_m, ItemKind::bubble, i};
    }
    for (int i = 0; i < bubbles_->particle_count(); ++i) {
      const Speck s = bubbles_->particle(i, time_s);
      const Eigen::Vector3d c = T_cam_marker * s.centre_marker_m;
      if (c.z() > 0.05) items[n++] = {c.norm(), c, s.radius_m, ItemKind::particle, i};
    }
  }
  std::sort(items.begin(), items.begin() + n, farther);
  for (int k = 0; k < n; ++k) {
    const DrawItem& it = items[k];
    switch (it.kind) {
      case ItemKind::sphere:
        shade_sphere(marker_.spheres[it.index], it.centre_cam_m, lighting, it.index, out_bgr);
        break;
      case ItemKind::bubble:
        bubbles_->draw_bubble(camera_, it.centre_cam_m, it.radius_m, out_bgr);
        break;
      case ItemKind::particle:
        bubbles_->draw_particle(camera_, it.centre_cam_m, it.radius_m, out_bgr);
        break;
      case ItemKind::bar:
        shade_rod(bar, sp.occluders.albedo_rgb.cast<float>(), lighting, out_bgr);
        break;
      case ItemKind::strut:
        shade_rod(strut, sp.side_light.strut_albedo_rgb.cast<float>(), lighting, out_bgr);
        break;
    }
  }
}

void SceneRenderer::sense(std::uint64_t noise_seed, double time_s, cv::Mat& out_bgr) const {
  const ScenarioParams& sp = scene_.params;
  // The sensor records the exposed light, then adds its noise; the encoder compresses last.
  if (exposure_) exposure_->apply(exposure_gain(sp.exposure, time_s), out_bgr);
  if (!noise_plus_.empty()) {
    const std::uint64_t h = splitmix64(noise_seed);
    const cv::Rect roi(static_cast<int>(h % kNoiseMargin),
                       static_cast<int>((h >> 16) % kNoiseMargin), camera_.width_px,
                       camera_.height_px);
    cv::add(out_bgr, noise_plus_(roi), out_bgr);
    cv::subtract(out_bgr, noise_minus_(roi), out_bgr);
  }
  if (compression_) compression_->apply(out_bgr);
}

std::uint64_t right_noise_seed(std::uint64_t noise_seed) {
  return splitmix64(noise_seed ^ 0xA5A5A5A5ull);
}

void render_stereo(const SceneRenderer& left, const SceneRenderer& right, const StereoRig& rig,
                   const Eigen::Isometry3d& T_cl_marker, std::uint64_t noise_seed, double time_s,
                   cv::Mat& left_bgr, cv::Mat& right_bgr) {
  left.render(T_cl_marker, noise_seed, time_s, left_bgr);
  right.render(rig.T_cr_cl * T_cl_marker, right_noise_seed(noise_seed), time_s, right_bgr);
}

void render_stereo(const SceneRenderer& left, const SceneRenderer& right, const StereoRig& rig,
                   const Eigen::Isometry3d& T_cl_marker, std::uint64_t noise_seed,
                   cv::Mat& left_bgr, cv::Mat& right_bgr) {
  render_stereo(left, right, rig, T_cl_marker, noise_seed, 0.0, left_bgr, right_bgr);
}

}  // namespace rovctl::hal::mock
