// Declarations (key, unit, range, meaning) of the estimator section.
#include "estimator/estimator_params.hpp"

#include <stdexcept>

namespace rovctl::estimator {

void EstimatorParams::validate() const {
  auto ordered = [](double lo, double hi, const char* key) {
    if (!(lo < hi)) {
      throw std::invalid_argument(std::string("estimator.search.") + key +
                                  ": min must be below max");
    }
  };
  ordered(search.x_min_m, search.x_max_m, "x");
  ordered(search.y_min_m, search.y_max_m, "y");
  ordered(search.z_min_m, search.z_max_m, "z");
  if (denoise_retry_px != 0 && denoise_retry_px != 3 && denoise_retry_px != 5) {
    throw std::invalid_argument("estimator.denoise_retry_px must be 0 (off), 3 or 5");
  }
  if (ga.elite_count >= ga.population) {
    throw std::invalid_argument("estimator.ga.elite_count must be below estimator.ga.population");
  }
  if (rim_loose_rms_px < rim_sharp_rms_px) {
    throw std::invalid_argument("estimator.rim_loose_rms_px must be at least rim_sharp_rms_px");
  }
  if (fitness.outer_radius_fraction <= fitness.inner_radius_fraction) {
    throw std::invalid_argument(
        "estimator.fitness.outer_radius_fraction must exceed inner_radius_fraction");
  }
}

GaReading first_ga_reading() { return GaReading{"per_child", "children", "children", "binary"}; }

GaReading EstimatorParams::ga_reading() const { return improved() ? first_ga_reading() : faithful; }

void describe(hal::ParamVisitor& v, EstimatorParams& p) {
  v.param("mode", p.mode,
          "faithful: the paper's RM-GA alone; improved: plus blob seeding, elite refinement and "
          "motion prediction (each switchable below)",
          {"faithful", "improved"});
  v.param("budget", p.budget,
          "generations per frame: a fixed count (reproducible) or as many as fit in the time "
          "budget",
          {"generations", "time"});
  v.param("generations_per_frame", p.generations_per_frame,
          {"-", 1, 10000, "GA generations per frame when budget is 'generations' (paper: 9)"});
  v.param("time_budget_ms", p.time_budget_ms,
          {"ms", 0.1, 1000.0, "GA time per frame when budget is 'time'"});
  v.param(
      "recognition_threshold", p.recognition_threshold,
      {"-", 0.0, 1.0, "fitness at or above which the marker counts as recognised (paper: 0.6)"});
  v.param("water_correction", p.water_correction,
          {"-", 0.0, 1.0,
           "improved mode: white balance to the scene's median colour before the hue windows, "
           "as a power of the full gain (0 off, 1 full): water takes red first"});
  v.param("water_retry", p.water_retry,
          {"-", 0.0, 1.0,
           "improved mode: a frame whose estimate is not ok is segmented again white-balanced "
           "with this strength (as water_correction) and kept if that estimate is ok; the red "
           "sphere far out in coastal water; 0 off"});
  v.param("denoise_retry_px", p.denoise_retry_px,
          {"px", 0, 5,
           "improved mode: a frame whose estimate is still not ok after the second look is "
           "median-filtered with this aperture (3 or 5) and looked at once more, kept if ok: "
           "sensor noise and JPEG blocks break a small sphere's rim into specks; 0 off"});
  v.param("retry_memory_frames", p.retry_memory_frames,
          {"frames", 1, 1000,
           "improved mode, with the tracker on: for this many frames after the first look was "
           "last ok, a frame it declines for a partial view or no marker gets the second and "
           "third looks only while they earn their keep (retry_pause_frames): such a frame "
           "mostly has a bar or a hidden sphere in it, which the tracker carries the pose "
           "through (the sim's bars hide a sphere for up to 2.3 s)"});
  v.param("retry_misses", p.retry_misses,
          {"-", 1, 1000,
           "improved mode, with the tracker on, within retry_memory_frames: after this many "
           "tries in a row of the second and third looks that none made ok, they pause "
           "(retry_pause_frames)"});
  v.param("retry_pause_frames", p.retry_pause_frames,
          {"frames", 1, 1000,
           "improved mode, with the tracker on: once paused (retry_misses), the second and "
           "third looks are tried once per this many frames declined for a partial view or no "
           "marker"});
  v.param("ga_restart_frames", p.ga_restart_frames,
          {"frames", 0, 1000,
           "improved mode: after this many frames in a row whose pose neither the centroids nor "
           "the rims could confirm, the next frame's GA starts from a fresh population: beside a "
           "sphere cut by the image edge it can settle 30-80 deg off, where neither refinement "
           "is accepted, and stay; 0 off"});
  v.param("sphere_support", p.sphere_support,
          {"-", 0.0, 1.0,
           "score of one sphere in one view (inner hits minus ring hits) at which it counts as "
           "seen; an estimate is ok only with every sphere seen in both views"});
  v.param("rim_support", p.rim_support,
          {"-", 0.0, 1.0,
           "improved mode: fraction of a sphere's predicted rim that its colour edge must confirm "
           "for a partly hidden sphere (score below sphere_support) to count as seen"});
  v.param("smear_inner_min", p.smear_inner_min,
          {"-", 0.0, 1.01,
           "improved mode: share of a sphere's inner disc on its colour at which a sphere that "
           "spills over its ring (motion blur) still counts as seen; 1.01 turns this off"});
  v.param("smear_ring_max", p.smear_ring_max,
          {"-", 0.0, 1.0,
           "improved mode: most of the ring a smeared sphere may cover and still count as seen; "
           "a pose that is off, or too far, puts colour all round the ring"});
  v.param("rim_bound", p.rim_bound,
          "improved mode: how a rim fit's error bound is found. counted: its covariance counts 8 "
          "independent points a silhouette, 99 % quantile for rims within rim_quantile_rms_px, "
          "else 3 sigma; measured: on the first look, from the rims' own misfit per silhouette "
          "(radius and centre), 99 % quantile, with rims up to rim_loose_rms_px where tighter "
          "than the centroids' and the centroids' noise over the coordinates the pose leaves "
          "free",
          {"counted", "measured"});
  v.param("rim_sharp_rms_px", p.rim_sharp_rms_px,
          {"px", 0.1, 10.0,
           "improved mode: the rim fit replaces the centroids' pose when the rims fit this well "
           "(rms); a sharp sphere's rim fits to 0.35-0.45 px, a blurred or noisy one (motion "
           "blur, JPEG) leans the pose while its centroids stay true"});
  v.param("rim_quantile_rms_px", p.rim_quantile_rms_px,
          {"px", 0.1, 10.0,
           "improved mode, rim_bound counted: a rim fit's error bound is its covariance's 99 % "
           "quantile only when the rims fit this well (rms); a looser fit (JPEG blocks, a faded "
           "or smeared edge) keeps 3 sigma of the trace, as the centroids do: the quantile was "
           "calibrated on sharp rims, and a JPEG-blocked rim fitting to 0.61 px was 6.4 deg off "
           "inside a 3.5 deg quantile"});
  v.param("rim_loose_rms_px", p.rim_loose_rms_px,
          {"px", 0.1, 10.0,
           "improved mode, rim_bound measured: a rim fit looser than rim_sharp_rms_px but within "
           "this (rms) replaces the centroids' pose only where its error bound is tighter than "
           "theirs"});
  v.param("rim_ring_max", p.rim_ring_max,
          {"-", 0.0, 1.0,
           "improved mode: the rim fit replaces the centroids' pose only when no sphere's colour "
           "covers more than this share of the ring around its fitted rim (a smear: its rims lean "
           "the pose along it)"});
  v.param("ok_bound_mm", p.ok_bound_mm,
          {"mm", 0.1, 1000.0,
           "improved mode: an estimate is ok only when its position error bound (a sharp rim "
           "fit's 99 % quantile, or 3 sigma of the centroids' or a loose rim fit's) is within "
           "this"});
  v.param("ok_bound_deg", p.ok_bound_deg,
          {"deg", 0.01, 180.0,
           "improved mode: an estimate is ok only when its rotation error bound (as ok_bound_mm) "
           "is within this"});
  v.section("confirm",
            "improved mode, in the loop (run, sim): an ok estimate is trusted only when the frame "
            "before had an ok pose it agrees with, within both error bounds and the vehicle's "
            "motion in between (rovctl estimate and bench judge one pair and skip this)",
            [&p](hal::ParamVisitor& s) {
              s.param("rate_dps", p.confirm.rate_dps,
                      {"deg/s", 0.0, 3600.0,
                       "the fastest the vehicle turns: the rotation two frames may differ by "
                       "beyond their bounds, and with the marker's range, how far it may seem to "
                       "move; 0 turns confirmation off"});
              s.param("speed_mps", p.confirm.speed_mps,
                      {"m/s", 0.0, 100.0, "the fastest the vehicle moves"});
              s.param("gap_ms", p.confirm.gap_ms,
                      {"ms", 1.0, 10000.0,
                       "the frame before confirms only if taken this recently (a skipped frame "
                       "or two at 33 ms)"});
            });
  v.section("ga", "the genetic algorithm (paper's Table 2)", [&p](hal::ParamVisitor& s) {
    s.param("population", p.ga.population, {"-", 4, 2000, "number of genes"});
    s.param("selection_rate", p.ga.selection_rate,
            {"-", 0.05, 1.0, "fraction of the population, by rank, that survives and breeds"});
    s.param("mutation_rate", p.ga.mutation_rate,
            {"-", 0.0, 1.0, "probability that an offspring is mutated"});
    s.param("elite_count", p.ga.elite_count,
            {"-", 0, 100, "best genes carried over unchanged (elitism)"});
  });
  v.section("faithful",
            "faithful mode: the reading of what the paper's GA leaves open (improved mode runs "
            "per_child / children / children); `rovctl study` scores each against the paper",
            [&p](hal::ParamVisitor& s) {
              s.param("mutation", p.faithful.mutation,
                      "what mutation_rate is the probability of: per_child (one random bit "
                      "flipped in each of the six fields of a mutated child), per_field (one "
                      "random bit in each field that mutates), per_bit (each of the 72 bits)",
                      {"per_child", "per_field", "per_bit"});
              s.param("mutants", p.faithful.mutants,
                      "which genes mutate: the bred children only, or every gene outside the "
                      "elite (survivors mutate in place)",
                      {"children", "non_elite"});
              s.param("evaluation", p.faithful.evaluation,
                      "which genes a generation evaluates: the changed ones, or the whole "
                      "population (same result on one frame, the cost the paper's Fig. 8 counts)",
                      {"children", "population"});
              s.param("coding", p.faithful.coding,
                      "how 12 bits encode a field: binary, or a reflected Gray code (neighbouring "
                      "values one bit apart)",
                      {"binary", "gray"});
            });
  v.section("search", "GA search volume: marker origin in the left camera frame",
            [&p](hal::ParamVisitor& s) {
              s.param("x_min_m", p.search.x_min_m, {"m", -5.0, 5.0, "lowest x (right)"});
              s.param("x_max_m", p.search.x_max_m, {"m", -5.0, 5.0, "highest x"});
              s.param("y_min_m", p.search.y_min_m, {"m", -5.0, 5.0, "lowest y (down)"});
              s.param("y_max_m", p.search.y_max_m, {"m", -5.0, 5.0, "highest y"});
              s.param("z_min_m", p.search.z_min_m, {"m", 0.05, 10.0, "nearest z (ahead)"});
              s.param("z_max_m", p.search.z_max_m, {"m", 0.05, 10.0, "farthest z"});
              s.param("epsilon_max", p.search.epsilon_max,
                      {"-", 0.01, 1.0,
                       "range of each quaternion vector component e1..e3 (0.5: 60 deg per axis)"});
            });
  v.section("fitness", "sample points of the fitness function", [&p](hal::ParamVisitor& s) {
    s.param("inner_points", p.fitness.inner_points,
            {"-", 1, 256, "points inside each projected sphere"});
    s.param("outer_points", p.fitness.outer_points,
            {"-", 1, 256, "points on the background ring around each projected sphere"});
    s.param("inner_radius_fraction", p.fitness.inner_radius_fraction,
            {"-", 0.1, 1.0, "inner points lie within this fraction of the projected radius"});
    s.param("outer_radius_fraction", p.fitness.outer_radius_fraction,
            {"-", 1.0, 4.0, "radius of the background ring, in projected radii"});
    s.param("far_field_weight", p.fitness.far_field_weight,
            {"-", 0.0, 100.0,
             "not in the paper (far_field_fitness): weight of the mean nearness in the score the "
             "GA ranks by; weight / reach is the far field's slope, 1 per 50 px like the paper's "
             "F as it begins to see a sphere; F alone decides among poses whose spheres all lie "
             "on their colours"});
    s.param("far_field_reach_px", p.fitness.far_field_reach_px,
            {"px", 8.0, 10000.0,
             "not in the paper (far_field_fitness): a projected sphere centre this far from the "
             "nearest pixels of its colour has nearness 0 (1 on them, linear between)"});
    s.param("far_field_cell_px", p.fitness.far_field_cell_px,
            {"px", 1, 64,
             "not in the paper (far_field_fitness): side of the grid cells on which the far "
             "field's distances are measured once per frame"});
  });
  v.param("blob_seeding", p.blob_seeding,
          "improved mode: seed genes from colour blobs triangulated in both images");
  v.param("refine_elite", p.refine_elite,
          "improved mode: least-squares refinement of the elite on the blobs' centroids");
  v.param("far_field_fitness", p.far_field_fitness,
          "not in the paper, any mode: rank genes by the paper's fitness plus a graded term for "
          "how near each projected sphere lies to its colour (orders the poses the paper's "
          "fitness scores 0); the estimate's fitness stays the paper's");
}

}  // namespace rovctl::estimator
