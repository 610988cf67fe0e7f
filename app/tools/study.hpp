// The paper's GA-parameter study on this machine and the mock HAL: how many RM-GA generations fit
// in one 33 ms frame (Fig. 8) and how fast each GA setting converges on a fixed marker (Table 1,
// Fig. 9, Table 2), for the faithful estimator and the improved one.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <iosfwd>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "estimator/estimator_params.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

// One GA setting of the paper's 60: population x selection rate x mutation rate.
struct GaCombination {
  int population = 40;
  double selection_rate = 0.6;
  double mutation_rate = 0.1;
};

// An estimator set-up under study: its mode and where its generations per frame come from.
struct StudyVariant {
  StudyVariant() = default;
  StudyVariant(std::string name_, std::string description_, std::string mode_, bool paper_budget_)
      : name(std::move(name_)),
        description(std::move(description_)),
        mode(std::move(mode_)),
        paper_budget(paper_budget_) {}

  std::string name;  // "faithful", "faithful-paper-pc", "improved", "reading: ...", ...
  std::string description;
  std::string mode;           // the estimator mode ("faithful" or "improved")
  bool paper_budget = false;  // the paper PC's generations per frame instead of this machine's
  // Faithful mode: the reading of the paper's GA (unset: the configured one).
  std::optional<estimator::GaReading> reading;
  bool far_field = false;  // the non-paper graded far-field fitness
  // The GA's search box (unset: the study's).
  std::optional<estimator::SearchVolume> search;
  bool ablation = false;  // a row of the readings' ablation table
  bool paper = true;      // only what the paper describes (false: improvements of our own)
};

// The paper's Table 2 search area read literally: x +-400 mm, y +-200 mm, z 415 +-400 mm (the
// marker's distance +- 400), z clipped at 50 mm where the spheres fill the image.
estimator::SearchVolume paper_search_box();

struct StudySettings {
  bool quick = false;
  int seeds = 8;  // runs per combination and variant at the paper PC's budget
  // Runs per combination of the variants at this machine's budget (`faithful`, `improved`): each
  // of their frames costs a full 33 ms of CPU, where a paper-budget frame costs ~1-3 ms, so on 8
  // seeds they took 4/5 of the study's 1,000 s CPU. None of the paper's claims is scored on them;
  // fewer seeds keep the default study within 10 min on 2 cores. `full` runs them on `seeds`.
  int machine_budget_seeds = 3;
  bool full_seeds = false;  // every variant on `seeds` (rovctl study --full)
  // Runs of Table 2's setting (to_limit) per paper-budget variant: the ablation ranks the readings
  // there, and 8 seeds cannot (the faithful default's median over blocks of 8 seeds spans
  // 0.26-0.58 s). 32 cost ~1 min of CPU.
  int table2_seeds = 32;
  int seeds_for(const StudyVariant& v) const;
  int seeds_for(const StudyVariant& v, const GaCombination& c) const;
  double frame_period_s = 0.033;  // one frame: the paper's 33 ms control period
  double time_limit_s = 0.99;     // 30 frames; a run not converged by then is a failure
  int threads = 2;                // independent runs in parallel
  int frame_bank = 32;            // pre-rendered noisy stereo pairs, cycled through by every run
  double goal_fitness = 0.6;      // the paper's recognition threshold
  double goal_translation_mm = 5.0;
  double goal_rotation_deg = 2.0;
  // Runs of this setting (the paper's Table 2) go on to the time limit, for the error after 1 s.
  GaCombination to_limit{40, 0.6, 0.1};
  int landscape_samples = 20000;  // random poses in the search box for the fitness's blindness
  std::vector<int> fig8_populations;
  int fig8_repeats = 7;  // timings per point; the minimum is kept (load only ever adds time)
  std::vector<GaCombination> combinations;
  std::vector<StudyVariant> variants;
  // Names of the variants to run (empty: all). A variant keeps its seeds whatever else runs.
  std::vector<std::string> only;
  bool runs_variant(const std::string& name) const;
  // Settings to run (empty: all). A setting keeps its seeds whatever else runs.
  std::vector<GaCombination> only_settings;
  bool runs_setting(const GaCombination& c) const;
  std::vector<GaCombination> settings_run() const;  // the combinations that run, in order
  // The GA's search volume: the estimator's default, the paper's Table 2 area (x +-400 mm,
  // y +-200 mm), not a docking config's wider one, so runs start as randomly as the paper's.
  estimator::SearchVolume search;
  // The paper's set-up: marker fixed 415 mm ahead, midway between the cameras, 10 mm below them.
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();

  int time_limit_frames() const;
  // The full study: all 60 combinations. Quick: the three lines of the paper's Fig. 9
  // (selection/mutation 0.4/0.1, 0.6/0.1, 0.8/0.15) at the five populations, which hold A-E.
  static StudySettings full(const hal::StereoRig& rig);
  static StudySettings quick_subset(const hal::StereoRig& rig);
};

// The paper's numbers, drawn beside ours.
struct PaperTable1Row {
  const char* label;
  int population;
  double selection_rate;
  double mutation_rate;
  double time_s;
};
const std::vector<PaperTable1Row>& paper_table1();
// The values the paper states for Fig. 8: 37 at population 10, 9 at 40 (Table 2), 1 from 360 up.
const std::vector<std::pair<int, int>>& paper_fig8_points();
// All of them fit floor(370 / population): the paper PC's budget at any population.
int paper_generations_per_frame(int population);

// Fig. 8: one population's measured per-frame cost.
struct Fig8Point {
  int population = 0;
  double fixed_ms = 0.0;  // per-frame work besides generations: segmentation, re-evaluation
  double per_generation_us = 0.0;  // one GA generation
  int generations = 1;             // floor((frame - fixed) / per_generation), at least 1
};

// One mode's points at one selection rate (the per-generation cost scales with the children bred,
// (1 - selection_rate) * population; the mutation rate costs next to nothing).
struct Fig8Curve {
  std::string mode;
  double selection_rate = 0.6;
  std::vector<Fig8Point> points;
  // Generations per frame at `population` (measured, else interpolated between measured points).
  int generations_at(int population) const;
};

// One run: a fresh random population on the fixed marker, frame after frame, until both goals
// are met or the time limit passes.
struct StudyRun {
  std::string variant;
  GaCombination combination;
  int seed = 0;
  int generations_per_frame = 1;
  int frames_run = 0;
  int frames_to_fitness = -1;      // first frame (1-based) whose best fitness >= goal; -1: never
  int frames_to_pose = -1;         // first frame within goal_translation_mm and goal_rotation_deg
  double wall_to_fitness_s = 0.0;  // estimator compute time up to that frame (0 if never)
  double wall_to_pose_s = 0.0;
  double wall_s = 0.0;  // estimator compute time of the whole run
  // The same in CPU time of the run's thread (wall time includes other processes' share).
  double cpu_to_fitness_s = 0.0;
  double cpu_to_pose_s = 0.0;
  double cpu_s = 0.0;
  double final_fitness = 0.0;
  double final_translation_error_mm = 0.0;
  double final_rotation_error_deg = 0.0;
  // The estimate's error in the frame it first reached the goal fitness (NaN: never).
  double fitness_translation_error_mm = std::numeric_limits<double>::quiet_NaN();
  double fitness_rotation_error_deg = std::numeric_limits<double>::quiet_NaN();
  bool to_limit = false;             // ran to the time limit whatever it reached (final = at limit)
  double evaluations_per_frame = 0;  // fitness evaluations per frame, mean over the run
};

// Median and 90th percentile over all runs of a combination, a failure counting as infinitely
// slow (so a median is infinite when half the runs failed).
struct TimeStats {
  int runs = 0;
  int failures = 0;
  double median_s = 0.0;
  double p90_s = 0.0;
  double wall_median_s = 0.0;     // median compute time to the goal over the successful runs
  double cpu_median_s = 0.0;      // the same in thread CPU time
  double success_median_s = 0.0;  // median time over the successful runs only (inf: none)
};

struct CombinationSummary {
  std::string variant;
  GaCombination combination;
  int generations_per_frame = 1;
  TimeStats fitness;  // to the goal fitness (the paper's Table 1)
  TimeStats pose;     // to the goal accuracy
};

struct VariantSummary {
  StudyVariant variant;
  std::vector<CombinationSummary> table1;               // in the settings' combination order
  std::vector<CombinationSummary> best_per_population;  // Table 1: one per population
  CombinationSummary best;                              // Table 2
  int best_ties = 1;  // combinations indistinguishable from `best` (same median, p90, failures)
};

// What the fitness can tell: F along each axis through the truth, and how much of the search box
// it scores at all.
struct FitnessProfile {
  std::string fitness;  // "paper" or "far-field" (the search score the GA ranks by)
  double at_truth = 0.0;
  std::vector<double> offsets_mm;   // translation offsets, both signs
  std::vector<double> offsets_deg;  // rotation offsets, both signs
  // [axis][offset]: translation along the left camera's x, y, z; rotation about the marker's.
  std::array<std::vector<double>, 3> translation, rotation;
  int samples = 0;  // random poses in the study's search box
  double share_above_0 = 0.0, share_at_0_3 = 0.0, share_at_0_6 = 0.0;  // F > 0, >= 0.3, >= 0.6
  double share_graded = 0.0;      // poses the far field orders where F is 0 (far-field only)
  double far_field_weight = 0.0;  // the far field's weight and reach (far-field only)
  double far_field_reach_px = 0.0;
};

struct StudyResult {
  StudySettings settings;
  std::map<std::string, Fig8Curve> fig8;  // Fig. 8 by estimator mode, at the config's selection
  // The frame budgets of the runs: per mode and selection rate, at the study's populations.
  std::vector<Fig8Curve> budgets;
  std::vector<StudyRun> runs;
  std::vector<VariantSummary> variants;
  std::vector<FitnessProfile> profiles;     // paper's fitness, and the far field's search score
  estimator::GaReading configured_reading;  // the faithful reading of the config
  double fig8_wall_s = 0.0;
  double runs_wall_s = 0.0;
  double wall_s = 0.0;
  std::string machine;       // CPU model and core count
  double noise_sigma = 0.0;  // the rendered frames' sensor noise, grey levels

  // Generations per frame of this machine for a mode and setting (from `budgets`, else `fig8`).
  int generations_per_frame(const std::string& mode, const GaCombination& c) const;
};

TimeStats time_stats(const std::vector<int>& frames_to_goal, const std::vector<double>& wall_s,
                     double frame_period_s, const std::vector<double>& cpu_s = {});
// Groups runs by (variant, combination), in the order of `combinations`.
std::vector<CombinationSummary> summarise_combinations(
    const std::vector<StudyRun>& runs, const std::string& variant,
    const std::vector<GaCombination>& combinations, double frame_period_s);
// Faster to the goal fitness: lower median, then lower p90, then fewer failures, then lower
// median of the successful runs (which ranks settings where most runs fail).
bool faster(const CombinationSummary& a, const CombinationSummary& b);
std::vector<CombinationSummary> best_per_population(const std::vector<CombinationSummary>& rows);
VariantSummary summarise_variant(const StudyVariant& variant, const std::vector<StudyRun>& runs,
                                 const std::vector<GaCombination>& combinations,
                                 double frame_period_s);

// How a reading's runs fit the paper's claims (the ablation table's row).
struct ReadingFit {
  std::string variant;
  CombinationSummary table2;       // 40 / 0.6 / 0.1 (the paper's C, 0.125 s)
  int populations_converging = 0;  // populations whose best setting has a finite median
  int populations = 0;
  // Per population, the best over selection rates at each mutation rate: 0.05 slower than 0.1
  // (the paper: 0.05 "no enough fitness value"), 0.1 faster than 0.15 ("in most").
  int mutation_05_slower = 0;
  int mutation_10_faster_than_15 = 0;
  int mutation_populations = 0;
  // RMS of log2(our best time / the paper's) over A-E, "never" counted at the time limit.
  double table1_log2_rms = 0.0;
  // Fig. 8: evaluations per frame at the paper's budget, min and max over the settings (the
  // paper's one curve floor(370 / population) means ~370 whatever the selection rate).
  double evaluations_per_frame_min = 0.0, evaluations_per_frame_max = 0.0;
  int claims_held = 0;  // of kReadingClaims below
};
constexpr int kReadingClaims = 5;
ReadingFit reading_fit(const VariantSummary& v, const std::vector<StudyRun>& runs,
                       double time_limit_s);

// Median of `value` over the runs of one variant (and one setting, if given) where it is finite.
double run_median(const std::vector<StudyRun>& runs, const std::string& variant,
                  const GaCombination* setting, double StudyRun::*value);

// Progress of a long phase: (phase, done, total).
using StudyProgress = std::function<void(const std::string&, long, long)>;

// The estimator's per-frame fixed and per-generation cost at each population, single thread,
// on rendered frames of the study's scene, in thread CPU time (so that other processes on a
// shared machine do not count; the minimum of `repeats` timings).
Fig8Curve measure_fig8(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                       const estimator::EstimatorParams& base, const std::string& mode,
                       double selection_rate, const std::vector<int>& populations, int repeats,
                       double frame_period_s, const std::vector<cv::Mat>& left,
                       const std::vector<cv::Mat>& right, const StudyProgress& progress);

// Everything: frame bank, Fig. 8 per mode, the runs on `settings.threads` threads, summaries.
// The estimator runs with `base` but in `settings.search`.
StudyResult run_study(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                      const estimator::EstimatorParams& base,
                      const hal::mock::RenderOptions& render, const StudySettings& settings,
                      const StudyProgress& progress);

// F (and the far field's search score) around the truth on the first frame of `left`/`right`.
std::vector<FitnessProfile> measure_fitness_profiles(const hal::StereoRig& rig,
                                                     const hal::MarkerModel& marker,
                                                     const estimator::EstimatorParams& base,
                                                     const Eigen::Isometry3d& T_cl_marker,
                                                     const cv::Mat& left, const cv::Mat& right,
                                                     int samples);

// `rovctl study` with its streams passed in (the CLI passes std::cout / std::cerr).
int run_study_command(const std::vector<std::string>& words, std::ostream& out, std::ostream& err);

}  // namespace rovctl::app
