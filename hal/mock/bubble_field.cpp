// Bubbles and particles are laid out once from the seed; a frame only evaluates positions at its
// time and blends small discs, so the field costs nothing at start-up beyond two fixed arrays.
#include "hal/mock/bubble_field.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace rovctl::hal::mock {
namespace {

double wrap(double x, double lo, double hi) {
  const double span = hi - lo;
  if (span <= 0.0) return lo;
  const double r = std::fmod(x - lo, span);
  return lo + (r < 0.0 ? r + span : r);
}

void check_range(double lo, double hi, const char* lo_key, const char* hi_key) {
  if (lo > hi) {
    throw std::invalid_argument(std::string("sim.scenarios.bubbles.") + lo_key + " (" +
                                std::to_string(lo) + ") is greater than " + hi_key + " (" +
                                std::to_string(hi) + ")");
  }
}

// Nearer than near_m, or far outside any lens's field (where the distortion polynomial runs
// away), nothing is drawn.
bool in_front(const Eigen::Vector3d& p, double near_m) {
  return p.z() >= near_m && std::abs(p.x()) < 3.0 * p.z() && std::abs(p.y()) < 3.0 * p.z();
}

// Blends `target` into the pixel with opacity a.
inline void blend(cv::Vec3b& px, float a, float target) {
  for (int ch = 0; ch < 3; ++ch) {
    const float v = px[ch] + a * (target - px[ch]);
    px[ch] = static_cast<std::uint8_t>(std::clamp(v + 0.5f, 0.0f, 255.0f));
  }
}

}  // namespace

void describe(ParamVisitor& v, BubbleParams& p) {
  v.param("bubble_count", p.bubble_count, {"-", 0, kMaxBubbles, "number of rising bubbles"});
  v.param("bubble_radius_min_m", p.bubble_radius_min_m,
          {"m", 0.0001, 0.05, "smallest bubble radius"});
  v.param("bubble_radius_max_m", p.bubble_radius_max_m,
          {"m", 0.0001, 0.05, "largest bubble radius"});
  v.param("rise_speed_min_mps", p.rise_speed_min_mps,
          {"m/s", 0.0, 2.0, "slowest rise speed (air bubbles of 1-5 mm: ~0.2-0.3 m/s)"});
  v.param("rise_speed_max_mps", p.rise_speed_max_mps, {"m/s", 0.0, 2.0, "fastest rise speed"});
  v.param("wobble_m", p.wobble_m, {"m", 0.0, 0.1, "amplitude of a bubble's zig-zag"});
  v.param("wobble_hz", p.wobble_hz, {"Hz", 0.0, 20.0, "frequency of a bubble's zig-zag"});
  v.param("bubble_volume_min_marker_m", p.bubble_volume_min_marker_m,
          {"m", -10.0, 10.0, "lower corner of the bubbles' box, marker frame"});
  v.param("bubble_volume_max_marker_m", p.bubble_volume_max_marker_m,
          {"m", -10.0, 10.0, "upper corner of the bubbles' box (they rise towards -y)"});
  v.param("rim_opacity", p.rim_opacity, {"-", 0.0, 1.0, "opacity of a bubble's bright rim"});
  v.param("interior_opacity", p.interior_opacity,
          {"-", 0.0, 1.0, "opacity of a bubble's translucent body"});
  v.param("particle_count", p.particle_count,
          {"-", 0, kMaxParticles, "number of floating particles (marine snow)"});
  v.param("particle_radius_min_m", p.particle_radius_min_m,
          {"m", 0.00001, 0.01, "smallest particle radius"});
  v.param("particle_radius_max_m", p.particle_radius_max_m,
          {"m", 0.00001, 0.01, "largest particle radius"});
  v.param("particle_drift_mps", p.particle_drift_mps,
          {"m/s", 0.0, 1.0, "random drift speed of a particle, at most, per axis"});
  v.param("particle_sink_mps", p.particle_sink_mps, {"m/s", -1.0, 1.0, "sinking speed (+y)"});
  v.param("particle_opacity", p.particle_opacity,
          {"-", 0.0, 1.0, "peak opacity of a near, lamp-lit particle"});
  v.param("particle_volume_min_marker_m", p.particle_volume_min_marker_m,
          {"m", -10.0, 10.0, "lower corner of the particles' box, marker frame"});
  v.param("particle_volume_max_marker_m", p.particle_volume_max_marker_m,
          {"m", -10.0, 10.0, "upper corner of the particles' box"});
}

BubbleField::BubbleField(const BubbleParams& params, std::uint64_t seed)
    : p_(params),
      bubble_count_(std::clamp(params.bubble_count, 0, kMaxBubbles)),
      particle_count_(std::clamp(params.particle_count, 0, kMaxParticles)) {
  check_range(p_.bubble_radius_min_m, p_.bubble_radius_max_m, "bubble_radius_min_m",
              "bubble_radius_max_m");
  check_range(p_.rise_speed_min_mps, p_.rise_speed_max_mps, "rise_speed_min_mps",
              "rise_speed_max_mps");
  check_range(p_.particle_radius_min_m, p_.particle_radius_max_m, "particle_radius_min_m",
              "particle_radius_max_m");
  for (int i = 0; i < 3; ++i) {
    check_range(p_.bubble_volume_min_marker_m[i], p_.bubble_volume_max_marker_m[i],
                "bubble_volume_min_marker_m", "bubble_volume_max_marker_m");
    check_range(p_.particle_volume_min_marker_m[i], p_.particle_volume_max_marker_m[i],
                "particle_volume_min_marker_m", "particle_volume_max_marker_m");
  }
  std::mt19937_64 rng(seed ^ 0xB0BB1E5ull);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  auto point_in = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return Eigen::Vector3d(uniform(lo.x(), hi.x()), uniform(lo.y(), hi.y()),
                           uniform(lo.z(), hi.z()));
  };
  for (int i = 0; i < bubble_count_; ++i) {
    Seed& b = bubbles_[static_cast<std::size_t>(i)];
    b.start = point_in(p_.bubble_volume_min_marker_m, p_.bubble_volume_max_marker_m);
    b.radius_m = uniform(p_.bubble_radius_min_m, p_.bubble_radius_max_m);
    b.velocity_mps = {0.0, -uniform(p_.rise_speed_min_mps, p_.rise_speed_max_mps), 0.0};
    b.phase_rad = uniform(0.0, 2.0 * M_PI);
  }
  const double drift = p_.particle_drift_mps;
  for (int i = 0; i < particle_count_; ++i) {
    Seed& s = particles_[static_cast<std::size_t>(i)];
    s.start = point_in(p_.particle_volume_min_marker_m, p_.particle_volume_max_marker_m);
    s.radius_m = uniform(p_.particle_radius_min_m, p_.particle_radius_max_m);
    s.velocity_mps = {uniform(-drift, drift), uniform(-drift, drift) + p_.particle_sink_mps,
                      uniform(-drift, drift)};
    s.phase_rad = 0.0;
  }
}

Speck BubbleField::bubble(int i, double time_s) const {
  const Seed& b = bubbles_[static_cast<std::size_t>(i)];
  const double phase = 2.0 * M_PI * p_.wobble_hz * time_s + b.phase_rad;
  Eigen::Vector3d c = b.start + time_s * b.velocity_mps;
  // A spiralling zig-zag: millimetre bubbles do not rise straight.
  c.x() += p_.wobble_m * std::sin(phase);
  c.z() += p_.wobble_m * std::cos(phase);
  c.y() = wrap(c.y(), p_.bubble_volume_min_marker_m.y(), p_.bubble_volume_max_marker_m.y());
  return {c, b.radius_m};
}

Speck BubbleField::particle(int i, double time_s) const {
  const Seed& s = particles_[static_cast<std::size_t>(i)];
  Eigen::Vector3d c = s.start + time_s * s.velocity_mps;
  for (int k = 0; k < 3; ++k) {
    c[k] = wrap(c[k], p_.particle_volume_min_marker_m[k], p_.particle_volume_max_marker_m[k]);
  }
  return {c, s.radius_m};
}

void BubbleField::draw_bubble(const CameraModel& cam, const Eigen::Vector3d& centre_cam_m,
                              double radius_m, cv::Mat& out_bgr) const {
  Eigen::Vector2d uv;
  if (!in_front(centre_cam_m, 0.05) || !cam.project(centre_cam_m, uv)) return;
  const float r_px = static_cast<float>(cam.fx_px * radius_m / centre_cam_m.z());
  if (r_px < 0.3f) return;
  const float cu = static_cast<float>(uv.x()), cv_ = static_cast<float>(uv.y());
  const int u0 = std::max(0, static_cast<int>(std::floor(cu - r_px - 2.0f)));
  const int u1 = std::min(out_bgr.cols - 1, static_cast<int>(std::ceil(cu + r_px + 2.0f)));
  const int v0 = std::max(0, static_cast<int>(std::floor(cv_ - r_px - 2.0f)));
  const int v1 = std::min(out_bgr.rows - 1, static_cast<int>(std::ceil(cv_ + r_px + 2.0f)));
  const float rim_px = std::max(1.0f, 0.25f * r_px);
  const float rim = static_cast<float>(p_.rim_opacity);
  const float body = static_cast<float>(p_.interior_opacity);
  // A glint where the light source reflects off the upper-left of the wall.
  const float gu = cu - 0.4f * r_px, gv = cv_ - 0.4f * r_px, g_px = 0.18f * r_px;
  for (int v = v0; v <= v1; ++v) {
    cv::Vec3b* row = out_bgr.ptr<cv::Vec3b>(v);
    for (int u = u0; u <= u1; ++u) {
      const float du = static_cast<float>(u) - cu, dv = static_cast<float>(v) - cv_;
      const float dist = std::sqrt(du * du + dv * dv);
      const float cover = std::clamp(r_px + 0.5f - dist, 0.0f, 1.0f);
      if (cover <= 0.0f) continue;
      blend(row[u], cover * (dist > r_px - rim_px ? rim : body), 250.0f);
      if (g_px >= 0.7f) {
        const float eu = static_cast<float>(u) - gu, ev = static_cast<float>(v) - gv;
        if (eu * eu + ev * ev <= g_px * g_px) blend(row[u], 0.8f, 255.0f);
      }
    }
  }
}

void BubbleField::draw_particle(const CameraModel& cam, const Eigen::Vector3d& centre_cam_m,
                                double radius_m, cv::Mat& out_bgr) const {
  Eigen::Vector2d uv;
  if (!in_front(centre_cam_m, 0.08) || !cam.project(centre_cam_m, uv)) return;
  const float r_px =
      std::clamp(static_cast<float>(cam.fx_px * radius_m / centre_cam_m.z()), 0.5f, 3.0f);
  // Lit by the vehicle's lamp: nearer particles are brighter.
  const float a =
      static_cast<float>(p_.particle_opacity * std::clamp(0.5 / centre_cam_m.z(), 0.25, 1.0));
  const float cu = static_cast<float>(uv.x()), cv_ = static_cast<float>(uv.y());
  const int u0 = std::max(0, static_cast<int>(std::floor(cu - r_px - 1.0f)));
  const int u1 = std::min(out_bgr.cols - 1, static_cast<int>(std::ceil(cu + r_px + 1.0f)));
  const int v0 = std::max(0, static_cast<int>(std::floor(cv_ - r_px - 1.0f)));
  const int v1 = std::min(out_bgr.rows - 1, static_cast<int>(std::ceil(cv_ + r_px + 1.0f)));
  for (int v = v0; v <= v1; ++v) {
    cv::Vec3b* row = out_bgr.ptr<cv::Vec3b>(v);
    for (int u = u0; u <= u1; ++u) {
      const float du = static_cast<float>(u) - cu, dv = static_cast<float>(v) - cv_;
      const float cover = std::clamp(r_px + 0.5f - std::sqrt(du * du + dv * dv), 0.0f, 1.0f);
      if (cover > 0.0f) blend(row[u], a * cover, 235.0f);
    }
  }
}

}  // namespace rovctl::hal::mock
