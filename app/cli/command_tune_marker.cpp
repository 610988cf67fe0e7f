// `rovctl tune-marker`: the marker's hue windows and floors learnt from a recording made in the
// water the vehicle will dock in, written as a `marker:` config fragment with a figure per view.
// Refuses (exit 2, nothing written) when a sphere cannot be told from the background.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/atomic_file.hpp"
#include "app/tools/json_writer.hpp"
#include "app/tools/marker_colour_tuning.hpp"
#include "app/tools/output_folder.hpp"
#include "drivers/replay/recording_format.hpp"
#include "estimator/hue_segmenter.hpp"
#include "hal/primitives/image_header.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

constexpr const char* kUsageLine =
    "usage: rovctl tune-marker --config FILE --pairs DIR --out FILE [--images DIR] [--frames N] "
    "[--seed S] [--max-background F] [--range-m NEAR,FAR] [--json] [--force]";

cv::Mat read_recorded_image(const fs::path& path, const hal::CameraModel& camera,
                            const std::string& calibration_file) {
  const std::string problem = hal::check_image_file(
      path.string(), camera.width_px, camera.height_px, "the calibration " + calibration_file);
  if (!problem.empty()) throw ConfigError(problem);
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty()) throw ConfigError(path.string() + ": cannot read image");
  return image;
}

std::vector<StereoImages> read_recording(const std::string& dir, const hal::StereoRig& rig,
                                         const std::string& calibration_file) {
  std::vector<drivers::RecordedFrame> frames;
  std::string error;
  if (!fs::is_directory(dir)) {
    throw ConfigError(dir +
                      ": not a folder (--pairs takes a recording as `rovctl record` writes it)");
  }
  if (!drivers::read_frames_csv(dir, frames, error)) throw ConfigError(error);
  if (frames.empty()) throw ConfigError(dir + "/" + drivers::kFramesCsv + ": no stereo pairs");
  std::vector<StereoImages> pairs;
  for (const drivers::RecordedFrame& f : frames) {
    StereoImages p;
    p.name = f.left_file;
    p.left = read_recorded_image(fs::path(dir) / f.left_file, rig.left, calibration_file);
    p.right = read_recorded_image(fs::path(dir) / f.right_file, rig.right, calibration_file);
    pairs.push_back(std::move(p));
  }
  return pairs;
}

std::string window_text(const hal::MarkerSphere& s) {
  char t[96];
  std::snprintf(t, sizeof t, "hue %5.1f-%5.1f deg, S >= %.2f, V >= %.2f", s.hue_min_deg,
                s.hue_max_deg, s.saturation_min, s.value_min);
  return t;
}

void print_report(const ColourTuningResult& r, const hal::MarkerModel& configured,
                  double water_correction, double range_near_m, double range_far_m) {
  std::printf(
      "rovctl tune-marker: marker located in %d of %zu pairs (estimator ok, "
      "water_correction %.2f)\n",
      r.located(), r.pairs.size(), water_correction);
  for (const PairLocation& p : r.pairs) {
    std::printf("  %-24s %s%s\n", p.name.c_str(), p.located ? "located with " : "not located",
                p.how.c_str());
  }
  if (r.located() == 0) return;
  std::printf(
      "sphere colours (inner 0.7 of each whole sphere, as the segmenter sees them; p3, p97 "
      "and p10: the extremes over the views):\n");
  for (const SphereSpread& s : r.spreads) {
    std::printf(
        "  %-6s %7ld px  hue p3/p50/p97 %5.1f/%5.1f/%5.1f deg  S p10/p50 %.2f/%.2f  "
        "V p10/p50 %.2f/%.2f\n",
        s.name.c_str(), s.pixels, s.hue_p3_deg, s.hue_p50_deg, s.hue_p97_deg, s.saturation_p10,
        s.saturation_p50, s.value_p10, s.value_p50);
  }
  std::printf(
      "hue drift with range (each view's p3 and p97 against the sphere's range; the windows "
      "follow it over the working range %.2f-%.2f m):\n",
      range_near_m, range_far_m);
  for (const SphereSpread& s : r.spreads) {
    std::printf(
        "  %-6s views at %.2f-%.2f m  p3 %+6.1f deg/m, p97 %+6.1f deg/m  ->  hue %5.1f-%5.1f "
        "deg\n",
        s.name.c_str(), s.range_min_m, s.range_max_m, s.hue_low_drift_deg_per_m,
        s.hue_high_drift_deg_per_m, s.hue_low_deg, s.hue_high_deg);
  }
  std::printf("located pairs: the marker %.2f-%.2f m out; near range %s, far range %s\n",
              r.located_range_min_m, r.located_range_max_m,
              r.covers_near ? "covered" : "NOT covered", r.covers_far ? "covered" : "NOT covered");
  std::printf("windows (configured -> proposed):\n");
  for (std::size_t i = 0; i < configured.spheres.size(); ++i) {
    std::printf("  %-6s %s  ->  %s\n", configured.spheres[i].name.c_str(),
                window_text(configured.spheres[i]).c_str(),
                window_text(r.tuned.spheres[i]).c_str());
  }
  for (const std::string& note : r.notes) std::printf("  note: %s\n", note.c_str());
  std::printf(
      "pixels of each colour, configured -> proposed: inside the sphere (share of its "
      "disc), outside every sphere (per view):\n");
  for (const ColourCounts& c : r.counts) {
    std::printf(
        "  %-6s inside %5.1f %% -> %5.1f %%   outside %7.1f -> %7.1f px   background "
        "%.1f %% of the sphere pixels\n",
        c.name.c_str(), 100.0 * c.inside_before, 100.0 * c.inside_after, c.outside_per_view_before,
        c.outside_per_view_after, 100.0 * c.background_fraction_after);
  }
}

void print_json(const ColourTuningResult& r) {
  JsonWriter j;
  j.begin_object()
      .field("refused", r.refused)
      .field("reason", std::string_view(r.reason))
      .field("pairs", static_cast<long>(r.pairs.size()))
      .field("located", static_cast<long>(r.located()))
      .field("located_range_min_m", r.located_range_min_m)
      .field("located_range_max_m", r.located_range_max_m)
      .field("covers_near", r.covers_near)
      .field("covers_far", r.covers_far)
      .begin_array("spheres");
  for (std::size_t i = 0; i < r.spreads.size(); ++i) {
    const SphereSpread& s = r.spreads[i];
    const ColourCounts& c = r.counts[i];
    const hal::MarkerSphere& t = r.tuned.spheres[i];
    j.begin_object()
        .field("name", std::string_view(s.name))
        .field("pixels", s.pixels)
        .field("hue_p3_deg", s.hue_p3_deg)
        .field("hue_p50_deg", s.hue_p50_deg)
        .field("hue_p97_deg", s.hue_p97_deg)
        .field("range_min_m", s.range_min_m)
        .field("range_max_m", s.range_max_m)
        .field("hue_low_drift_deg_per_m", s.hue_low_drift_deg_per_m)
        .field("hue_high_drift_deg_per_m", s.hue_high_drift_deg_per_m)
        .field("hue_low_deg", s.hue_low_deg)
        .field("hue_high_deg", s.hue_high_deg)
        .field("saturation_p10", s.saturation_p10)
        .field("value_p10", s.value_p10)
        .field("hue_min_deg", t.hue_min_deg)
        .field("hue_max_deg", t.hue_max_deg)
        .field("saturation_min", t.saturation_min)
        .field("value_min", t.value_min)
        .field("inside_before", c.inside_before)
        .field("inside_after", c.inside_after)
        .field("outside_per_view_before", c.outside_per_view_before)
        .field("outside_per_view_after", c.outside_per_view_after)
        .field("background_fraction_after", c.background_fraction_after)
        .end_object();
  }
  j.end_array().begin_array("notes");
  for (const std::string& note : r.notes) {
    j.begin_object().field("text", std::string_view(note)).end_object();
  }
  j.end_array().end_object();
  std::cout << j.str() << "\n";
}

// A figure per view: the image, the configured windows' labels, the proposed ones'.
void write_figures(const std::string& dir, const std::vector<StereoImages>& pairs,
                   const ColourTuningResult& r, const hal::StereoRig& rig,
                   const hal::MarkerModel& configured, double water_correction) {
  estimator::HueSegmenter before(configured, water_correction);
  estimator::HueSegmenter after(r.tuned, water_correction);
  const hal::MarkerModel none;  // no outlines where the marker was not located
  cv::Mat lb, la;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PairLocation& p = r.pairs[i];
    for (int side = 0; side < 2; ++side) {
      const cv::Mat& image = side == 0 ? pairs[i].left : pairs[i].right;
      before.segment(image, lb);
      after.segment(image, la);
      const Eigen::Isometry3d T = side == 0 ? p.T_cl_marker : rig.T_cr_cl * p.T_cl_marker;
      const cv::Mat figure = segmentation_figure(side == 0 ? rig.left : rig.right, T,
                                                 p.located ? configured : none, image, lb, la);
      char name[64];
      std::snprintf(name, sizeof name, "%03zu_%s.png", i, side == 0 ? "left" : "right");
      if (!cv::imwrite((fs::path(dir) / name).string(), figure)) {
        throw std::runtime_error(dir + "/" + name + ": cannot write");
      }
    }
  }
}

// --range-m NEAR,FAR: the marker's working range from the camera, metres, NEAR below FAR.
void parse_range(const CliArgs& args, ColourTuningOptions& options) {
  const std::vector<double> range =
      args.get_ascending("--range-m", 0.0, 20.0, "NEAR,FAR: ascending ranges in (0, 20] m");
  if (range.empty()) return;
  if (range.size() != 2) {
    throw UsageError("rovctl tune-marker: --range-m " + args.get("--range-m") +
                     ": must be NEAR,FAR, two ranges in metres (" + kUsageLine + ")");
  }
  options.range_near_m = range[0];
  options.range_far_m = range[1];
}

}  // namespace

int command_tune_marker(const Words& words) {
  const CliArgs args = CliArgs::parse("tune-marker", words,
                                      {"--config", "--pairs", "--out", "--images", "--frames",
                                       "--seed", "--max-background", "--range-m"},
                                      {"--json", "--force"});
  for (const char* required : {"--config", "--pairs", "--out"}) {
    if (!args.has(required)) {
      throw UsageError(std::string("rovctl tune-marker: ") + required + " is required (" +
                       kUsageLine + ")");
    }
  }
  const std::string out = args.get("--out");
  const fs::path out_path(out);
  const std::string images = args.get(
      "--images", (out_path.parent_path() / (out_path.stem().string() + "-segmentation")).string());
  const bool force = args.has("--force");
  std::error_code ec;
  if (!force && fs::exists(out, ec)) {
    throw UsageError("rovctl tune-marker: --out " + out + " exists (--force overwrites it)");
  }
  if (!force && fs::is_directory(images, ec) && !fs::is_empty(images, ec)) {
    throw UsageError("rovctl tune-marker: --images " + images +
                     " exists and is not empty (--force writes into it)");
  }
  ColourTuningOptions options;
  options.frames = static_cast<int>(args.get_int("--frames", options.frames, 1, 1000));
  options.seed = static_cast<std::uint64_t>(args.get_int("--seed", 1, 0, 0x7FFFFFFFL));
  options.max_background_fraction =
      args.get_double("--max-background", options.max_background_fraction, 0.0, 10.0);
  parse_range(args, options);

  const AppConfig config = load_app_config(args.get("--config"));
  const hal::StereoRig rig = load_rig(config);
  const std::vector<StereoImages> pairs =
      read_recording(args.get("--pairs"), rig, config.calibration_file);
  const double wc = config.estimator.water_correction;
  const ColourTuningResult r =
      tune_marker_colours(rig, config.marker, config.estimator, pairs, options);
  if (args.has("--json")) {
    print_json(r);
  } else {
    print_report(r, config.marker, wc, options.range_near_m, options.range_far_m);
  }
  if (r.refused) {
    std::cerr << "rovctl tune-marker: refused, nothing written: " << r.reason << "\n";
    return kExitUsage;
  }
  prepare_output_folder("tune-marker", images);
  write_figures(images, pairs, r, rig, config.marker, wc);
  char header[512];
  std::snprintf(header, sizeof header,
                "rovctl tune-marker: marker colours measured in %s (%d of %zu pairs located),\n"
                "estimator.water_correction %.2f, from the config %s.\n"
                "Merge: replace the config's `marker:` section with this one; the geometry is the\n"
                "config's, unchanged. Figures: %s",
                args.get("--pairs").c_str(), r.located(), r.pairs.size(), wc,
                args.get("--config").c_str(), images.c_str());
  write_file_atomically(out, marker_fragment_yaml(r.tuned, header));
  std::cerr << "rovctl tune-marker: wrote " << out << " and " << 2 * pairs.size()
            << " figures into " << images << "\n";
  return kExitOk;
}

}  // namespace rovctl::app
