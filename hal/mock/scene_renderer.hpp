// Renders the three-sphere marker as one camera of the rig sees it: shaded spheres with specular
// highlights over a background gradient, optional water attenuation and sensor noise, and the
// named imaging scenarios (turbid water, side light, bubbles, occluders, noisy, exposure).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

#include "hal/mock/block_compression.hpp"
#include "hal/mock/bubble_field.hpp"
#include "hal/mock/camera_response.hpp"
#include "hal/mock/render_scenario.hpp"
#include "hal/mock/side_light.hpp"
#include "hal/mock/water_optics.hpp"
#include "hal/model/camera_model.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

struct RenderOptions {
  Eigen::Vector3d background_top_rgb{0.20, 0.32, 0.34};  // linear RGB 0..1, a vertical gradient
  Eigen::Vector3d background_bottom_rgb{0.06, 0.11, 0.12};
  double water_attenuation_per_m = 0.0;  // 0 = clear; >0 attenuates red most (blue-green cast)
  double noise_sigma = 2.0;              // sensor noise, std dev in 8-bit grey levels
  double ambient = 0.35;                 // ambient light fraction
  bool highlights = true;                // specular highlights on the spheres
};

void describe(ParamVisitor& v, RenderOptions& options);

// Working images of render_exposed(), kept by the caller so that a frame allocates nothing.
struct ExposureScratch {
  cv::Mat accumulator;  // CV_32FC3: the sum of the exposure's sub-frames
  cv::Mat view;         // CV_8UC3: one sub-frame
};

class SceneRenderer {
 public:
  // The clear scenario.
  SceneRenderer(const CameraModel& camera, const MarkerModel& marker, const RenderOptions& options);
  // Any scenario; `scene.seed` lays out its random parts (give both views of a rig the same).
  // Throws std::invalid_argument for inconsistent scenario parameters.
  SceneRenderer(const CameraModel& camera, const MarkerModel& marker, const RenderOptions& options,
                const SceneConditions& scene);

  // Renders one view into out_bgr (CV_8UC3, camera size) as the scene stands at `time_s`
  // (simulated time: what moves or drifts in a scenario moves with it; clear ignores it). No heap
  // allocation when out_bgr already has the right size and type. Deterministic for a given
  // noise_seed, time and scene seed.
  void render(const Eigen::Isometry3d& T_cam_marker, std::uint64_t noise_seed, double time_s,
              cv::Mat& out_bgr) const;
  // At time 0.
  void render(const Eigen::Isometry3d& T_cam_marker, std::uint64_t noise_seed,
              cv::Mat& out_bgr) const {
    render(T_cam_marker, noise_seed, 0.0, out_bgr);
  }

  // One exposure through which the marker moves: the sharp views at each of `count` poses
  // (spread evenly over the exposure), averaged as the sensor integrates them, then the sensor's
  // gain, noise and compression once. count 1 is render(). No heap allocation once out_bgr and
  // the scratch images have the camera size.
  void render_exposed(const Eigen::Isometry3d* T_cam_marker, int count, std::uint64_t noise_seed,
                      double time_s, cv::Mat& out_bgr, ExposureScratch& scratch) const;

  const CameraModel& camera() const { return camera_; }
  Scenario scenario() const { return scene_.scenario; }

 private:
  struct FrameLighting;

  // The light that reaches the sensor (scene, lighting, water), before the sensor's effects.
  void draw_scene(const Eigen::Isometry3d& T_cam_marker, double time_s, cv::Mat& out_bgr) const;
  // Gain, noise, compression: what the camera's electronics do to the exposed image.
  void sense(std::uint64_t noise_seed, double time_s, cv::Mat& out_bgr) const;

  void shade_sphere(const MarkerSphere& sphere, const Eigen::Vector3d& centre_cam_m,
                    const FrameLighting& lighting, int self, cv::Mat& out_bgr) const;
  void shade_rod(const Rod& rod, const Eigen::Vector3f& albedo, const FrameLighting& lighting,
                 cv::Mat& out_bgr) const;

  CameraModel camera_;
  MarkerModel marker_;
  RenderOptions options_;
  SceneConditions scene_;
  std::vector<Eigen::Vector3f> rays_;   // per pixel: the unit-z ray (x, y, 1) through its centre
  cv::Mat background_bgr_;              // CV_8UC3, the gradient
  cv::Mat noise_plus_, noise_minus_;    // CV_8UC3 noise texture split into its +/- parts
  std::vector<std::uint8_t> to_srgb8_;  // linear [0, 1] in 4096 steps -> 8-bit sRGB
  Eigen::Vector3d water_rgb_;           // veiling light colour (mean of the background)
  // What the selected scenario needs, built once.
  std::optional<WaterOptics> turbid_;
  std::vector<Eigen::Vector3f> background_row_rgb_;  // turbid: the gradient per row, linear
  std::optional<BubbleField> bubbles_;
  std::optional<ExposureResponse> exposure_;
  std::optional<BlockCompression> compression_;
};

// The right view's noise seed for a pair whose left view has `noise_seed`.
std::uint64_t right_noise_seed(std::uint64_t noise_seed);

// Both views of a rig: T_cr_marker = rig.T_cr_cl * T_cl_marker.
void render_stereo(const SceneRenderer& left, const SceneRenderer& right, const StereoRig& rig,
                   const Eigen::Isometry3d& T_cl_marker, std::uint64_t noise_seed, double time_s,
                   cv::Mat& left_bgr, cv::Mat& right_bgr);
// At time 0.
void render_stereo(const SceneRenderer& left, const SceneRenderer& right, const StereoRig& rig,
                   const Eigen::Isometry3d& T_cl_marker, std::uint64_t noise_seed,
                   cv::Mat& left_bgr, cv::Mat& right_bgr);

}  // namespace rovctl::hal::mock
