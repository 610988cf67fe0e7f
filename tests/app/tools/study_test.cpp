// The study's aggregation on synthetic runs: percentiles with failures, Table 1 rows, the best
// setting per population and overall, and the settings of the full and quick studies.
#include "app/tools/study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rovctl::app {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFrame = 0.033;

StudyRun run(const std::string& variant, GaCombination c, int seed, int frames_to_fitness,
             int frames_to_pose = -1) {
  StudyRun r;
  r.variant = variant;
  r.combination = c;
  r.seed = seed;
  r.generations_per_frame = 100 / c.population;
  r.frames_to_fitness = frames_to_fitness;
  r.frames_to_pose = frames_to_pose;
  r.wall_to_fitness_s = frames_to_fitness > 0 ? frames_to_fitness * 0.030 : 0.0;
  r.wall_to_pose_s = frames_to_pose > 0 ? frames_to_pose * 0.030 : 0.0;
  return r;
}

TEST(StudyTimeStats, CountsFramesAsTimeAndFailures) {
  const TimeStats t = time_stats({2, -1, 4, 6, -1}, {0.05, 0.0, 0.11, 0.2, 0.0}, kFrame);
  EXPECT_EQ(t.runs, 5);
  EXPECT_EQ(t.failures, 2);
  EXPECT_NEAR(t.median_s, 6 * kFrame, 1e-12);  // sorted: 2, 4, 6, inf, inf
  EXPECT_TRUE(std::isinf(t.p90_s));
  EXPECT_NEAR(t.wall_median_s, 0.11, 1e-12);  // over the successful runs only

  const TimeStats all = time_stats({1, 1, 1}, {0.03, 0.03, 0.03}, kFrame);
  EXPECT_EQ(all.failures, 0);
  EXPECT_NEAR(all.median_s, kFrame, 1e-12);
  EXPECT_NEAR(all.p90_s, kFrame, 1e-12);

  const TimeStats none = time_stats({-1, -1}, {0.0, 0.0}, kFrame);
  EXPECT_EQ(none.failures, 2);
  EXPECT_TRUE(std::isinf(none.median_s));
  EXPECT_TRUE(std::isinf(none.wall_median_s));
}

TEST(StudySummary, GroupsRunsByVariantAndCombinationInOrder) {
  const GaCombination a{10, 0.8, 0.15}, b{40, 0.6, 0.1};
  const std::vector<StudyRun> runs = {
      run("faithful", a, 0, 3),      run("faithful", b, 0, 2, 5), run("faithful", a, 1, 5),
      run("faithful", b, 1, -1, -1), run("improved", a, 0, 1, 1), run("faithful", a, 2, 4, 9),
  };
  const auto rows = summarise_combinations(runs, "faithful", {b, a}, kFrame);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].combination.population, 40);
  EXPECT_EQ(rows[0].fitness.runs, 2);
  EXPECT_EQ(rows[0].fitness.failures, 1);
  EXPECT_EQ(rows[0].pose.failures, 1);
  EXPECT_EQ(rows[0].generations_per_frame, 100 / 40);
  EXPECT_EQ(rows[1].combination.population, 10);
  EXPECT_EQ(rows[1].fitness.runs, 3);  // the improved run is not counted
  EXPECT_EQ(rows[1].fitness.failures, 0);
  EXPECT_NEAR(rows[1].fitness.median_s, 4 * kFrame, 1e-12);
  EXPECT_EQ(rows[1].pose.failures, 2);
  EXPECT_TRUE(std::isinf(rows[1].pose.median_s));
}

TEST(StudySummary, BestPerPopulationAndOverall) {
  std::vector<StudyRun> runs;
  auto add = [&runs](GaCombination c, std::vector<int> frames) {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      runs.push_back(run("faithful", c, static_cast<int>(i), frames[i]));
    }
  };
  const GaCombination p10a{10, 0.4, 0.1}, p10b{10, 0.8, 0.15}, p20a{20, 0.4, 0.1},
      p20b{20, 0.6, 0.1}, p20c{20, 0.8, 0.15};
  add(p10a, {5, 6, 7, 8});
  add(p10b, {4, 5, 6, -1});   // lower median, but a failure
  add(p20a, {3, 3, 4, 4});    // the fastest
  add(p20b, {3, 3, 4, 9});    // same median, worse p90
  add(p20c, {3, 3, -1, -1});  // infinite median: half failed
  const StudyVariant variant{"faithful", "", "faithful", false};
  const VariantSummary v = summarise_variant(variant, runs, {p10a, p10b, p20a, p20b, p20c}, kFrame);
  ASSERT_EQ(v.table1.size(), 5u);
  ASSERT_EQ(v.best_per_population.size(), 2u);
  EXPECT_EQ(v.best_per_population[0].combination.population, 10);
  // Median 5.5 frames vs 6.5: the lower median wins although it has a failure.
  EXPECT_DOUBLE_EQ(v.best_per_population[0].combination.selection_rate, 0.8);
  EXPECT_EQ(v.best_per_population[0].fitness.failures, 1);
  EXPECT_EQ(v.best_per_population[1].combination.population, 20);
  EXPECT_DOUBLE_EQ(v.best_per_population[1].combination.selection_rate, 0.4);
  EXPECT_EQ(v.best.combination.population, 20);
  EXPECT_DOUBLE_EQ(v.best.combination.selection_rate, 0.4);
  EXPECT_EQ(v.best_ties, 1);
}

TEST(StudySummary, FasterComparesMedianThenP90ThenFailures) {
  CombinationSummary a, b;
  a.fitness = {10, 0, 0.1, 0.2, 0.1};
  b.fitness = {10, 0, 0.1, 0.3, 0.1};
  EXPECT_TRUE(faster(a, b));
  EXPECT_FALSE(faster(b, a));
  b.fitness.p90_s = 0.2;
  b.fitness.failures = 0;
  EXPECT_FALSE(faster(a, b));
  EXPECT_FALSE(faster(b, a));  // a tie
  b.fitness.median_s = kInf;
  EXPECT_TRUE(faster(a, b));
}

TEST(StudySettings, FullStudyHasThePapersSixtyCombinations) {
  hal::StereoRig rig;
  rig.T_cr_cl.translation() = Eigen::Vector3d(-0.178, 0.0, 0.0);
  const StudySettings full = StudySettings::full(rig);
  EXPECT_EQ(full.combinations.size(), 60u);
  EXPECT_FALSE(full.quick);
  EXPECT_EQ(full.time_limit_frames(), 30);
  EXPECT_NEAR(full.T_cl_marker.translation().z(), 0.415, 1e-12);
  EXPECT_NEAR(full.T_cl_marker.translation().x(), 0.089, 1e-9);  // midway between the cameras
  const StudySettings quick = StudySettings::quick_subset(rig);
  EXPECT_TRUE(quick.quick);
  EXPECT_EQ(quick.combinations.size(), 15u);
  EXPECT_LT(quick.seeds, full.seeds);
  // The quick subset holds the paper's A-E.
  for (const PaperTable1Row& paper : paper_table1()) {
    bool found = false;
    for (const GaCombination& c : quick.combinations) {
      found |= c.population == paper.population && c.selection_rate == paper.selection_rate &&
               c.mutation_rate == paper.mutation_rate;
    }
    EXPECT_TRUE(found) << paper.label;
  }
}

TEST(StudyPaper, Fig8ModelFitsThePapersStatedValues) {
  for (const auto& [population, generations] : paper_fig8_points()) {
    EXPECT_EQ(paper_generations_per_frame(population), generations) << population;
  }
  EXPECT_EQ(paper_generations_per_frame(20), 18);
  EXPECT_EQ(paper_generations_per_frame(1000), 1);
}

TEST(StudyFig8Curve, InterpolatesBetweenMeasuredPopulations) {
  Fig8Curve curve;
  curve.points = {{10, 0.5, 2.0, 1000}, {30, 0.5, 6.0, 300}};
  EXPECT_EQ(curve.generations_at(10), 1000);
  EXPECT_EQ(curve.generations_at(20), 650);
  EXPECT_EQ(curve.generations_at(5), 1000);
  EXPECT_EQ(curve.generations_at(40), 300);
}

TEST(StudyReadingFit, ScoresThePapersClaimsOnOneVariantsRuns) {
  std::vector<StudyRun> runs;
  std::vector<GaCombination> combos;
  // Two populations; at 40 mutation 0.05 never converges, 0.1 is fastest; at 10 0.15 is fastest.
  auto add = [&](GaCombination c, int frames) {
    combos.push_back(c);
    for (int seed = 0; seed < 4; ++seed) {
      StudyRun r = run("reading", c, seed, frames);
      r.evaluations_per_frame = 360 + seed;
      runs.push_back(r);
    }
  };
  add({40, 0.6, 0.05}, -1);
  add({40, 0.6, 0.1}, 4);
  add({40, 0.6, 0.15}, 6);
  add({10, 0.8, 0.05}, 9);
  add({10, 0.8, 0.1}, 8);
  add({10, 0.8, 0.15}, 5);
  const StudyVariant variant{"reading", "", "faithful", true};
  const VariantSummary v = summarise_variant(variant, runs, combos, kFrame);
  const ReadingFit fit = reading_fit(v, runs, 0.99);
  EXPECT_EQ(fit.populations, 2);
  EXPECT_EQ(fit.populations_converging, 2);
  EXPECT_NEAR(fit.table2.fitness.median_s, 4 * kFrame, 1e-12);
  EXPECT_EQ(fit.mutation_populations, 2);
  EXPECT_EQ(fit.mutation_05_slower, 2);
  EXPECT_EQ(fit.mutation_10_faster_than_15, 1);
  EXPECT_DOUBLE_EQ(fit.evaluations_per_frame_min, 360.0);
  EXPECT_DOUBLE_EQ(fit.evaluations_per_frame_max, 363.0);
  // Populations converge, C in time, 0.05 slower in both; 0.1 beats 0.15 in 1 of 2 only (not
  // most); one Fig. 8 curve.
  EXPECT_EQ(fit.claims_held, 4);
  // A and C at 5 x 33 ms and 4 x 33 ms against 0.187 s and 0.125 s.
  const double a = std::log2(5 * kFrame / 0.187), c = std::log2(4 * kFrame / 0.125);
  EXPECT_NEAR(fit.table1_log2_rms, std::sqrt((a * a + c * c) / 2), 1e-9);
}

TEST(StudySettings, TheAblationHoldsEveryReadingAndTheNonPaperVariantIsMarked) {
  hal::StereoRig rig;
  const StudySettings full = StudySettings::full(rig);
  int ablation = 0, non_paper = 0;
  bool per_child = false, per_bit = false, per_field = false, non_elite = false, binary = false;
  bool paper_box = false, rovctl_box = false;
  for (const StudyVariant& v : full.variants) {
    if (v.ablation) {
      ++ablation;
      EXPECT_TRUE(v.paper_budget) << v.name;
      ASSERT_TRUE(v.reading.has_value()) << v.name;
      per_child |= v.reading->mutation == "per_child";
      per_field |= v.reading->mutation == "per_field";
      per_bit |= v.reading->mutation == "per_bit";
      non_elite |= v.reading->mutants == "non_elite";
      binary |= v.reading->coding == "binary";
      (v.search ? paper_box : rovctl_box) = true;
    }
    if (!v.paper) {
      ++non_paper;
      EXPECT_TRUE(v.far_field) << v.name;
    }
  }
  EXPECT_GE(ablation, 5);
  EXPECT_EQ(non_paper, 1);
  EXPECT_TRUE(per_child && per_field && per_bit && non_elite && binary);
  EXPECT_TRUE(paper_box && rovctl_box);
  EXPECT_NEAR(paper_search_box().z_max_m, 0.815, 1e-12);
}

TEST(StudySettings, VariantsAtThisMachinesBudgetRunFewerSeedsUnlessFull) {
  hal::StereoRig rig;
  StudySettings s = StudySettings::full(rig);
  const StudyVariant paper_pc{"p", "", "faithful", true};
  const StudyVariant machine{"m", "", "faithful", false};
  s.seeds = 8;
  s.machine_budget_seeds = 3;
  EXPECT_EQ(s.seeds_for(paper_pc), 8);
  EXPECT_EQ(s.seeds_for(machine), 3);
  s.seeds = 2;  // never more than asked for
  EXPECT_EQ(s.seeds_for(machine), 2);
  s.seeds = 8;
  s.full_seeds = true;
  EXPECT_EQ(s.seeds_for(machine), 8);
}

}  // namespace
}  // namespace rovctl::app
