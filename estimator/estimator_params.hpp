// The `estimator` config section: segmentation samples, the RM-GA's parameters (defaults from the
// paper's Table 2), the search volume, the per-frame budget and the improvements beyond the paper.
#pragma once

#include <string>

#include "hal/primitives/parameters.hpp"

namespace rovctl::estimator {

// Where the genes live: the marker origin in the left camera frame, and the range of the
// quaternion's vector part (each of e1, e2, e3 in [-epsilon_max, epsilon_max]).
struct SearchVolume {
  double x_min_m = -0.4, x_max_m = 0.4;
  double y_min_m = -0.2, y_max_m = 0.2;
  double z_min_m = 0.15, z_max_m = 1.6;
  double epsilon_max = 0.5;  // 0.5: up to 60 degrees about any one axis
};

// Sample points of the fitness function, in units of each sphere's projected radius.
struct FitnessParams {
  int inner_points = 16;
  int outer_points = 16;
  double inner_radius_fraction = 0.8;  // inner points lie within this fraction of the radius
  double outer_radius_fraction = 1.4;  // the background ring lies at this fraction
  // Not in the paper: the graded far field (EstimatorParams::far_field_fitness, MarkerFitness).
  // Its slope, weight / reach = 1 per 50 px, matches the paper's F where F begins to see a sphere:
  // one sphere's score rises from 0 to ~1 over 1.8 projected radii (the inner disc's 0.8 r plus
  // the sphere's r), 48 px for the paper's 20 mm spheres at 415 mm (552 px focal length). So
  // where the far field saturates (a centre on its colour) F carries on at the same rate, with no
  // cliff in what the GA prefers. At weight 2 (1 per 400 px) the far-field variant took 5 frames
  // median to F 0.6 instead of 4, p90 9 instead of 6 (128 seeds of the study's scene).
  double far_field_weight = 16.0;     // of the mean nearness in the score the GA ranks by
  double far_field_reach_px = 800.0;  // the image diagonal: every pose seen in the image is graded
  int far_field_cell_px = 8;          // side of the grid cells the distances are measured on
};

struct GaParams {
  int population = 40;
  double selection_rate = 0.6;  // the top fraction (by rank) that survives and breeds
  double mutation_rate = 0.1;   // probability that an offspring is mutated
  int elite_count = 1;          // best individuals carried unchanged (elitism)
};

// The paper (Sec. 2.3) names elitism, two-point crossover, a selection rate and a mutation rate
// and leaves the rest open; these are the readings of what it leaves open. The faithful mode runs
// the configured reading (the defaults fit the paper best: `rovctl study`'s ablation); the improved
// mode always runs the reading rovctl shipped first (per_child, children, children), so the
// closed loop does not change with the faithful default.
struct GaReading {
  // per_child: with probability mutation_rate a child gets one random bit flipped in each of its
  // six fields; per_field: each field, with that probability, gets one random bit flipped;
  // per_bit: each of the 72 bits flips with that probability.
  std::string mutation = "per_bit";
  std::string mutants = "children";       // children: only the bred children; non_elite: too
                                          // the survivors outside the elite
  std::string evaluation = "population";  // children: only changed genes; population: every gene
                                          // every generation (Fig. 8's cost ~ population)
  std::string coding = "gray";  // binary: a field is a plain 12-bit number; gray: a Gray code
};

// In the loop only (improved mode): an ok estimate must be confirmed by the frame before.
struct ConfirmationParams {
  double rate_dps = 60.0;  // the fastest the vehicle turns; 0 turns the check off
  double speed_mps = 1.0;  // the fastest it moves
  double gap_ms = 100.0;   // the last sound pose confirms only this recently
};

struct EstimatorParams {
  // "faithful": the paper's RM-GA alone. "improved": plus the switches below.
  std::string mode = "improved";
  GaParams ga;
  GaReading faithful;  // the faithful mode's reading of the paper's GA
  SearchVolume search;
  FitnessParams fitness;
  // "generations": a fixed count per frame (reproducible with a seed); "time": as many
  // generations as fit in time_budget_ms.
  std::string budget = "generations";
  int generations_per_frame = 9;
  double time_budget_ms = 15.0;
  double recognition_threshold = 0.6;
  // A sphere counts as seen in a view when its score(v, s) reaches this (1 = the whole disc on
  // its colour and none of the ring).
  double sphere_support = 0.8;
  double rim_support = 0.4;
  // "counted" or "measured": how a rim fit's error bound is found (see describe()).
  std::string rim_bound = "counted";
  double rim_sharp_rms_px = 0.62;
  double rim_quantile_rms_px = 0.5;
  double rim_loose_rms_px = 0.8;
  double rim_ring_max = 0.1;
  // Improved mode: a motion-blurred sphere fills its disc and smears over part of its ring, so it
  // scores under sphere_support while its centroid (mid-exposure) is right. It counts as seen when
  // at least smear_inner_min of the disc and at most smear_ring_max of the ring are its colour.
  double smear_inner_min = 0.95;
  double smear_ring_max = 0.5;
  double ok_bound_mm = 10.0;
  double ok_bound_deg = 5.0;
  ConfirmationParams confirm;
  // Improved mode: how far the segmentation divides out the scene's colour cast (0 off, 1 full
  // von Kries white balance to the median colour).
  double water_correction = 0.0;
  // Improved mode: a frame whose estimate is not ok is segmented again with this correction (the
  // same scale) and estimated once more; that estimate is kept only if it is ok. 0 off.
  double water_retry = 0.5;
  // Improved mode: and if that is not ok either, the pair median-filtered with this aperture is
  // looked at once more, kept only if ok. 0 off.
  int denoise_retry_px = 5;
  // Improved mode, Looks::as_needed (the tracker on): how long the first look's last ok counts
  // as seeing the marker (longer than a bar hides a sphere), after how many tries in a row that
  // none made ok the later looks pause, and for how many declined frames.
  int retry_memory_frames = 90;
  int retry_misses = 8;
  int retry_pause_frames = 15;
  // Improved mode: after this many frames in a row that no refinement confirmed, the GA starts
  // the next frame from a fresh population. 0 off.
  int ga_restart_frames = 3;
  // Improvements (used when mode is "improved").
  bool blob_seeding = true;  // seed individuals from colour blobs triangulated in 3D
  bool refine_elite = true;  // least-squares refinement of the elite on blob centroids
  // Not in the paper, any mode: the GA ranks genes by the paper's fitness plus a small graded
  // term (how near each projected sphere centre lies to its colour) that orders the ~90 % of
  // the search volume the paper's fitness scores 0. The estimate's fitness stays the paper's.
  bool far_field_fitness = false;

  bool improved() const { return mode == "improved"; }
  // The GA reading this mode runs (see GaReading).
  GaReading ga_reading() const;
  // Cross-field checks the per-key ranges cannot express; throws std::invalid_argument.
  void validate() const;
};

// The reading rovctl shipped first and the improved mode keeps (binary coding).
GaReading first_ga_reading();

void describe(hal::ParamVisitor& v, EstimatorParams& params);

}  // namespace rovctl::estimator
