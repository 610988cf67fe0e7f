// `rovctl bench`: the estimator's throughput (fitness evaluations/s, generations per 33 ms frame
// per population size: the paper's Fig. 8) and convergence (cold-start frames, errors) on seeded
// rendered pairs, for the configured (improved) mode and the paper's faithful mode in one run;
// with --set, the score on a validation set; with --sequence, frame by frame on rendered sequences.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/json_writer.hpp"
#include "app/tools/sequence_score.hpp"
#include "app/tools/validation_set.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/model/pose.hpp"
#include "hal/primitives/percentile.hpp"

namespace rovctl::app {
namespace {

using Clock = std::chrono::steady_clock;

// CPU time of this thread: the figures are per core, and the machine may be shared.
double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Pair {
  Eigen::Isometry3d truth;
  cv::Mat left, right;
};

struct ModeFigures {
  double evals_per_s = 0.0;
  std::vector<std::pair<int, int>> generations_per_frame;
  double cold_p50 = 0.0, cold_p95 = 0.0, converged_fraction = 0.0;
  // Cold start to the paper's recognition (fitness >= the threshold), beside the one to 5 mm / 2
  // deg.
  double fitness_p50 = 0.0, fitness_p95 = 0.0, fitness_fraction = 0.0;
  double fitness_t_err_mm_median = 0.0, fitness_r_err_deg_median = 0.0;
  double ms_per_frame = 0.0, ms_per_frame_p95 = 0.0;
  double t_err_mm_median = 0.0, r_err_deg_median = 0.0;
};

// A marker pose 0.3..0.7 m ahead, in view of both cameras, turned up to 25 degrees.
Eigen::Isometry3d random_pose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double z = 0.5 + 0.2 * u(rng);
  const Eigen::Vector3d t(0.05 + z * 0.12 * u(rng), z * 0.08 * u(rng), z);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  const double angle = 25.0 * M_PI / 180.0 * 0.5 * (u(rng) + 1.0);
  return hal::make_pose(t, Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)));
}

double evals_per_second(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                        const estimator::EstimatorParams& params, const Pair& pair) {
  estimator::PoseEstimator est(rig, marker, params, 1);
  est.update(pair.left, pair.right);  // segments the pair
  std::mt19937_64 rng(3);
  std::vector<Eigen::Isometry3d> poses;
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 4096; ++i) {  // half random genes, half near the truth (hits and misses)
    estimator::Gene g;
    for (auto& f : g.field) f = static_cast<std::uint16_t>(rng() & estimator::kFieldMax);
    Eigen::Isometry3d T = est.codec().decode(g);
    if (i % 2 == 0) {
      T = pair.truth;
      T.translation() += 0.01 * Eigen::Vector3d(n(rng), n(rng), n(rng));
    }
    poses.push_back(T);
  }
  double sink = 0.0;
  long count = 0;
  const double start = thread_cpu_s();
  double elapsed = 0.0;
  while (elapsed < 0.4) {
    for (const Eigen::Isometry3d& T : poses) sink += est.fitness().evaluate(T);
    count += static_cast<long>(poses.size());
    elapsed = thread_cpu_s() - start;
  }
  if (sink < 0.0) std::cerr << "";  // keeps the evaluations from being optimised away
  return count / elapsed;
}

ModeFigures bench_mode(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                       const estimator::EstimatorParams& params, const std::vector<Pair>& pairs,
                       int frame_cap) {
  ModeFigures out;
  out.evals_per_s = evals_per_second(rig, marker, params, pairs.front());
  for (const int population : {10, 20, 40, 60, 80, 100, 200, 360, 500}) {
    estimator::EstimatorParams p = params;
    p.ga.population = population;
    p.budget = "time";
    p.time_budget_ms = 33.0;
    estimator::PoseEstimator est(rig, marker, p, 1);
    std::vector<double> gens;
    for (int f = 0; f < 3; ++f)
      gens.push_back(est.update(pairs[f].left, pairs[f].right).generations);
    out.generations_per_frame.emplace_back(population,
                                           static_cast<int>(hal::percentile(gens, 0.5)));
  }
  std::vector<double> cold, ms, t_err, r_err, cold_fitness, fit_t_err, fit_r_err;
  int converged = 0, recognised = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    estimator::PoseEstimator est(rig, marker, params, 1000 + i);
    int first = frame_cap + 1, first_fitness = frame_cap + 1;
    estimator::PoseEstimate e;
    Eigen::Isometry3d T_at_pose = Eigen::Isometry3d::Identity();
    for (int f = 1; f <= frame_cap; ++f) {
      const double cpu0 = thread_cpu_s();
      e = est.update(pairs[i].left, pairs[i].right);
      ms.push_back(1e3 * (thread_cpu_s() - cpu0));
      const double et = (e.T_cl_marker.translation() - pairs[i].truth.translation()).norm();
      const double er = hal::rotation_angle_rad(e.T_cl_marker.linear(), pairs[i].truth.linear());
      if (first_fitness > frame_cap && e.fitness >= params.recognition_threshold) {
        first_fitness = f;
        fit_t_err.push_back(et * 1e3);
        fit_r_err.push_back(er * 180.0 / M_PI);
      }
      if (first > frame_cap && et <= 0.005 && er <= 2.0 * M_PI / 180.0) {
        first = f;
        T_at_pose = e.T_cl_marker;
      }
      if (first <= frame_cap && first_fitness <= frame_cap) break;
    }
    // Errors after the run: at convergence, or at the frame cap.
    if (first <= frame_cap) e.T_cl_marker = T_at_pose;
    t_err.push_back((e.T_cl_marker.translation() - pairs[i].truth.translation()).norm() * 1e3);
    r_err.push_back(hal::rotation_angle_rad(e.T_cl_marker.linear(), pairs[i].truth.linear()) *
                    180.0 / M_PI);
    if (first <= frame_cap) ++converged;
    if (first_fitness <= frame_cap) ++recognised;
    cold.push_back(first);
    cold_fitness.push_back(first_fitness);
  }
  out.fitness_p50 = hal::percentile(cold_fitness, 0.5);
  out.fitness_p95 = hal::percentile(cold_fitness, 0.95);
  out.fitness_fraction = static_cast<double>(recognised) / pairs.size();
  out.fitness_t_err_mm_median = fit_t_err.empty() ? std::nan("") : hal::percentile(fit_t_err, 0.5);
  out.fitness_r_err_deg_median = fit_r_err.empty() ? std::nan("") : hal::percentile(fit_r_err, 0.5);
  out.cold_p50 = hal::percentile(cold, 0.5);
  out.cold_p95 = hal::percentile(cold, 0.95);
  out.converged_fraction = static_cast<double>(converged) / pairs.size();
  double sum = 0.0;
  for (double m : ms) sum += m;
  out.ms_per_frame = sum / ms.size();
  out.ms_per_frame_p95 = hal::percentile(ms, 0.95);
  out.t_err_mm_median = hal::percentile(t_err, 0.5);
  out.r_err_deg_median = hal::percentile(r_err, 0.5);
  return out;
}

void write_figures(JsonWriter& json, const ModeFigures& m, const std::string& mode, int cap) {
  json.field("mode", mode)
      .field("fitness_evals_per_s", m.evals_per_s)
      .begin_object("generations_per_frame");
  for (const auto& [population, generations] : m.generations_per_frame) {
    json.field(std::to_string(population), generations);
  }
  json.end_object()
      .field("cold_start_frames_p50", m.cold_p50)
      .field("cold_start_frames_p95", m.cold_p95)
      .field("cold_start_converged_fraction", m.converged_fraction)
      .field("cold_start_frame_cap", cap)
      .field("cold_start_fitness_frames_p50", m.fitness_p50)
      .field("cold_start_fitness_frames_p95", m.fitness_p95)
      .field("cold_start_fitness_fraction", m.fitness_fraction)
      .field("at_first_fitness_translation_error_mm_median", m.fitness_t_err_mm_median)
      .field("at_first_fitness_rotation_error_deg_median", m.fitness_r_err_deg_median)
      .field("estimator_ms_per_frame", m.ms_per_frame)
      .field("estimator_ms_per_frame_p95", m.ms_per_frame_p95)
      .field("translation_error_mm_median", m.t_err_mm_median)
      .field("rotation_error_deg_median", m.r_err_deg_median);
}

void print_figures(const ModeFigures& m, const std::string& mode, int cap) {
  std::printf("%s mode\n", mode.c_str());
  std::printf("  fitness evaluations/s (1 thread)   %.0f\n", m.evals_per_s);
  std::printf("  generations per 33 ms frame        ");
  for (const auto& [population, generations] : m.generations_per_frame)
    std::printf("%d:%d ", population, generations);
  std::printf(
      "\n  cold start frames to 5 mm / 2 deg p50 / p95 %.0f / %.0f (%.0f%% within %d frames)\n",
      m.cold_p50, m.cold_p95, 100.0 * m.converged_fraction, cap);
  std::printf(
      "  cold start frames to fitness p50/p95 %.0f / %.0f (%.0f%% within %d frames); error then "
      "%.1f mm, %.1f deg\n",
      m.fitness_p50, m.fitness_p95, 100.0 * m.fitness_fraction, cap, m.fitness_t_err_mm_median,
      m.fitness_r_err_deg_median);
  std::printf("  estimator CPU ms/frame mean / p95 %.2f / %.2f\n", m.ms_per_frame,
              m.ms_per_frame_p95);
  std::printf("  median error                       %.2f mm, %.2f deg\n", m.t_err_mm_median,
              m.r_err_deg_median);
}

// `--range-bands-m 0.5,1.0,1.3`: the edges between range bands, m, ascending.
std::vector<double> range_edges(const CliArgs& args) {
  if (!args.has("--range-bands-m")) return {0.5, 1.0, 1.3};
  return args.get_ascending("--range-bands-m", 0.0, 100.0, "ascending ranges in (0, 100] m");
}

// `--by FIELD --by-edges 1,1.5`: a manifest number to split each condition's score by, and its
// edges, ascending. Empty field when not asked for.
struct FieldSplit {
  std::string field;
  std::vector<double> edges;
};

FieldSplit field_split(const CliArgs& args) {
  FieldSplit split;
  if (!args.has("--by") && !args.has("--by-edges")) return split;
  if (!args.has("--by") || !args.has("--by-edges")) {
    throw UsageError("rovctl bench: --by FIELD and --by-edges E1,E2,... go together");
  }
  split.field = args.get("--by");
  const double inf = std::numeric_limits<double>::infinity();
  split.edges = args.get_ascending("--by-edges", -inf, inf, "ascending numbers");
  return split;
}

// A condition's score as JSON fields, the one writer for every row: a whole condition's row
// (`conditions`) or a band of one (`by_range`, `by_field`: after its edges), which leaves out
// what only the whole condition has (ok, the false-ok rate, p95s, the median over every pair,
// the time). A rate over no pairs is null: no data, not a rate of 0.
enum class ScoreRow { condition, band };
JsonWriter& score_fields(JsonWriter& json, const ConditionScore& s, ScoreRow row) {
  const bool whole = row == ScoreRow::condition;
  const auto rate = [&s](int n) {
    return s.pairs > 0 ? static_cast<double>(n) / s.pairs
                       : std::numeric_limits<double>::quiet_NaN();
  };
  json.field("pairs", s.pairs);
  if (whole) json.field("ok", s.ok);
  json.field("success", s.success)
      .field("success_rate", rate(s.success))
      .field("false_ok", s.false_ok);
  if (whole) json.field("false_ok_rate", rate(s.false_ok));
  json.field("partial", s.partial)
      .field("partial_view", s.partial_view)
      .field("not_refined", s.not_refined)
      .field("bound_over_limit", s.bound_over_limit)
      .field("translation_mm_median", s.translation_mm_median);
  if (whole) json.field("translation_mm_p95", s.translation_mm_p95);
  json.field("rotation_deg_median", s.rotation_deg_median);
  if (whole) {
    json.field("rotation_deg_p95", s.rotation_deg_p95)
        .field("translation_mm_median_all", s.translation_mm_median_all)
        .field("ms_per_frame_p95", s.ms_per_frame_p95)
        .field("bounded", s.bounded)
        .field("bound_held", s.bound_held)
        .field("rotation_bound_ratio_p99", s.rotation_bound_ratio_p99)
        .field("rotation_bound_ratio_max", s.rotation_bound_ratio_max)
        .field("translation_bound_ratio_p99", s.translation_bound_ratio_p99)
        .field("translation_bound_ratio_max", s.translation_bound_ratio_max);
  }
  return json;
}

// `rovctl bench --set DIR`: the estimator scored on an independent validation set, per condition.
int bench_set(const AppConfig& config, const hal::StereoRig& rig, const std::string& dir,
              int frames, std::uint64_t seed, const std::vector<double>& range_edges_m,
              const FieldSplit& split, bool json_out, bool verbose) {
  std::vector<ValidationPair> pairs;
  try {
    pairs = load_validation_set(dir);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(e.what());
  }
  // Before the estimator's minutes: a field no pair has is a typing error.
  if (!split.field.empty() &&
      std::none_of(pairs.begin(), pairs.end(), [&split](const ValidationPair& p) {
        return p.numbers.count(split.field) > 0;
      })) {
    throw UsageError("rovctl bench --by " + split.field + ": no pair of " + dir +
                     "/manifest.json has a number '" + split.field + "'");
  }
  std::vector<PairResult> details;
  const std::vector<ConditionScore> scores =
      score_validation_set(rig, config.marker, config.estimator, pairs, frames, &details, seed);
  const std::vector<ConditionScore> by_range = score_by_range(details, range_edges_m);
  const std::vector<FieldBandScore> by_field =
      split.field.empty() ? std::vector<FieldBandScore>{}
                          : score_by_field(details, split.field, split.edges);
  if (verbose) {
    for (const PairResult& r : details) {
      std::fprintf(
          stderr,
          "%-44s %-16s %7.1f mm %6.1f deg  fitness %.3f  seen %d/%d  scores L %.2f %.2f "
          "%.2f R %.2f %.2f %.2f  ring L %.2f %.2f %.2f R %.2f %.2f %.2f  rim %s L %.2f %.2f %.2f "
          "R %.2f %.2f %.2f  bound %.1f mm %.1f deg%s\n",
          r.pair->left_png.c_str(),
          r.ok ? "ok" : (r.partial ? estimator::to_string(r.not_ok_reason) : "not_recognised"),
          r.translation_mm, r.rotation_deg, r.fitness, r.spheres_seen_left, r.spheres_seen_right,
          r.sphere_scores[0][0], r.sphere_scores[0][1], r.sphere_scores[0][2],
          r.sphere_scores[1][0], r.sphere_scores[1][1], r.sphere_scores[1][2],
          r.sphere_ring_hits[0][0], r.sphere_ring_hits[0][1], r.sphere_ring_hits[0][2],
          r.sphere_ring_hits[1][0], r.sphere_ring_hits[1][1], r.sphere_ring_hits[1][2],
          r.rim_refined ? "yes" : "no ", r.rim_support[0][0], r.rim_support[0][1],
          r.rim_support[0][2], r.rim_support[1][0], r.rim_support[1][1], r.rim_support[1][2],
          r.error_bound_mm, r.error_bound_deg, r.mirror_fits ? "  mirror fits" : "");
    }
  }
  if (json_out) {
    JsonWriter json;
    json.begin_object()
        .field("set", dir)
        .field("mode", config.estimator.mode)
        .field("frames", frames)
        .field("seed", static_cast<long>(seed))
        .field("right_translation_mm", kRightTranslationMm)
        .field("right_rotation_deg", kRightRotationDeg)
        .begin_array("conditions");
    for (const ConditionScore& s : scores) {
      json.begin_object().field("condition", s.condition);
      score_fields(json, s, ScoreRow::condition).end_object();
    }
    json.end_array().begin_array("by_range");
    for (const ConditionScore& s : by_range) {
      json.begin_object()
          .field("condition", s.condition)
          .field("range_from_m", s.range_from_m)
          .field("range_to_m", s.range_to_m);  // null: no upper edge
      score_fields(json, s, ScoreRow::band).end_object();
    }
    json.end_array();
    if (!split.field.empty()) {
      json.begin_array("by_field");
      for (const FieldBandScore& b : by_field) {
        const ConditionScore& s = b.score;
        json.begin_object()
            .field("condition", s.condition)
            .field("field", b.field)
            .field("from", b.from)  // null: no lower edge
            .field("to", b.to);     // null: no upper edge
        score_fields(json, s, ScoreRow::band).end_object();
      }
      json.end_array();
    }
    json.end_object();
    std::cout << json.str() << "\n";
  } else {
    std::printf(
        "rovctl bench --set %s: %zu pairs, %d frames each, GA seed %lu, %s mode; right = within "
        "%.0f mm and %.0f deg\n",
        dir.c_str(), pairs.size(), frames, static_cast<unsigned long>(seed),
        config.estimator.mode.c_str(), kRightTranslationMm, kRightRotationDeg);
    std::printf("%-14s %5s %8s %9s %8s %14s %10s %10s %9s\n", "condition", "pairs", "success",
                "false-ok", "not-ok", "view/ref/bound", "mm med/p95", "deg med/p95", "ms p95");
    for (const ConditionScore& s : scores) {
      char reasons[24];
      std::snprintf(reasons, sizeof reasons, "%d/%d/%d", s.partial_view, s.not_refined,
                    s.bound_over_limit);
      std::printf("%-14s %5d %7.0f%% %8.0f%% %8d %14s %5.1f/%-5.1f %5.2f/%-5.2f %8.2f\n",
                  s.condition.c_str(), s.pairs, 100.0 * s.success / std::max(1, s.pairs),
                  100.0 * s.false_ok / std::max(1, s.pairs), s.partial, reasons,
                  s.translation_mm_median, s.translation_mm_p95, s.rotation_deg_median,
                  s.rotation_deg_p95, s.ms_per_frame_p95);
    }
    std::printf(
        "\nerror / bound over the ok pairs with a bound (held: both errors within it):\n"
        "%-14s %7s %6s %17s %17s\n",
        "condition", "bounded", "held", "deg ratio p99/max", "mm ratio p99/max");
    for (const ConditionScore& s : scores) {
      std::printf("%-14s %7d %5.0f%% %8.2f/%-8.2f %8.2f/%-8.2f\n", s.condition.c_str(), s.bounded,
                  100.0 * s.bound_held / std::max(1, s.bounded), s.rotation_bound_ratio_p99,
                  s.rotation_bound_ratio_max, s.translation_bound_ratio_p99,
                  s.translation_bound_ratio_max);
    }
    std::printf("\nby the marker's true range from the left camera:\n%-14s %11s %5s %8s %9s\n",
                "condition", "range m", "pairs", "success", "false-ok");
    for (const ConditionScore& s : by_range) {
      char to[16] = "";
      if (std::isfinite(s.range_to_m)) std::snprintf(to, sizeof to, "%.2f", s.range_to_m);
      std::printf("%-14s %4.2f-%-5s %6d %7.0f%% %8.0f%%\n", s.condition.c_str(), s.range_from_m, to,
                  s.pairs, 100.0 * s.success / s.pairs, 100.0 * s.false_ok / s.pairs);
    }
    if (!split.field.empty()) {
      std::printf("\nby %s:\n%-14s %17s %5s %8s %9s\n", split.field.c_str(), "condition", "band",
                  "pairs", "success", "false-ok");
      for (const FieldBandScore& b : by_field) {
        char band[48];
        if (std::isfinite(b.from) && std::isfinite(b.to)) {
          std::snprintf(band, sizeof band, "%g to %g", b.from, b.to);
        } else if (std::isfinite(b.to)) {
          std::snprintf(band, sizeof band, "under %g", b.to);
        } else if (std::isfinite(b.from)) {
          std::snprintf(band, sizeof band, "%g and over", b.from);
        } else {
          std::snprintf(band, sizeof band, "all");
        }
        const ConditionScore& s = b.score;
        std::printf("%-14s %17s %5d %7.0f%% %8.0f%%\n", s.condition.c_str(), band, s.pairs,
                    100.0 * s.success / s.pairs, 100.0 * s.false_ok / s.pairs);
      }
    }
  }
  return kExitOk;
}

void arm_fields(JsonWriter& json, const char* key, const ArmCount& a) {
  json.begin_object(key)
      .field("frames", a.frames)
      .field("right", a.right)
      .field("ok_but_wrong", a.wrong)
      .field("not_ok", a.not_ok)
      .end_object();
}

// The tracker's own claim: on its ok frames the error is within the bound it gave. Returns the
// tracked ok frames and those of them off by more than their bound.
std::pair<int, int> beyond_bound(const SequenceScores& scores) {
  int tracked_ok = 0, beyond = 0;
  for (const FrameScore& s : scores.frames) {
    if (!s.tracked_ok) continue;
    ++tracked_ok;
    if (s.tracked_mm > s.bound_mm || s.tracked_deg > s.bound_deg) ++beyond;
  }
  return {tracked_ok, beyond};
}

void print_rows(const char* title, const std::vector<SequenceScoreRow>& rows) {
  std::printf("\n%-22s %6s | %8s %8s %6s | %8s %8s %6s\n", title, "frames", "right", "ok-wrong",
              "not-ok", "right", "ok-wrong", "not-ok");
  for (const SequenceScoreRow& r : rows) {
    std::printf("%-22s %6d | %7.1f%% %8d %6d | %7.1f%% %8d %6d\n", r.label.c_str(), r.still.frames,
                100.0 * r.still.right / std::max(1, r.still.frames), r.still.wrong, r.still.not_ok,
                100.0 * r.tracked.right / std::max(1, r.tracked.frames), r.tracked.wrong,
                r.tracked.not_ok);
  }
}

// `rovctl bench --sequence DIR`: each rendered sequence frame by frame, the still estimator (with
// the loop's confirmation) beside the same followed by the pose tracker.
int bench_sequence(const AppConfig& config, const hal::StereoRig& rig, const std::string& dir,
                   int updates, std::uint64_t seed, bool json_out, bool verbose) {
  std::vector<RenderedSequence> sequences;
  try {
    sequences = load_sequences(dir);
    if (verbose) std::fprintf(stderr, "%zu sequences from %s\n", sequences.size(), dir.c_str());
  } catch (const std::invalid_argument& e) {
    throw ConfigError(e.what());
  }
  SequenceScores scores;
  try {
    scores = score_sequences(rig, config.marker, config.estimator, config.control.tracker,
                             sequences, updates, seed);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(e.what());
  }
  if (verbose) {
    for (const FrameScore& s : scores.frames) {
      std::fprintf(stderr,
                   "%-12s %3lu  still %-5s %6.1f mm %5.1f deg  (bound %5.1f mm %5.1f deg)  "
                   "tracked %-5s %-8s %6.1f mm %5.1f deg  bound %5.1f mm %5.1f deg%s%s\n",
                   s.sequence->name.c_str(), static_cast<unsigned long>(s.frame->frame),
                   s.still_ok ? "ok" : "-", s.still_mm, s.still_deg, s.still_bound_mm,
                   s.still_bound_deg, s.tracked_ok ? "ok" : "-", control::to_string(s.source),
                   s.tracked_mm, s.tracked_deg, s.bound_mm, s.bound_deg,
                   s.frame->hidden_sphere ? "  hidden" : "",
                   s.frame->bubbles_on_sight_lines > 0 ? "  bubbles" : "");
    }
  }
  if (json_out) {
    JsonWriter json;
    json.begin_object()
        .field("sequences", dir)
        .field("mode", config.estimator.mode)
        .field("updates_per_frame", updates)
        .field("seed", static_cast<long>(seed))
        .field("right_translation_mm", kRightTranslationMm)
        .field("right_rotation_deg", kRightRotationDeg);
    for (const auto& [key, rows] :
         {std::pair{"by_sequence", &scores.by_sequence}, std::pair{"by_kind", &scores.by_kind},
          std::pair{"by_event", &scores.by_event}}) {
      json.begin_array(key);
      for (const SequenceScoreRow& r : *rows) {
        json.begin_object().field("label", r.label);
        arm_fields(json, "still", r.still);
        arm_fields(json, "tracked", r.tracked);
        json.end_object();
      }
      json.end_array();
    }
    const auto [tracked_ok, beyond] = beyond_bound(scores);
    json.field("tracked_ok_frames", tracked_ok)
        .field("tracked_ok_beyond_bound", beyond)
        .end_object();
    std::cout << json.str() << "\n";
    return kExitOk;
  }
  std::printf(
      "rovctl bench --sequence %s: %zu sequences, %zu frames, %d estimator update(s) per frame, "
      "GA seed %lu, %s mode; right = within %.0f mm and %.0f deg\n"
      "left: still (estimator + confirmation); right: tracked (+ pose tracker)\n",
      dir.c_str(), sequences.size(), scores.frames.size(), updates,
      static_cast<unsigned long>(seed), config.estimator.mode.c_str(), kRightTranslationMm,
      kRightRotationDeg);
  print_rows("sequence", scores.by_sequence);
  print_rows("kind", scores.by_kind);
  print_rows("frames", scores.by_event);
  const auto [tracked_ok, beyond] = beyond_bound(scores);
  std::printf("\ntracked ok frames with an error beyond the tracker's bound: %d of %d\n", beyond,
              tracked_ok);
  return kExitOk;
}

}  // namespace

int command_bench(const Words& words) {
  const CliArgs args =
      CliArgs::parse("bench", words,
                     {"--config", "--pairs", "--frame-cap", "--set", "--frames", "--seed",
                      "--range-bands-m", "--by", "--by-edges", "--sequence"},
                     {"--json", "--verbose"});
  const std::string config_file =
      args.has("--config") ? args.get("--config") : default_config_path();
  const AppConfig config = load_app_config(config_file);
  const hal::StereoRig rig = load_rig(config);
  if (args.has("--set") && args.has("--sequence")) {
    throw UsageError("rovctl bench: --set and --sequence are two benches; give one");
  }
  if (args.has("--sequence")) {
    return bench_sequence(config, rig, args.get("--sequence"),
                          static_cast<int>(args.get_int("--frames", 1, 1, 10000)),
                          static_cast<std::uint64_t>(args.get_int("--seed", 0, 0, 1000000)),
                          args.has("--json"), args.has("--verbose"));
  }
  if (args.has("--set")) {
    return bench_set(
        config, rig, args.get("--set"), static_cast<int>(args.get_int("--frames", 10, 1, 10000)),
        static_cast<std::uint64_t>(args.get_int("--seed", 0, 0, 1000000)), range_edges(args),
        field_split(args), args.has("--json"), args.has("--verbose"));
  }
  if (args.has("--by") || args.has("--by-edges")) {
    throw UsageError("rovctl bench: --by splits a validation set's scores; it needs --set DIR");
  }
  const int n_pairs = static_cast<int>(args.get_int("--pairs", 100, 3, 100000));
  const int cap = static_cast<int>(args.get_int("--frame-cap", 100, 1, 100000));

  const hal::mock::RenderOptions render_options;
  const hal::mock::SceneRenderer left(rig.left, config.marker, render_options);
  const hal::mock::SceneRenderer right(rig.right, config.marker, render_options);
  std::vector<Pair> pairs(static_cast<std::size_t>(n_pairs));
  std::mt19937_64 rng(2018);
  for (int i = 0; i < n_pairs; ++i) {
    pairs[i].truth = random_pose(rng);
    hal::mock::render_stereo(left, right, rig, pairs[i].truth, static_cast<std::uint64_t>(i),
                             pairs[i].left, pairs[i].right);
  }
  estimator::EstimatorParams improved = config.estimator;
  improved.mode = "improved";
  estimator::EstimatorParams faithful = config.estimator;
  faithful.mode = "faithful";
  const ModeFigures a = bench_mode(rig, config.marker, improved, pairs, cap);
  const ModeFigures b = bench_mode(rig, config.marker, faithful, pairs, cap);

  if (args.has("--json")) {
    JsonWriter json;
    json.begin_object();
    write_figures(json, a, "improved", cap);
    json.field("pairs", n_pairs).begin_object("faithful");
    write_figures(json, b, "faithful", cap);
    json.end_object().end_object();
    std::cout << json.str() << "\n";
  } else {
    std::printf("rovctl bench: %d rendered pairs at 0.3-0.7 m, config %s\n", n_pairs,
                config_file.c_str());
    print_figures(a, "improved", cap);
    print_figures(b, "faithful", cap);
  }
  return kExitOk;
}

}  // namespace rovctl::app
