// OpenCV stereo calibration YAML: the shipped file, a round trip, and every kind of bad file.
#include "estimator/stereo_calibration.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_scene.hpp"

namespace rovctl::estimator {
namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() / ("rovctl_est_" + name);
  std::ofstream(p) << text;
  return p.string();
}

std::string error_of(const std::string& file) {
  try {
    load_stereo_calibration(file);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

const char* kGood = R"(%YAML:1.0
---
image_size: [ 640, 480 ]
K1: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]
D1: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.1, 0.01, 0., 0., 0. ]
K2: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 510., 0., 300., 0., 505., 250., 0., 0., 1. ]
D2: !!opencv-matrix
   rows: 1
   cols: 4
   dt: d
   data: [ -0.1, 0.01, 0., 0. ]
R: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]
T: !!opencv-matrix
   rows: 3
   cols: 1
   dt: d
   data: [ -0.178, 0., 0. ]
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(StereoCalibration, LoadsTheShippedToeInRig) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  EXPECT_DOUBLE_EQ(rig.left.fx_px, 552.0);
  EXPECT_DOUBLE_EQ(rig.right.cx_px, 312.0);
  EXPECT_DOUBLE_EQ(rig.left.k1, -0.12);
  EXPECT_DOUBLE_EQ(rig.right.k3, 0.002);
  EXPECT_EQ(rig.left.width_px, 640);
  EXPECT_NEAR(rig.baseline_m(), 0.178, 1e-3);
  EXPECT_NEAR(Eigen::AngleAxisd(rig.T_cr_cl.linear()).angle(), 4.0 * M_PI / 180.0, 1e-6);
}

TEST(StereoCalibration, RoundTrip) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  const std::string file = temp_file("roundtrip.yaml", "");
  save_stereo_calibration(file, rig);
  const hal::StereoRig back = load_stereo_calibration(file);
  EXPECT_DOUBLE_EQ(back.right.fy_px, rig.right.fy_px);
  EXPECT_DOUBLE_EQ(back.left.p2, rig.left.p2);
  EXPECT_TRUE(back.T_cr_cl.isApprox(rig.T_cr_cl, 1e-12));
  EXPECT_EQ(back.right.height_px, 480);
}

TEST(StereoCalibration, FourCoefficientDistortionIsAccepted) {
  const hal::StereoRig rig = load_stereo_calibration(temp_file("good.yaml", kGood));
  EXPECT_DOUBLE_EQ(rig.right.k3, 0.0);
  EXPECT_DOUBLE_EQ(rig.right.cy_px, 250.0);
}

TEST(StereoCalibration, BadFilesNameFileAndKey) {
  EXPECT_NE(error_of("/nonexistent/cal.yaml").find("no such file"), std::string::npos);
  const std::string missing_r = temp_file("missing_r.yaml", replaced(kGood, "R: ", "Q: "));
  EXPECT_EQ(error_of(missing_r), missing_r + ": missing key 'R'");
  const std::string bad_shape =
      temp_file("bad_shape.yaml", replaced(kGood, "rows: 3\n   cols: 1", "rows: 1\n   cols: 1"));
  EXPECT_NE(error_of(bad_shape).find("key 'T'"), std::string::npos) << error_of(bad_shape);
  const std::string wide_d =
      temp_file("wide_d.yaml", replaced(kGood, "cols: 4\n   dt: d\n   data: [ -0.1, 0.01, 0., 0. ]",
                                        "cols: 2\n   dt: d\n   data: [ -0.1, 0.01 ]"));
  EXPECT_NE(error_of(wide_d).find("key 'D2' has shape"), std::string::npos) << error_of(wide_d);
  const std::string not_rotation =
      temp_file("not_rotation.yaml", replaced(kGood, "[ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]",
                                              "[ 2., 0., 0., 0., 1., 0., 0., 0., 1. ]"));
  EXPECT_NE(error_of(not_rotation).find("key 'R' is not a rotation"), std::string::npos);
  const std::string millimetres =
      temp_file("mm.yaml", replaced(kGood, "[ -0.178, 0., 0. ]", "[ -178., 0., 0. ]"));
  EXPECT_NE(error_of(millimetres).find("units must be metres"), std::string::npos);
  const std::string no_size =
      temp_file("no_size.yaml", replaced(kGood, "image_size: [ 640, 480 ]", "foo: 1"));
  EXPECT_NE(error_of(no_size).find("missing key 'image_size'"), std::string::npos);
  const std::string bad_focal =
      temp_file("bad_focal.yaml", replaced(kGood, "[ 500., 0., 320.", "[ -500., 0., 320."));
  EXPECT_NE(error_of(bad_focal).find("K1"), std::string::npos);
  const std::string garbage = temp_file("garbage.yaml", "%YAML:1.0\n---\nK1: [ unclosed\n");
  EXPECT_NE(error_of(garbage).find(garbage), std::string::npos);
  const std::string not_matrix = temp_file(
      "not_matrix.yaml", replaced(kGood, "D1: !!opencv-matrix", "D1: 7\nX: !!opencv-matrix"));
  EXPECT_NE(error_of(not_matrix).find("D1"), std::string::npos);
}

// What every command accepted before the loader checked the matrix's pattern and which side the
// right camera is on; each is refused naming the file, the key's line and what is wrong.
TEST(StereoCalibration, RefusesAGeometryNoCameraHas) {
  const std::string skewed = temp_file(
      "k10.yaml", replaced(kGood, "[ 500., 0., 320., 0., 500.", "[ 500., 0., 320., 300., 500."));
  EXPECT_NE(error_of(skewed).find(skewed + ":4: key 'K1': K(1,0) = 300"), std::string::npos)
      << error_of(skewed);
  const std::string swapped =
      temp_file("swapped.yaml", replaced(kGood, "[ -0.178, 0., 0. ]", "[ 0.178, 0., 0. ]"));
  EXPECT_NE(error_of(swapped).find(swapped + ":29: key 'T'"), std::string::npos)
      << error_of(swapped);
  EXPECT_NE(error_of(swapped).find("to the LEFT of the left one"), std::string::npos);
  const std::string forward =
      temp_file("forward.yaml", replaced(kGood, "[ -0.178, 0., 0. ]", "[ 0., 0., 0.2 ]"));
  EXPECT_NE(error_of(forward).find(forward + ":29: key 'T'"), std::string::npos)
      << error_of(forward);
  EXPECT_NE(error_of(forward).find("side by side"), std::string::npos);
  // A rig tilted or toed in but still side by side stays accepted (the shipped one is toed in).
  EXPECT_EQ(error_of(temp_file("toe.yaml",
                               replaced(kGood, "[ -0.178, 0., 0. ]", "[ -0.17, 0.02, 0.03 ]"))),
            "");
}

}  // namespace
}  // namespace rovctl::estimator
