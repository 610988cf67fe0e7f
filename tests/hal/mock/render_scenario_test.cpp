// The imaging scenarios: each renders what it claims, measurably (range-dependent colour loss and
// veil, a dark side and cast shadows, rising bubbles, a passing occluder, noise and block seams,
// a drifting exposure), deterministically, and the mock camera renders the world's scenario at
// the frame's capture time.
#include "hal/mock/render_scenario.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "hal/mock/mock_stereo_camera.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/model/pose.hpp"
#include "render_test_support.hpp"
#include "sim_test_support.hpp"

namespace rovctl::hal::mock {
namespace {

using test::ahead;
using test::distorted_camera;

RenderOptions quiet() {
  RenderOptions o;
  o.noise_sigma = 0.0;
  return o;
}

SceneConditions conditions(Scenario s, const ScenarioParams& p = {}, std::uint64_t seed = 7) {
  SceneConditions c;
  c.scenario = s;
  c.params = p;
  c.seed = seed;
  return c;
}

// One camera in one scenario (building a renderer costs far more than a frame).
class View {
 public:
  explicit View(const SceneConditions& scene, const RenderOptions& options = quiet())
      : renderer_(distorted_camera(), MarkerModel::standard(), options, scene) {}
  cv::Mat at(const Eigen::Isometry3d& T, double time_s, std::uint64_t noise_seed = 1) const {
    cv::Mat image;
    renderer_.render(T, noise_seed, time_s, image);
    return image;
  }

 private:
  SceneRenderer renderer_;
};

cv::Mat render(const SceneConditions& scene, const Eigen::Isometry3d& T, double time_s,
               const RenderOptions& options = quiet()) {
  return View(scene, options).at(T, time_s);
}

// A sphere's image: centre and (approximate) radius in pixels.
struct Disc {
  double u = 0.0, v = 0.0, r_px = 0.0;
};

Disc disc_of(const Eigen::Isometry3d& T, const MarkerSphere& s) {
  const CameraModel cam = distorted_camera();
  const Eigen::Vector3d c = T * s.centre_marker_m;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  EXPECT_TRUE(cam.project(c, uv));
  return {uv.x(), uv.y(), cam.fx_px * s.radius_m / c.z()};
}

// Mean of channel `ch` over the pixels within `frac` of the disc's radius whose horizontal
// offset from the centre, in radii, lies in [du_min, du_max].
double disc_mean(const cv::Mat& image, const Disc& d, int ch, double frac = 0.6,
                 double du_min = -2.0, double du_max = 2.0) {
  double sum = 0.0;
  int n = 0;
  const int r = static_cast<int>(std::ceil(d.r_px));
  for (int v = static_cast<int>(d.v) - r; v <= static_cast<int>(d.v) + r; ++v) {
    for (int u = static_cast<int>(d.u) - r; u <= static_cast<int>(d.u) + r; ++u) {
      const double du = (u - d.u) / d.r_px, dv = (v - d.v) / d.r_px;
      if (du * du + dv * dv > frac * frac || du < du_min || du > du_max) continue;
      if (u < 0 || v < 0 || u >= image.cols || v >= image.rows) continue;
      sum += image.at<cv::Vec3b>(v, u)[ch];
      ++n;
    }
  }
  EXPECT_GT(n, 0);
  return n > 0 ? sum / n : 0.0;
}

int channel_of(const MarkerSphere& s) {
  return s.colour == ColourClass::red ? 2 : s.colour == ColourClass::green ? 1 : 0;
}

// Pixels that look like the sphere's colour: the dominant channel well above both others.
int coloured_pixels(const cv::Mat& image, int ch) {
  int n = 0;
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const cv::Vec3b p = image.at<cv::Vec3b>(v, u);
      if (p[ch] > p[(ch + 1) % 3] + 40 && p[ch] > p[(ch + 2) % 3] + 40) ++n;
    }
  }
  return n;
}

double channel_mean(const cv::Mat& image, int ch, const cv::Rect& roi) {
  return cv::mean(image(roi))[ch];
}

TEST(RenderScenario, NamesRoundTripAndUnknownNamesAreRejected) {
  EXPECT_EQ(scenario_names().size(), 7u);
  for (const std::string& name : scenario_names()) {
    Scenario s = Scenario::clear;
    ASSERT_TRUE(scenario_from_name(name, s)) << name;
    EXPECT_EQ(name, to_string(s));
  }
  Scenario s = Scenario::turbid;
  EXPECT_FALSE(scenario_from_name("murky", s));
  EXPECT_EQ(s, Scenario::turbid);
  try {
    scene_conditions("murky", ScenarioParams{}, 1);
    ADD_FAILURE() << "an unknown scenario was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sim.scenario"), std::string::npos) << what;
    EXPECT_NE(what.find("murky"), std::string::npos) << what;
    EXPECT_NE(what.find("side_light"), std::string::npos) << what;
  }
  EXPECT_EQ(scene_conditions("noisy", ScenarioParams{}, 1).scenario, Scenario::noisy);
}

TEST(RenderScenario, ClearIsTheRendererWithoutScenarioAtAnyTime) {
  const CameraModel cam = distorted_camera();
  const SceneRenderer plain(cam, MarkerModel::standard(), RenderOptions{});
  const SceneRenderer clear(cam, MarkerModel::standard(), RenderOptions{},
                            conditions(Scenario::clear, ScenarioParams{}, 99));
  cv::Mat a, b;
  plain.render(ahead(0.7), 5, a);
  clear.render(ahead(0.7), 5, 21.5, b);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(RenderScenario, TurbidRedFadesWithRangeFasterThanBlue) {
  const MarkerModel marker = MarkerModel::standard();
  const MarkerSphere& red = marker.spheres[0];
  const MarkerSphere& blue = marker.spheres[2];
  const View turbid(conditions(Scenario::turbid)), clear(conditions(Scenario::clear));
  auto fade = [&](const View& view, const MarkerSphere& sphere) {
    const int ch = channel_of(sphere);
    const double near = disc_mean(view.at(ahead(0.5), 0.0), disc_of(ahead(0.5), sphere), ch);
    const double far = disc_mean(view.at(ahead(1.5), 0.0), disc_of(ahead(1.5), sphere), ch);
    return far / near;
  };
  const double red_fade = fade(turbid, red);
  const double blue_fade = fade(turbid, blue);
  EXPECT_LT(red_fade, 0.8) << "the red sphere's red should fade over 1 m of turbid water";
  EXPECT_LT(red_fade, blue_fade - 0.1) << "red is attenuated faster than blue";
  // In clear water range alone changes neither.
  EXPECT_GT(fade(clear, red), 0.95);
  EXPECT_GT(fade(clear, blue), 0.95);
}

TEST(RenderScenario, TurbidVeilBrightensTheBackgroundWithRange) {
  const cv::Rect bottom(0, 360, 640, 120);  // below the marker: only background
  const View turbid(conditions(Scenario::turbid)), clear(conditions(Scenario::clear));
  const double near = channel_mean(turbid.at(ahead(0.5), 0.0), 1, bottom);
  const double far = channel_mean(turbid.at(ahead(1.5), 0.0), 1, bottom);
  const double clear_near = channel_mean(clear.at(ahead(0.5), 0.0), 1, bottom);
  const double clear_far = channel_mean(clear.at(ahead(1.5), 0.0), 1, bottom);
  EXPECT_GT(far, near + 6.0) << "more water between camera and background: more veil";
  EXPECT_NEAR(clear_far, clear_near, 0.5);
  // Far enough, the background is the veil's colour alone.
  ScenarioParams p;
  p.turbid.background_behind_marker_m = 40.0;
  p.turbid.open_water_m = 50.0;
  const cv::Mat deep = render(conditions(Scenario::turbid, p), ahead(1.0), 0.0);
  const cv::Scalar m = cv::mean(deep(bottom));
  auto srgb8 = [](double x) {
    return 255.0 * (x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
  };
  EXPECT_NEAR(m[2], srgb8(p.turbid.veil_rgb.x()), 3.0);
  EXPECT_NEAR(m[1], srgb8(p.turbid.veil_rgb.y()), 3.0);
  EXPECT_NEAR(m[0], srgb8(p.turbid.veil_rgb.z()), 3.0);
}

TEST(RenderScenario, SideLightLeavesOneSideOfEachSphereDark) {
  const MarkerModel marker = MarkerModel::standard();
  const Eigen::Isometry3d T = ahead(0.8);
  // Without cast shadows, so that the strut's band does not darken the lit side.
  ScenarioParams p;
  p.side_light.cast_shadows = false;
  const cv::Mat side = render(conditions(Scenario::side_light, p), T, 0.0);
  const cv::Mat clear = render(conditions(Scenario::clear), T, 0.0);
  for (const MarkerSphere& s : marker.spheres) {
    const Disc d = disc_of(T, s);
    const int ch = channel_of(s);
    // The light comes from the marker's left: the left third lit, the right third in shade.
    const double lit = disc_mean(side, d, ch, 0.85, -1.0, -0.35);
    const double shade = disc_mean(side, d, ch, 0.85, 0.35, 1.0);
    EXPECT_GT(lit, 2.0 * shade) << s.name << ": lit " << lit << ", shade " << shade;
    // The clear scene's lamp over the rig lights both halves.
    EXPECT_LT(disc_mean(clear, d, ch, 0.85, -1.0, -0.35),
              1.5 * disc_mean(clear, d, ch, 0.85, 0.35, 1.0))
        << s.name;
  }
}

TEST(RenderScenario, SideLightCastsAShadowAcrossASphere) {
  const MarkerModel marker = MarkerModel::standard();
  const Eigen::Isometry3d T = ahead(0.8);
  ScenarioParams no_shadows;
  no_shadows.side_light.cast_shadows = false;
  const cv::Mat shadowed = render(conditions(Scenario::side_light), T, 0.0);
  const cv::Mat unshadowed = render(conditions(Scenario::side_light, no_shadows), T, 0.0);
  // Every pixel the shadows darken lies on a sphere; the strut's band crosses the blue one.
  int darkened = 0, darkened_on_blue = 0;
  const Disc blue = disc_of(T, marker.spheres[2]);
  for (int v = 0; v < shadowed.rows; ++v) {
    for (int u = 0; u < shadowed.cols; ++u) {
      const cv::Vec3b a = shadowed.at<cv::Vec3b>(v, u), b = unshadowed.at<cv::Vec3b>(v, u);
      const int drop = std::max({b[0] - a[0], b[1] - a[1], b[2] - a[2]});
      EXPECT_GE(drop, 0) << "a shadow brightened (" << u << ", " << v << ")";
      if (drop < 40) continue;
      ++darkened;
      if (std::hypot(u - blue.u, v - blue.v) <= blue.r_px + 1.5) ++darkened_on_blue;
    }
  }
  EXPECT_GT(darkened_on_blue, 30) << "the strut's shadow band should cross the blue sphere";
  EXPECT_GE(darkened, darkened_on_blue);
}

TEST(RenderScenario, BubblesAreReproducibleFromSeedAndTime) {
  const Eigen::Isometry3d T = ahead(0.8);
  const View view(conditions(Scenario::bubbles, {}, 3));
  const cv::Mat a = view.at(T, 4.0);
  EXPECT_EQ(cv::norm(a, render(conditions(Scenario::bubbles, {}, 3), T, 4.0), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, view.at(T, 4.2), cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(a, render(conditions(Scenario::bubbles, {}, 4), T, 4.0), cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(a, render(conditions(Scenario::clear), T, 4.0), cv::NORM_L1), 0.0);
}

TEST(RenderScenario, ABubbleRisesThroughTheImage) {
  // One bubble, nothing else, in a thin column 0.3 m in front of the marker.
  ScenarioParams p;
  p.bubbles.bubble_count = 1;
  p.bubbles.particle_count = 0;
  p.bubbles.bubble_radius_min_m = p.bubbles.bubble_radius_max_m = 0.004;
  p.bubbles.bubble_volume_min_marker_m = {-0.01, -0.4, -0.3};
  p.bubbles.bubble_volume_max_marker_m = {0.01, 0.4, -0.3};
  const BubbleField field(p.bubbles, 7);
  // A moment when it is in view and will not wrap to the bottom in the next 0.3 s.
  double t1 = -1.0;
  for (double t = 0.0; t < 10.0 && t1 < 0.0; t += 0.05) {
    const double y = field.bubble(0, t).centre_marker_m.y();
    if (y > -0.05 && y < 0.1) t1 = t;
  }
  ASSERT_GE(t1, 0.0);
  const double t2 = t1 + 0.3;
  ASSERT_LT(field.bubble(0, t2).centre_marker_m.y(), field.bubble(0, t1).centre_marker_m.y());
  const Eigen::Isometry3d T = ahead(0.6);
  const cv::Mat background = render(conditions(Scenario::clear), T, 0.0);
  const View view(conditions(Scenario::bubbles, p));
  auto bubble_row = [&](double t) {
    const cv::Mat img = view.at(T, t);
    double sum_v = 0.0;
    int n = 0;
    for (int v = 0; v < img.rows; ++v) {
      for (int u = 0; u < img.cols; ++u) {
        const cv::Vec3b a = img.at<cv::Vec3b>(v, u), b = background.at<cv::Vec3b>(v, u);
        if (a[1] > b[1] + 20) {  // the bright rim
          sum_v += v;
          ++n;
        }
      }
    }
    EXPECT_GT(n, 10) << "the bubble's rim at t = " << t;
    return n > 0 ? sum_v / n : 0.0;
  };
  // 0.3 s at >= 0.18 m/s is >= 54 mm at 0.3 m from the camera: about 100 px up.
  EXPECT_LT(bubble_row(t2), bubble_row(t1) - 50.0);
}

TEST(RenderScenario, BubblesPassInFrontOfTheSpheres) {
  const MarkerModel marker = MarkerModel::standard();
  const Eigen::Isometry3d T = ahead(0.8);
  const cv::Mat clear = render(conditions(Scenario::clear), T, 0.0);
  const View view(conditions(Scenario::bubbles));
  int frames_with_a_bubble_over_a_sphere = 0;
  for (double t = 0.0; t < 20.0; t += 0.5) {
    const cv::Mat img = view.at(T, t);
    bool covered = false;
    for (const MarkerSphere& s : marker.spheres) {
      const Disc d = disc_of(T, s);
      int changed = 0;
      for (int v = static_cast<int>(d.v - 0.8 * d.r_px); v <= d.v + 0.8 * d.r_px; ++v) {
        for (int u = static_cast<int>(d.u - 0.8 * d.r_px); u <= d.u + 0.8 * d.r_px; ++u) {
          if (std::hypot(u - d.u, v - d.v) > 0.8 * d.r_px) continue;
          const cv::Vec3b a = img.at<cv::Vec3b>(v, u), b = clear.at<cv::Vec3b>(v, u);
          if (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) > 40) {
            ++changed;
          }
        }
      }
      covered = covered || changed >= 5;
    }
    frames_with_a_bubble_over_a_sphere += covered ? 1 : 0;
  }
  EXPECT_GE(frames_with_a_bubble_over_a_sphere, 3);
  EXPECT_LT(frames_with_a_bubble_over_a_sphere, 40) << "bubbles should not hide the marker always";
}

TEST(RenderScenario, ParticlesShowAsSmallBrightSpecks) {
  ScenarioParams p;
  p.bubbles.bubble_count = 0;
  const Eigen::Isometry3d T = ahead(0.8);
  const cv::Mat img = render(conditions(Scenario::bubbles, p), T, 2.0);
  const cv::Mat clear = render(conditions(Scenario::clear), T, 0.0);
  int brighter = 0;
  for (int v = 0; v < img.rows; ++v) {
    for (int u = 0; u < img.cols; ++u) {
      brighter += img.at<cv::Vec3b>(v, u)[1] > clear.at<cv::Vec3b>(v, u)[1] + 15 ? 1 : 0;
    }
  }
  EXPECT_GT(brighter, 100);
  EXPECT_LT(brighter, img.rows * img.cols / 50) << "specks, not a haze";
}

TEST(RenderScenario, OccluderHidesASphereForSomeSeconds) {
  const Eigen::Isometry3d T = ahead(0.8);
  const View view(conditions(Scenario::occluders));
  std::vector<int> red;
  const double dt = 0.1;
  for (double t = 0.0; t < 20.0; t += dt) red.push_back(coloured_pixels(view.at(T, t), 2));
  const int full = *std::max_element(red.begin(), red.end());
  const int least = *std::min_element(red.begin(), red.end());
  ASSERT_GT(full, 200);
  EXPECT_LT(least, full / 4) << "at some moment the bar hides most of the red sphere";
  const double hidden_s =
      dt * static_cast<double>(
               std::count_if(red.begin(), red.end(), [full](int n) { return n < 0.8 * full; }));
  EXPECT_GT(hidden_s, 1.0);
  EXPECT_LT(hidden_s, 8.0) << "a passing bar, not a permanent one";
  // The clear scene has nothing in the way.
  EXPECT_EQ(coloured_pixels(render(conditions(Scenario::clear), T, 0.0), 2), full);
}

TEST(RenderScenario, TheBarSweepsToAndFro) {
  const PassingBar p;
  const double span_s = (p.sweep_max_m - p.sweep_min_m) / p.speed_mps;
  EXPECT_NEAR(bar_x_m(p, 0.0), p.sweep_min_m, 1e-12);
  EXPECT_NEAR(bar_x_m(p, 0.5 * span_s), 0.5 * (p.sweep_min_m + p.sweep_max_m), 1e-9);
  EXPECT_NEAR(bar_x_m(p, span_s), p.sweep_max_m, 1e-9);
  EXPECT_NEAR(bar_x_m(p, 1.5 * span_s), 0.5 * (p.sweep_min_m + p.sweep_max_m), 1e-9);
}

// Mean absolute difference between horizontally adjacent pixels (green), across the 8-pixel
// block seams and inside the blocks.
void seam_and_inner_steps(const cv::Mat& img, double& seam, double& inner) {
  double s = 0.0, i = 0.0;
  int ns = 0, ni = 0;
  for (int v = 0; v < img.rows; ++v) {
    for (int u = 0; u + 1 < img.cols; ++u) {
      const double d = std::abs(img.at<cv::Vec3b>(v, u + 1)[1] - img.at<cv::Vec3b>(v, u)[1]);
      if (u % 8 == 7) {
        s += d;
        ++ns;
      } else {
        i += d;
        ++ni;
      }
    }
  }
  seam = s / ns;
  inner = i / ni;
}

TEST(RenderScenario, NoisyHasStrongerNoiseAndBlockSeams) {
  const Eigen::Isometry3d T = ahead(0.8);
  RenderOptions o;
  o.noise_sigma = 3.0;
  const cv::Mat clean = render(conditions(Scenario::clear), T, 0.0);
  auto deviation = [&](const cv::Mat& img) {
    cv::Mat a, b, diff;
    img.convertTo(a, CV_32F);
    clean.convertTo(b, CV_32F);
    cv::subtract(a, b, diff);
    cv::Scalar mean, sd;
    cv::meanStdDev(diff.reshape(1), mean, sd);
    return sd[0];
  };
  const cv::Mat clear = render(conditions(Scenario::clear), T, 0.0, o);
  // The sensor's noise, seen through a near-lossless encoder: noise_gain times the clear one.
  ScenarioParams lossless;
  lossless.noisy.jpeg_quality = 100;
  lossless.noisy.chroma_subsampling = false;
  const double gain = lossless.noisy.noise_gain;
  EXPECT_NEAR(deviation(render(conditions(Scenario::noisy, lossless), T, 0.0, o)),
              gain * deviation(clear), 0.15 * gain * deviation(clear));
  // At quality 50 the encoder smooths part of that noise away but leaves its own error: still
  // further from the clean image than the clear camera, and with 8x8 block seams.
  const cv::Mat noisy = render(conditions(Scenario::noisy), T, 0.0, o);
  EXPECT_GT(deviation(noisy), 1.2 * deviation(clear));
  double seam = 0.0, inner = 0.0;
  seam_and_inner_steps(noisy, seam, inner);
  EXPECT_GT(seam, 1.2 * inner) << "8x8 block seams";
  seam_and_inner_steps(clear, seam, inner);
  EXPECT_LT(seam, 1.05 * inner) << "no seams without compression";
}

TEST(RenderScenario, ExposureDriftsSlowlyBetweenUnderAndOver) {
  const ExposureDrift e;
  double lo = 1e9, hi = 0.0;
  for (double t = 0.0; t < e.period_s; t += 0.01) {
    lo = std::min(lo, exposure_gain(e, t));
    hi = std::max(hi, exposure_gain(e, t));
  }
  EXPECT_NEAR(lo, e.gain_min, 1e-3);
  EXPECT_NEAR(hi, e.gain_max, 1e-3);
  const Eigen::Isometry3d T = ahead(0.8);
  const double over_s = 0.25 * e.period_s, under_s = 0.75 * e.period_s;
  const View view(conditions(Scenario::exposure));
  const cv::Mat over = view.at(T, over_s);
  const cv::Mat under = view.at(T, under_s);
  const double m_over = cv::mean(over)[1], m_under = cv::mean(under)[1];
  EXPECT_GT(m_over, 2.0 * m_under);
  // Over-exposed, the red sphere clips.
  const Disc red = disc_of(T, MarkerModel::standard().spheres[0]);
  EXPECT_GT(disc_mean(over, red, 2, 0.6), 250.0);
  EXPECT_LT(disc_mean(under, red, 2, 0.6), 200.0);
  // From one frame to the next (33 ms) the level barely moves.
  double step = 0.0;
  for (double t = 0.0; t < e.period_s; t += 1.0) {
    step =
        std::max(step, std::abs(cv::mean(view.at(T, t + 0.033))[1] - cv::mean(view.at(T, t))[1]));
  }
  EXPECT_LT(step, 2.0);
}

struct WorldCameraFixture : ::testing::Test {
  StereoRig rig = make_parallel_rig(CameraModel{}, 0.178);
  MarkerModel marker = MarkerModel::standard();

  // Mean grey level of the left image at world times t1 and t2, with the vehicle at rest 1 m
  // short of docked (the world's default start) in still water.
  std::pair<double, double> means(const std::string& scenario, double t1_s, double t2_s) {
    SimParams params = test::still_water_params();
    params.scenario = scenario;
    params.camera.render.noise_sigma = 0.0;
    SimulatedWorld world(params, VehicleGeometry{}, DockingStation{});
    MockStereoCamera camera(world, rig, marker, params.camera, FaultInjection{}, 11);
    std::string error;
    EXPECT_TRUE(camera.open(error)) << error;
    StereoFrame frame;
    world.step_to(std::chrono::nanoseconds(std::llround(t1_s * 1e9)));
    EXPECT_EQ(camera.grab(frame), GrabStatus::ok);
    const double m1 = cv::mean(frame.left_bgr)[1];
    world.step_to(std::chrono::nanoseconds(std::llround(t2_s * 1e9)));
    EXPECT_EQ(camera.grab(frame), GrabStatus::ok);
    return {m1, cv::mean(frame.left_bgr)[1]};
  }
};

TEST_F(WorldCameraFixture, MockCameraRendersTheWorldsScenarioAtCaptureTime) {
  const ExposureDrift e;
  // Capture times 40 ms before: at the drift's top and bottom.
  const auto [over, under] = means("exposure", 0.25 * e.period_s + 0.04, 0.75 * e.period_s + 0.04);
  EXPECT_GT(over, 2.0 * under);
  const auto [first, second] = means("clear", 0.25 * e.period_s + 0.04, 0.75 * e.period_s + 0.04);
  EXPECT_NEAR(first, second, 2.0);
}

TEST_F(WorldCameraFixture, UnknownScenarioIsAConstructionError) {
  SimParams params = test::still_water_params();
  params.scenario = "murky";
  SimulatedWorld world(params, VehicleGeometry{}, DockingStation{});
  EXPECT_THROW(MockStereoCamera(world, rig, marker, params.camera, FaultInjection{}, 11),
               std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::hal::mock
