// `rovctl estimate`: runs the RM-GA over one stereo pair for N frames and prints the marker pose
// in the left camera frame. Bad input (images, calibration, config) is one line and exit code 2.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/json_writer.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/primitives/image_header.hpp"

namespace rovctl::app {
namespace {

cv::Mat read_image(const std::string& path, const hal::CameraModel& camera,
                   const std::string& calibration_file) {
  if (!std::filesystem::is_regular_file(path)) {
    throw ConfigError(path + ": cannot read image (no such file)");
  }
  // The size from the header, before decoding: a small file can declare a huge image.
  const std::string problem = hal::check_image_file(path, camera.width_px, camera.height_px,
                                                    "the calibration " + calibration_file);
  if (!problem.empty()) throw ConfigError(problem);
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_COLOR);
  } catch (const cv::Exception&) {
    image.release();
  }
  if (image.empty()) throw ConfigError(path + ": cannot read image (not a readable image file)");
  if (image.cols != camera.width_px || image.rows != camera.height_px) {
    throw ConfigError(path + ": image is " + std::to_string(image.cols) + "x" +
                      std::to_string(image.rows) + " but the calibration " + calibration_file +
                      " says " + std::to_string(camera.width_px) + "x" +
                      std::to_string(camera.height_px));
  }
  return image;
}

const char* not_ok_label(estimator::NotOkReason reason) {
  switch (reason) {
    case estimator::NotOkReason::partial_view:
      return "PARTIAL view";
    case estimator::NotOkReason::not_refined:
      return "NOT refined";
    case estimator::NotOkReason::bound_over_limit:
      return "BOUND over limit";
    case estimator::NotOkReason::unconfirmed:
      return "UNCONFIRMED";
    case estimator::NotOkReason::none:
      break;
  }
  return "not ok";
}

// The test the estimate failed, with the figures and the config keys it was judged by.
std::string not_ok_message(const estimator::PoseEstimate& e, const AppConfig& config) {
  const estimator::EstimatorParams& p = config.estimator;
  char text[320];
  switch (e.not_ok_reason) {
    case estimator::NotOkReason::partial_view:
      std::snprintf(text, sizeof text, "partial view (spheres seen: %d left, %d right, of %zu)",
                    e.spheres_seen[0], e.spheres_seen[1], config.marker.spheres.size());
      break;
    case estimator::NotOkReason::not_refined:
      std::snprintf(text, sizeof text,
                    "every sphere seen, but no refinement accepted (on the centroids or the rims), "
                    "so the pose has no error bound");
      break;
    case estimator::NotOkReason::bound_over_limit:
      std::snprintf(text, sizeof text,
                    "every sphere seen, but the error bound %.1f mm / %.1f deg is over "
                    "estimator.ok_bound_mm / ok_bound_deg (%g mm / %g deg)",
                    e.error_bound_m * 1000.0, e.error_bound_deg, p.ok_bound_mm, p.ok_bound_deg);
      break;
    case estimator::NotOkReason::unconfirmed:  // one pair has no frame before it; for completeness
      std::snprintf(text, sizeof text,
                    "not confirmed by the frame before (estimator.confirm.rate_dps, speed_mps)");
      break;
    case estimator::NotOkReason::none:
      std::snprintf(text, sizeof text, "fitness %.3f", e.fitness);
      break;
  }
  return text;
}

}  // namespace

int command_estimate(const Words& words) {
  const CliArgs args = CliArgs::parse(
      "estimate", words, {"--config", "--left", "--right", "--frames", "--seed"}, {"--json"});
  for (const char* required : {"--config", "--left", "--right"}) {
    if (!args.has(required)) {
      throw UsageError(std::string("rovctl estimate: ") + required +
                       " is required (usage: rovctl estimate --config FILE --left L.png --right "
                       "R.png [--frames N] [--seed S] [--json])");
    }
  }
  const AppConfig config = load_app_config(args.get("--config"));
  const hal::StereoRig rig = load_rig(config);
  const cv::Mat left = read_image(args.get("--left"), rig.left, config.calibration_file);
  const cv::Mat right = read_image(args.get("--right"), rig.right, config.calibration_file);
  // Enough frames to converge: the improved mode needs a few, the paper's GA alone many more.
  const long default_frames = config.estimator.improved() ? 10 : 300;
  const long frames = args.get_int("--frames", default_frames, 1, 100000);
  const long seed = args.get_int("--seed", 1, 0, 0x7FFFFFFFFFFFFFFFL);

  estimator::PoseEstimator estimator(rig, config.marker, config.estimator,
                                     static_cast<std::uint64_t>(seed));
  estimator::PoseEstimate estimate;
  long generations = 0;
  double time_ms = 0.0;
  for (long f = 0; f < frames; ++f) {
    estimate = estimator.update(left, right);
    generations += estimate.generations;
    time_ms += std::chrono::duration<double, std::milli>(estimate.compute_time).count();
  }
  const Eigen::Vector3d t = estimate.T_cl_marker.translation();
  Eigen::Quaterniond q(estimate.T_cl_marker.linear());
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  if (args.has("--json")) {
    JsonWriter json;
    json.begin_object()
        .field("ok", estimate.ok)
        .field("recognised", estimate.recognised)
        .field("not_ok_reason", std::string_view(estimator::to_string(estimate.not_ok_reason)))
        .begin_array("spheres_seen")
        .value(static_cast<double>(estimate.spheres_seen[0]))
        .value(static_cast<double>(estimate.spheres_seen[1]))
        .end_array()
        .begin_array("t_cl_marker_m")
        .value(t.x())
        .value(t.y())
        .value(t.z())
        .end_array()
        .begin_array("q_cl_marker_wxyz")
        .value(q.w())
        .value(q.x())
        .value(q.y())
        .value(q.z())
        .end_array()
        .field("fitness", estimate.fitness)
        .field("error_bound_mm", estimate.error_bound_m * 1000.0)
        .field("error_bound_deg", estimate.error_bound_deg)
        .field("refined_on",
               std::string_view(estimate.rim_refined ? "rims"
                                                     : (estimate.refined ? "centroids" : "none")))
        .field("refine_rms_px", estimate.rim_refined ? estimate.rim_rms_px : estimate.refine_rms_px)
        .field("water_corrected", estimate.water_corrected)
        .field("denoised", estimate.denoised)
        .field("ga_restarted", estimate.ga_restarted)
        .field("mirror_fits", estimate.mirror_fits)
        .begin_array("rim_support")
        .begin_array()
        .value(estimate.rim_support[0][0])
        .value(estimate.rim_support[0][1])
        .value(estimate.rim_support[0][2])
        .end_array()
        .begin_array()
        .value(estimate.rim_support[1][0])
        .value(estimate.rim_support[1][1])
        .value(estimate.rim_support[1][2])
        .end_array()
        .end_array()
        .field("generations", generations)
        .field("time_ms", time_ms)
        .end_object();
    std::cout << json.str() << "\n";
  } else {
    char line[256];
    std::snprintf(line, sizeof line, "t_cl_marker_m     [%.5f, %.5f, %.5f]\n", t.x(), t.y(), t.z());
    std::cout << line;
    std::snprintf(line, sizeof line, "q_cl_marker_wxyz  [%.6f, %.6f, %.6f, %.6f]\n", q.w(), q.x(),
                  q.y(), q.z());
    std::cout << line;
    std::snprintf(line, sizeof line,
                  "fitness %.3f (%s), spheres seen %d left %d right, %ld frames, %ld generations, "
                  "%.2f ms estimator time\n",
                  estimate.fitness,
                  estimate.ok            ? "ok"
                  : !estimate.recognised ? "NOT recognised"
                                         : not_ok_label(estimate.not_ok_reason),
                  estimate.spheres_seen[0], estimate.spheres_seen[1], frames, generations, time_ms);
    std::cout << line;
  }
  if (!estimate.recognised) {
    std::cerr << "rovctl estimate: marker not recognised (best fitness " << estimate.fitness
              << " < " << config.estimator.recognition_threshold << ")\n";
    return kExitRuntimeFailure;
  }
  if (!estimate.ok) {
    // Good enough to steer toward, not to trust as the pose: say which test it failed.
    std::cerr << "rovctl estimate: not ok: " << not_ok_message(estimate, config) << "\n";
    return kExitRuntimeFailure;
  }
  return kExitOk;
}

}  // namespace rovctl::app
