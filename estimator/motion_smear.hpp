// Motion blur read from the blobs: the camera's motion during the exposure smears every sphere of
// a view alike, so a smear two blobs agree on is the view's, and a dim sphere measured short of it
// is smeared by it all the same.
#pragma once

#include <array>

#include "hal/model/marker_model.hpp"

namespace rovctl::estimator {

// One blob's silhouette read as a disc smeared along a line (BlobSeeder): the smear's vector
// (either way along it) and the width across it, in pixels; zero for no blob.
struct BlobSmear {
  double u_px = 0.0, v_px = 0.0;
  double width_px = 0.0;
};

// The view's smear: the longest of the blobs that agree, and the least length and the range of
// widths among them, against which a sphere's image at a candidate pose is measured before the
// smear is taken.
struct SharedSmear {
  bool valid = false;
  double u_px = 0.0, v_px = 0.0;
  double min_length_px = 0.0;
  double min_width_px = 0.0;
  double max_width_px = 0.0;
};

// Two blobs agree when their smears point within kSmearAgreeDeg of each other and the shorter is
// at least kSmearAgreeLength of the longer. Valid when two or more agree (the largest such set;
// the longer at a tie); a lone elongated blob is a shadow, an occluder or a merged neighbour.
// A blob outside that set at least kSmearVetoWidth as wide as the set's narrowest and under
// kSmearVetoLength of its shortest is a sphere imaged sharp and whole, and then there is no smear
// (in the sim a bar passing two spheres made both long and wide, the third round beside them).
// A dim sphere's smear is labelled in its core only: short, but narrower too.
SharedSmear shared_smear(const std::array<BlobSmear, hal::kColourClassCount>& by_colour);

constexpr double kSmearAgreeDeg = 20.0;
constexpr double kSmearAgreeLength = 0.7;
constexpr double kSmearVetoWidth = 0.9;
constexpr double kSmearVetoLength = 0.5;

}  // namespace rovctl::estimator
