// `rovctl calibrate`: the stereo calibration from a recording of a chessboard, written as the
// `calibration` file every command reads. Bad input and a refused calibration: exit 2, nothing
// written.
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"
#include "app/tools/atomic_file.hpp"
#include "app/tools/board_spec.hpp"
#include "app/tools/json_writer.hpp"
#include "app/tools/stereo_board_calibration.hpp"
#include "drivers/replay/recording_format.hpp"
#include "estimator/stereo_calibration.hpp"

namespace rovctl::app {
namespace {

constexpr const char* kUsage =
    "usage: rovctl calibrate --pairs DIR --board chessboard:COLSxROWS:SQUARE_MM --out FILE "
    "[--json] [--force]";

cv::Mat read_pair_image(const std::string& folder, const std::string& file) {
  const std::string path = (std::filesystem::path(folder) / file).string();
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_COLOR);
  } catch (const cv::Exception&) {
    image.release();
  }
  if (image.empty()) throw ConfigError(path + ": cannot read image (missing or not an image)");
  return image;
}

// Every pair of the recording through the detector, one pair in memory at a time. All images
// must share one size: a calibration holds for one resolution only.
std::vector<BoardView> detect_views(const std::string& folder, const BoardSpec& board,
                                    const CalibrationLimits& limits, cv::Size& size) {
  if (!std::filesystem::is_directory(folder))
    throw ConfigError(folder + ": --pairs is not a folder");
  std::vector<drivers::RecordedFrame> frames;
  std::string error;
  if (!drivers::read_frames_csv(folder, frames, error)) {
    throw ConfigError(folder + ": not a recording as `rovctl record` writes it (" + error + ")");
  }
  std::vector<BoardView> views;
  std::string first_file;
  for (const drivers::RecordedFrame& f : frames) {
    const cv::Mat left = read_pair_image(folder, f.left_file);
    const cv::Mat right = read_pair_image(folder, f.right_file);
    if (first_file.empty()) {
      size = left.size();
      first_file = f.left_file;
    }
    for (const auto& [image, file] : {std::pair{&left, f.left_file}, {&right, f.right_file}}) {
      if (image->size() != size) {
        throw ConfigError(folder + "/" + file + ": image is " + std::to_string(image->cols) + "x" +
                          std::to_string(image->rows) + " but " + first_file + " is " +
                          std::to_string(size.width) + "x" + std::to_string(size.height) +
                          " (one calibration holds for one image size)");
      }
    }
    views.push_back(detect_board_view(f.left_file, left, right, board, limits));
  }
  return views;
}

std::string fixed(double v, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

void print_camera(const char* name, const hal::CameraModel& m) {
  std::cout << name << ": fx " << fixed(m.fx_px, 2) << "  fy " << fixed(m.fy_px, 2) << "  cx "
            << fixed(m.cx_px, 2) << "  cy " << fixed(m.cy_px, 2) << " px;  k1 " << fixed(m.k1, 4)
            << " k2 " << fixed(m.k2, 4) << " p1 " << fixed(m.p1, 5) << " p2 " << fixed(m.p2, 5)
            << " k3 " << fixed(m.k3, 4) << "\n";
}

double rotation_deg(const hal::StereoRig& rig) {
  return Eigen::AngleAxisd(rig.T_cr_cl.linear()).angle() * 180.0 / M_PI;
}

std::string tilt_band(std::size_t i) {
  const std::size_t n = std::size(kTiltBandsDeg);
  if (i == 0) return "<" + fixed(kTiltBandsDeg[0], 0);
  if (i == n) return ">" + fixed(kTiltBandsDeg[n - 1], 0);
  return fixed(kTiltBandsDeg[i - 1], 0) + "-" + fixed(kTiltBandsDeg[i], 0);
}

void print_report(const StereoBoardCalibration& c) {
  for (const ViewOutcome& v : c.views) {
    std::cout << (v.kept ? "  kept      " : "  left out  ") << v.name;
    if (v.kept)
      std::cout << "  " << fixed(v.error_px, 2) << " px, tilt " << fixed(v.tilt_deg, 0) << " deg";
    else
      std::cout << "  " << v.reason;
    std::cout << "\n";
  }
  std::cout << "views: " << c.views_used << " used of " << c.views.size() << "\n";
  if (c.views_used < 1 || c.coverage_left.views.empty()) return;
  std::cout << "RMS reprojection " << fixed(c.rms_px, 3) << " px (alone: left "
            << fixed(c.rms_left_px, 3) << ", right " << fixed(c.rms_right_px, 3)
            << "); rectified epipolar error " << fixed(c.epipolar_rms_px, 3) << " px RMS, "
            << fixed(c.epipolar_max_px, 3) << " px worst\n";
  print_camera("left ", c.rig.left);
  print_camera("right", c.rig.right);
  std::cout << "baseline " << fixed(c.rig.baseline_m() * 1000.0, 2) << " mm, rotation "
            << fixed(rotation_deg(c.rig), 3) << " deg; 1 sigma: fx " << fixed(c.sigma_fx_pct, 3)
            << " %, fy " << fixed(c.sigma_fy_pct, 3) << " %, centre " << fixed(c.sigma_c_px, 2)
            << " px\n";
  std::cout << "coverage, views per cell: left " << fixed(100.0 * c.coverage_left.fraction(), 0)
            << " % of cells\n"
            << coverage_table(c.coverage_left) << "right "
            << fixed(100.0 * c.coverage_right.fraction(), 0) << " % of cells\n"
            << coverage_table(c.coverage_right);
  std::cout << "board tilts (deg: views):";
  for (std::size_t i = 0; i < c.tilt_histogram.size(); ++i)
    std::cout << "  " << tilt_band(i) << ": " << c.tilt_histogram[i];
  std::cout << "\n";
  if (c.uncertain.empty()) std::cout << "certainty: no doubt flagged by the views\n";
  for (const std::string& u : c.uncertain) std::cout << "UNCERTAIN: " << u << "\n";
}

void camera_json(JsonWriter& json, const char* key, const hal::CameraModel& m) {
  json.begin_object(key)
      .field("fx_px", m.fx_px)
      .field("fy_px", m.fy_px)
      .field("cx_px", m.cx_px)
      .field("cy_px", m.cy_px)
      .field("k1", m.k1)
      .field("k2", m.k2)
      .field("p1", m.p1)
      .field("p2", m.p2)
      .field("k3", m.k3)
      .end_object();
}

std::string report_json(const StereoBoardCalibration& c, const std::string& out) {
  JsonWriter json;
  json.begin_object()
      .field("written", c.refusal.empty() ? out : std::string())
      .field("refusal", c.refusal)
      .field("views_total", static_cast<long>(c.views.size()))
      .field("views_used", c.views_used)
      .field("rms_reprojection_px", c.rms_px)
      .field("rms_left_px", c.rms_left_px)
      .field("rms_right_px", c.rms_right_px)
      .field("epipolar_rms_px", c.epipolar_rms_px)
      .field("epipolar_max_px", c.epipolar_max_px)
      .field("baseline_m", c.rig.baseline_m())
      .field("rotation_deg", rotation_deg(c.rig))
      .field("sigma_fx_pct", c.sigma_fx_pct)
      .field("sigma_fy_pct", c.sigma_fy_pct)
      .field("sigma_centre_px", c.sigma_c_px)
      .field("coverage_left", c.coverage_left.fraction())
      .field("coverage_right", c.coverage_right.fraction());
  camera_json(json, "left", c.rig.left);
  camera_json(json, "right", c.rig.right);
  json.begin_array("tilt_histogram");
  for (int n : c.tilt_histogram) json.value(n);
  json.end_array().begin_array("uncertain");
  for (const std::string& u : c.uncertain) json.begin_object().field("why", u).end_object();
  json.end_array().begin_array("views");
  for (const ViewOutcome& v : c.views) {
    json.begin_object()
        .field("name", v.name)
        .field("kept", v.kept)
        .field("reason", v.reason)
        .field("error_px", v.error_px)
        .field("tilt_deg", v.tilt_deg)
        .end_object();
  }
  json.end_array().end_object();
  return json.str();
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

// The coverage picture beside the calibration: calib.yaml -> calib.coverage.png.
std::string picture_path(const std::string& out) {
  std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + ".coverage.png")).string();
}

}  // namespace

int command_calibrate(const Words& words) {
  const CliArgs args =
      CliArgs::parse("calibrate", words, {"--pairs", "--board", "--out"}, {"--json", "--force"});
  for (const char* required : {"--pairs", "--board", "--out"}) {
    if (!args.has(required))
      throw UsageError(std::string("rovctl calibrate: ") + required + " is required (" + kUsage +
                       ")");
  }
  const std::string out = args.get("--out");
  const BoardSpec board = parse_board_spec(args.get("--board"));
  if (std::filesystem::exists(out) && !args.has("--force"))
    throw ConfigError(out + ": exists; give --force to overwrite it");
  const CalibrationLimits limits;
  cv::Size size;
  const std::vector<BoardView> views = detect_views(args.get("--pairs"), board, limits, size);
  const StereoBoardCalibration c = calibrate_stereo_board(views, size, board, limits);
  if (args.has("--json"))
    std::cout << report_json(c, out) << "\n";
  else
    print_report(c);
  if (!c.refusal.empty()) throw ConfigError("refused, nothing written: " + c.refusal);
  // The loader every command uses is the judge of what was written (a right camera on the left,
  // a forward baseline): what it refuses is not put in place.
  write_file_atomically(out, calibration_yaml(c, args.get("--board"), utc_now()),
                        [&](const std::string& written) {
                          try {
                            estimator::load_stereo_calibration(written);
                          } catch (const std::invalid_argument& e) {
                            throw ConfigError(std::string("refused, nothing written: ") + e.what());
                          }
                        });
  std::vector<unsigned char> png;
  cv::imencode(".png", coverage_picture(c), png);
  write_file_atomically(picture_path(out), std::string(png.begin(), png.end()));
  if (!args.has("--json")) std::cout << "wrote " << out << " and " << picture_path(out) << "\n";
  return kExitOk;
}

}  // namespace rovctl::app
