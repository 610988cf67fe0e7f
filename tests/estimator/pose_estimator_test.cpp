// The estimator end to end on rendered pairs of the shipped distorted, toe-in, non-rectified rig.
#include "estimator/pose_estimator.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "hal/model/pose.hpp"
#include "test_scene.hpp"

namespace rovctl::estimator {
namespace {

using testing::random_pose;
using testing::rotation_error_deg;
using testing::TestScene;
using testing::translation_error_mm;

TEST(PoseEstimator, ImprovedModeFindsThePoseInTheFirstFrame) {
  TestScene scene;
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    const Eigen::Isometry3d truth = random_pose(rng);
    scene.render(truth, trial);
    PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, trial);
    const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
    EXPECT_TRUE(e.recognised) << trial;
    EXPECT_GE(e.fitness, 0.9) << trial;
    EXPECT_EQ(e.generations, 9);
    EXPECT_LT(translation_error_mm(e.T_cl_marker, truth), 2.0) << trial;
    EXPECT_LT(rotation_error_deg(e.T_cl_marker, truth), 1.0) << trial;
  }
}

// `rovctl estimate` and the operator say why an estimate is not trusted: the first test it failed.
TEST(PoseEstimator, AnEstimateNotOkSaysWhichTestItFailed) {
  TestScene scene;
  const Eigen::Isometry3d truth = hal::make_pose(
      {0.03, -0.02, 0.6},
      Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 2, 0).normalized())));
  scene.render(truth, 5);
  {
    PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 5);
    const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
    ASSERT_TRUE(e.ok);
    EXPECT_EQ(e.not_ok_reason, NotOkReason::none);
  }
  {
    // Every sphere seen and refined, the bound over a limit tighter than any fit.
    EstimatorParams tight;
    tight.ok_bound_deg = 0.01;
    PoseEstimator est(scene.rig, scene.marker, tight, 5);
    const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
    EXPECT_FALSE(e.ok);
    EXPECT_TRUE(e.refined || e.rim_refined);
    EXPECT_EQ(e.spheres_seen[0], 3);
    EXPECT_EQ(e.not_ok_reason, NotOkReason::bound_over_limit);
    EXPECT_STREQ(to_string(e.not_ok_reason), "bound_over_limit");
  }
  {
    // The red sphere painted out of the left image: seen in one view only.
    Eigen::Vector2d uv;
    ASSERT_TRUE(scene.rig.left.project(truth * scene.marker.spheres[0].centre_marker_m, uv));
    cv::circle(scene.left_bgr, cv::Point(static_cast<int>(uv.x()), static_cast<int>(uv.y())), 40,
               cv::Scalar(90, 70, 40), cv::FILLED);
    PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 5);
    const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
    EXPECT_TRUE(e.recognised);
    EXPECT_FALSE(e.ok);
    EXPECT_EQ(e.spheres_seen[0], 2);
    EXPECT_EQ(e.not_ok_reason, NotOkReason::partial_view);
  }
  // Nothing to see: not recognised, which is its own answer.
  PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 5);
  const PoseEstimate e = est.update(scene.empty_image(), scene.empty_image());
  EXPECT_FALSE(e.recognised);
  EXPECT_EQ(e.not_ok_reason, NotOkReason::none);
}

// The marker 0.55 m out, turned 8.6 deg about a slanted axis, every sphere whole in both views.
Eigen::Isometry3d render_turned_marker(TestScene& scene) {
  const Eigen::Isometry3d truth = hal::make_pose(
      {0.02, 0.01, 0.55},
      Eigen::Quaterniond(Eigen::AngleAxisd(0.15, Eigen::Vector3d(1, -1, 0).normalized())));
  scene.render(truth, 7);
  return truth;
}

// A sphere hidden in both views: the rims' fit still places the two that show (what the tracker
// rides through the hidden sphere on).
TEST(PoseEstimator, AHiddenSpheresPartialViewPlacesTheOthersOnTheirRims) {
  TestScene scene;
  const Eigen::Isometry3d truth = render_turned_marker(scene);
  scene.hide_sphere(truth, 0);
  PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 5);
  const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
  ASSERT_EQ(e.not_ok_reason, NotOkReason::partial_view);
  ASSERT_TRUE(e.rims_sharp);
  for (int v = 0; v < 2; ++v) {
    EXPECT_LT(e.rim_support[v][0], EstimatorParams{}.rim_support);
    for (int s = 1; s < 3; ++s) {
      EXPECT_GE(e.rim_support[v][s], EstimatorParams{}.rim_support);
      const Eigen::Vector3d c = scene.marker.spheres[s].centre_marker_m;
      EXPECT_LE((e.T_cl_marker_rims * c - truth * c).norm(), 0.002) << s;
    }
  }
}

// With the tracker on, while the first look has been seeing the marker, the second and third
// looks at a frame it declines for a hidden sphere pause after retry_misses tries that none made
// ok, and are tried again once per retry_pause_frames such frames. Searching (nothing ok yet)
// they always run.
TEST(PoseEstimator, AsNeededLooksPastTheFirstOnlyWhileThatEarnsItsKeep) {
  TestScene scene;
  const Eigen::Isometry3d truth = render_turned_marker(scene);
  const cv::Mat whole_left = scene.left_bgr.clone(), whole_right = scene.right_bgr.clone();
  scene.hide_sphere(truth, 0);
  EstimatorParams params;
  params.retry_misses = 3;
  params.retry_pause_frames = 4;
  auto evaluations = [&](PoseEstimator& est, const cv::Mat& left, const cv::Mat& right,
                         PoseEstimate* e = nullptr) {
    const long before = est.fitness_evaluations();
    const PoseEstimate out = est.update(left, right, Looks::as_needed);
    if (e != nullptr) *e = out;
    return est.fitness_evaluations() - before;
  };
  PoseEstimator tracking(scene.rig, scene.marker, params, 5);
  PoseEstimate e;
  evaluations(tracking, whole_left, whole_right, &e);
  ASSERT_TRUE(e.ok);
  ASSERT_FALSE(e.water_corrected || e.denoised);
  std::vector<long> declined;
  for (int frame = 0; frame < 8; ++frame) {
    declined.push_back(evaluations(tracking, scene.left_bgr, scene.right_bgr, &e));
    EXPECT_EQ(e.not_ok_reason, NotOkReason::partial_view) << frame;
  }
  const long first_look_only = declined[3];
  for (int frame : {0, 1, 2, 7}) EXPECT_GT(declined[frame], 2 * first_look_only) << frame;
  for (int frame : {4, 5, 6}) EXPECT_LT(declined[frame], 2 * first_look_only) << frame;

  PoseEstimator searching(scene.rig, scene.marker, params, 5);
  for (int frame = 0; frame < 5; ++frame) {
    EXPECT_GT(evaluations(searching, scene.left_bgr, scene.right_bgr), 2 * first_look_only)
        << frame;
  }
}

// Telemetry writes the reason as its token and `rovctl view` reads it back.
TEST(PoseEstimator, ANotOkReasonReadsBackFromItsToken) {
  for (const NotOkReason r :
       {NotOkReason::none, NotOkReason::partial_view, NotOkReason::not_refined,
        NotOkReason::bound_over_limit, NotOkReason::unconfirmed}) {
    NotOkReason back = r == NotOkReason::none ? NotOkReason::partial_view : NotOkReason::none;
    ASSERT_TRUE(from_string(to_string(r), back)) << to_string(r);
    EXPECT_EQ(back, r);
  }
  NotOkReason unchanged = NotOkReason::not_refined;
  EXPECT_FALSE(from_string("partial", unchanged));
  EXPECT_FALSE(from_string("", unchanged));
  EXPECT_FALSE(from_string("unknown", unchanged));
  EXPECT_EQ(unchanged, NotOkReason::not_refined);
}

TEST(PoseEstimator, FaithfulModeClimbsAndIsReproducible) {
  TestScene scene;
  const Eigen::Isometry3d truth =
      hal::make_pose({0.05, 0.01, 0.45}, Eigen::Quaterniond::Identity());
  scene.render(truth);
  EstimatorParams p;
  p.mode = "faithful";
  PoseEstimator a(scene.rig, scene.marker, p, 5), b(scene.rig, scene.marker, p, 5);
  double first = 0.0, last = 0.0;
  for (int f = 0; f < 150; ++f) {
    const PoseEstimate ea = a.update(scene.left_bgr, scene.right_bgr);
    const PoseEstimate eb = b.update(scene.left_bgr, scene.right_bgr);
    ASSERT_EQ(ea.fitness, eb.fitness);
    ASSERT_TRUE(ea.T_cl_marker.isApprox(eb.T_cl_marker));
    ASSERT_GE(ea.fitness, last);  // elitism on a static pair
    if (f == 0) first = ea.fitness;
    last = ea.fitness;
  }
  EXPECT_GT(last, first);
}

// With nothing to confirm a pose (no marker in view) the GA starts afresh after every
// ga_restart_frames frames; while the refinement confirms the marker it never does, and 0 is off.
TEST(PoseEstimator, TheGaStartsAfreshOnlyAfterFramesNoRefinementConfirmed) {
  TestScene scene;
  scene.render(hal::make_pose({0.05, 0.01, 0.5}, Eigen::Quaterniond::Identity()));
  const cv::Mat empty_left = scene.empty_image();
  const cv::Mat empty_right = scene.empty_image();
  EstimatorParams p;
  p.ga_restart_frames = 3;
  PoseEstimator est(scene.rig, scene.marker, p, 1);
  std::vector<int> restarted_at;
  for (int frame = 1; frame <= 10; ++frame) {
    const PoseEstimate e = est.update(empty_left, empty_right);
    ASSERT_FALSE(e.refined || e.rim_refined);
    if (e.ga_restarted) restarted_at.push_back(frame);
  }
  EXPECT_EQ(restarted_at, (std::vector<int>{4, 7, 10}));

  for (int frame = 1; frame <= 10; ++frame) {
    const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
    EXPECT_TRUE(e.ok) << frame;
    EXPECT_FALSE(e.ga_restarted) << frame;
  }

  // reset() draws a fresh population itself: the frames unconfirmed before it no longer count.
  restarted_at.clear();
  for (int frame = 1; frame <= 7; ++frame) {
    if (frame == 4) est.reset();
    if (est.update(empty_left, empty_right).ga_restarted) restarted_at.push_back(frame);
  }
  EXPECT_EQ(restarted_at, (std::vector<int>{7}));

  p.ga_restart_frames = 0;
  PoseEstimator off(scene.rig, scene.marker, p, 1);
  for (int frame = 1; frame <= 10; ++frame) {
    EXPECT_FALSE(off.update(empty_left, empty_right).ga_restarted) << frame;
  }
  p.ga_restart_frames = 3;
  p.mode = "faithful";
  PoseEstimator faithful(scene.rig, scene.marker, p, 1);
  for (int frame = 1; frame <= 10; ++frame) {
    EXPECT_FALSE(faithful.update(empty_left, empty_right).ga_restarted) << "the paper's loop";
  }
}

// The estimator runs inside the tick: a wrong image is reported in the estimate, never thrown.
TEST(PoseEstimator, WrongImageSizeIsReportedNotThrown) {
  TestScene scene;
  PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 1);
  cv::Mat small(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_FALSE(est.segment(small, small));
  PoseEstimate e;
  EXPECT_NO_THROW(e = est.estimate());
  EXPECT_FALSE(e.recognised);
  ASSERT_NE(e.input_error, nullptr);
  EXPECT_NE(std::string(e.input_error).find("size"), std::string::npos);
  cv::Mat grey(scene.rig.left.height_px, scene.rig.left.width_px, CV_8UC1, cv::Scalar(0));
  EXPECT_FALSE(est.update(grey, grey).input_error == nullptr);
  // A good pair afterwards is estimated as usual.
  scene.render(hal::make_pose({0.0, 0.0, 0.5}, Eigen::Quaterniond::Identity()));
  EXPECT_EQ(est.update(scene.left_bgr, scene.right_bgr).input_error, nullptr);
}

TEST(PoseEstimator, InconsistentParamsThrow) {
  TestScene scene;
  EstimatorParams p;
  p.search.z_min_m = 2.0;
  EXPECT_THROW(PoseEstimator(scene.rig, scene.marker, p, 1), std::invalid_argument);
}

// A length_px smear along a slanted line, as a sideways surge during the exposure.
void smear(const cv::Mat& image, int length_px, cv::Mat& out) {
  cv::Mat kernel = cv::Mat::zeros(length_px, length_px, CV_32F);
  cv::line(kernel, {0, 4}, {length_px - 1, length_px - 5}, cv::Scalar(1.0));
  kernel /= cv::sum(kernel)[0];
  cv::filter2D(image, out, -1, kernel);
}

// A smeared rim fits loosely and leans the pose, while the smear's centroid stays at mid-exposure:
// the rims must not replace the centroids' pose then, and no blurred pair may be ok and wrong.
TEST(PoseEstimator, AMotionBlurredPairKeepsTheCentroidsPoseNotTheSmearedRims) {
  TestScene scene;
  std::mt19937_64 rng(11);
  int rim_refined = 0, sharp_rim_refined = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Eigen::Isometry3d truth = random_pose(rng);
    scene.render(truth, trial);
    PoseEstimator sharp(scene.rig, scene.marker, EstimatorParams{}, trial);
    sharp_rim_refined += sharp.update(scene.left_bgr, scene.right_bgr).rim_refined ? 1 : 0;
    cv::Mat left, right;
    smear(scene.left_bgr, 15, left);
    smear(scene.right_bgr, 15, right);
    PoseEstimator blurred(scene.rig, scene.marker, EstimatorParams{}, trial);
    const PoseEstimate e = blurred.update(left, right);
    rim_refined += e.rim_refined ? 1 : 0;
    if (e.ok) {
      EXPECT_LT(translation_error_mm(e.T_cl_marker, truth), 10.0) << trial;
      EXPECT_LT(rotation_error_deg(e.T_cl_marker, truth), 5.0) << trial;
    }
    if (e.rim_refined) {
      EXPECT_LE(e.rim_rms_px, EstimatorParams{}.rim_sharp_rms_px) << trial;
    }
  }
  EXPECT_GE(sharp_rim_refined, 6);
  EXPECT_LT(rim_refined, sharp_rim_refined);
}

// A smeared sphere fills its disc and spills over part of its ring, so it scores under
// sphere_support; it still counts as seen (and the pair as ok, when right), and only then.
TEST(PoseEstimator, ASmearedSphereThatFillsItsDiscCountsAsSeen) {
  TestScene scene;
  std::mt19937_64 rng(5);
  EstimatorParams rule;
  rule.water_retry = 0.0;     // the rule alone: no second look in the water's colour,
  rule.denoise_retry_px = 0;  // nor a third through a median
  EstimatorParams strict = rule;
  strict.smear_inner_min = 1.01;  // the rule off
  int ok = 0, ok_strict = 0, smeared = 0;
  for (int trial = 0; trial < 8; ++trial) {
    // A metre out, as in the validation set's motion blur: the spheres ~12 px across, the smear
    // about as long.
    const Eigen::Isometry3d truth = random_pose(rng, 0.9, 1.2, 20.0);
    scene.render(truth, trial);
    cv::Mat left, right;
    smear(scene.left_bgr, 13, left);
    smear(scene.right_bgr, 13, right);
    PoseEstimator with_rule(scene.rig, scene.marker, rule, trial);
    PoseEstimator without(scene.rig, scene.marker, strict, trial);
    const PoseEstimate e = with_rule.update(left, right);
    const PoseEstimate s = without.update(left, right);
    for (int v = 0; v < 2; ++v) {
      for (int k = 0; k < 3; ++k) {
        if (e.sphere_scores[v][k] < EstimatorParams{}.sphere_support &&
            e.sphere_ring_hits[v][k] > 0.0) {
          ++smeared;
        }
      }
    }
    if (e.ok) {
      ++ok;
      EXPECT_LT(translation_error_mm(e.T_cl_marker, truth), 10.0) << trial;
      EXPECT_LT(rotation_error_deg(e.T_cl_marker, truth), 5.0) << trial;
    }
    ok_strict += s.ok ? 1 : 0;
  }
  EXPECT_GT(smeared, 0);  // the smear does push spheres under sphere_support
  EXPECT_GT(ok, ok_strict);
}

}  // namespace
}  // namespace rovctl::estimator

namespace rovctl::estimator {
namespace {

// Far out in turbid water the red sphere fades under the hue windows; the second look, balanced
// to the water's cast, finds it again. Its estimate is kept only when ok, and says so.
TEST(PoseEstimator, ASecondLookInTheWatersColourFindsTheFadedRedSphere) {
  TestScene scene;
  // Murkier than the sim's default coastal water: red lost at 1.6 per metre, as in the validation
  // set's Jerlov 5C pairs, where the first look alone is right on half of them past a metre.
  hal::mock::ScenarioParams murky;
  murky.turbid.attenuation_rgb_per_m = {1.6, 0.45, 0.5};
  murky.turbid.veil_rgb = {0.05, 0.22, 0.17};
  const hal::mock::SceneConditions turbid = hal::mock::scene_conditions("turbid", murky, 3);
  const hal::mock::SceneRenderer left(scene.rig.left, scene.marker, scene.options, turbid);
  const hal::mock::SceneRenderer right(scene.rig.right, scene.marker, scene.options, turbid);
  EstimatorParams once;
  once.water_retry = 0.0;
  once.denoise_retry_px = 0;  // the first look alone
  std::mt19937_64 rng(17);
  int ok_once = 0, ok_twice = 0, corrected = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Isometry3d truth = random_pose(rng, 1.1, 1.5, 15.0);
    cv::Mat l, r;
    hal::mock::render_stereo(left, right, scene.rig, truth, trial, l, r);
    PoseEstimator first_only(scene.rig, scene.marker, once, trial);
    PoseEstimator with_retry(scene.rig, scene.marker, EstimatorParams{}, trial);
    const PoseEstimate a = first_only.update(l, r);
    const PoseEstimate b = with_retry.update(l, r);
    ok_once += a.ok ? 1 : 0;
    ok_twice += b.ok ? 1 : 0;
    if (b.water_corrected) {
      ++corrected;
      EXPECT_TRUE(b.ok) << trial << ": a second look is kept only when it is ok";
    }
    if (a.ok) {
      EXPECT_FALSE(b.water_corrected) << trial << ": no second look after an ok";
    }
    if (b.ok) {
      EXPECT_LT(translation_error_mm(b.T_cl_marker, truth), 10.0) << trial;
      EXPECT_LT(rotation_error_deg(b.T_cl_marker, truth), 5.0) << trial;
    }
  }
  std::printf("turbid 1.1-1.5 m: ok %d of 10 on the first look, %d with the second (%d from it)\n",
              ok_once, ok_twice, corrected);
  EXPECT_GT(corrected, 0);
  EXPECT_GT(ok_twice, ok_once);
}

}  // namespace
}  // namespace rovctl::estimator

namespace rovctl::estimator {
namespace {

// A committed pair of the water validation set (tests/data/estimator/NAME_{left,right}.png) and
// its truth, estimated as `rovctl bench --set` scores a still pair: the estimate after 10 frames.
struct WaterPair {
  cv::Mat left, right;
  Eigen::Isometry3d truth;
};

WaterPair read_water_pair(const std::string& name, const Eigen::Vector3d& t_cl_marker_m,
                          const Eigen::Quaterniond& q_cl_marker) {
  const std::string stem = std::string(ROVCTL_TEST_DATA_DIR) + "/estimator/" + name;
  WaterPair pair{cv::imread(stem + "_left.png", cv::IMREAD_COLOR),
                 cv::imread(stem + "_right.png", cv::IMREAD_COLOR),
                 Eigen::Translation3d(t_cl_marker_m) * q_cl_marker.normalized()};
  EXPECT_FALSE(pair.left.empty() || pair.right.empty()) << stem;
  return pair;
}

PoseEstimate after_ten_frames(PoseEstimator& estimator, const WaterPair& pair) {
  PoseEstimate e;
  for (int frame = 0; frame < 10; ++frame) e = estimator.update(pair.left, pair.right);
  return e;
}

// Two POV-Ray pairs of the validation set (seed 3, noise + JPEG, 1.3 m out; see
// tests/data/README.md): the first two looks leave them partial, the third look, on the median-
// filtered pair, vouches for them, and right.
TEST(PoseEstimator, AThirdLookOnTheMedianFilteredPairSeesThroughNoiseAndJpeg) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  const std::pair<const char*, WaterPair> pairs[] = {
      {"002", read_water_pair("noise_jpeg/002", {-0.17327, -0.403619, 1.27694},
                              {0.99630475, 0.01093526, 0.07218575, -0.04523804})},
      {"013", read_water_pair("noise_jpeg/013", {-0.079936, -0.092249, 1.297561},
                              {0.98971727, 0.13413628, 0.04740129, 0.01484281})},
  };
  EstimatorParams two_looks;
  two_looks.denoise_retry_px = 0;
  EstimatorParams no_water_look;  // the third look does not hang on the second
  no_water_look.water_retry = 0.0;
  int ok_two = 0, ok_three = 0, denoised = 0, denoised_without_water_look = 0, runs = 0;
  for (const auto& [name, pair] : pairs) {
    ASSERT_FALSE(pair.left.empty() || pair.right.empty()) << name;
    const cv::Mat& l = pair.left;
    const cv::Mat& r = pair.right;
    const Eigen::Isometry3d& truth = pair.truth;
    for (std::uint64_t seed = 0; seed < 3; ++seed, ++runs) {
      PoseEstimator without(rig, marker, two_looks, seed);
      PoseEstimator with(rig, marker, EstimatorParams{}, seed);
      PoseEstimator median_only(rig, marker, no_water_look, seed);
      PoseEstimate a, b, c;
      for (int frame = 0; frame < 10; ++frame) {  // as `rovctl bench --set` scores a pair
        a = without.update(l, r);
        b = with.update(l, r);
        c = median_only.update(l, r);
      }
      denoised_without_water_look += c.denoised ? 1 : 0;
      EXPECT_FALSE(c.water_corrected);
      ok_two += a.ok ? 1 : 0;
      ok_three += b.ok ? 1 : 0;
      if (b.denoised) {
        ++denoised;
        EXPECT_TRUE(b.ok) << name << ": a third look is kept only when it is ok";
      }
      if (b.ok) {
        EXPECT_LT(translation_error_mm(b.T_cl_marker, truth), 10.0) << name;
        EXPECT_LT(rotation_error_deg(b.T_cl_marker, truth), 5.0) << name;
      }
    }
  }
  std::printf(
      "noise + JPEG at 1.3 m: ok %d of %d runs with two looks, %d with three (%d from the "
      "third)\n",
      ok_two, runs, ok_three, denoised);
  EXPECT_GE(denoised, runs / 2);
  EXPECT_GE(denoised_without_water_look, runs / 2);
  EXPECT_GE(ok_three, ok_two + runs / 2);
}

// A water-set pair (seed 3) whose blue sphere the left image's top edge cuts, 1.39 m out: the
// centroids and the rims fit the triangle tilted either way about the line of sight, and the GA
// settles on the wrong tilt, 45 deg off. Whatever it settles on, its bound must reach the truth.
TEST(PoseEstimator, TheBoundReachesTheOtherTiltWhenTheImagesFitItAsWell) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  const WaterPair pair = read_water_pair("edge/022", {-0.323219, -0.476856, 1.259608},
                                         {0.96479046, 0.17103575, -0.19980979, 0.00148008});
  ASSERT_FALSE(pair.left.empty() || pair.right.empty());
  int wrong_tilt = 0, widened = 0;
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    PoseEstimator estimator(rig, hal::MarkerModel::standard(), EstimatorParams{}, seed);
    const PoseEstimate e = after_ten_frames(estimator, pair);
    const double off_deg = rotation_error_deg(e.T_cl_marker, pair.truth);
    ASSERT_TRUE(e.recognised);
    if (off_deg < 5.0) continue;
    ++wrong_tilt;
    EXPECT_FALSE(e.ok) << "seed " << seed << ": " << off_deg << " deg off";
    EXPECT_GE(e.error_bound_deg, 0.9 * off_deg) << "seed " << seed;
    widened += e.mirror_fits ? 1 : 0;
  }
  EXPECT_GE(wrong_tilt, 1) << "the pair no longer shows the ambiguity";
  EXPECT_EQ(widened, wrong_tilt);
}

// A water-set pair (seed 3) 1.1 m out with a pole's shadow across the red sphere: the rims fit
// to 0.64 deg, but the trace's 3 sigma of their covariance (5.9 deg) was over the 5 deg limit.
// The 99 % quantile of the same covariance is what the limit means.
TEST(PoseEstimator, TheRimsQuantileBoundVouchesForAShadowedMarker) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  const WaterPair pair = read_water_pair("side_light/004", {0.396253, -0.030454, 1.106398},
                                         {0.98701976, -0.13522834, 0.02919707, 0.08156486});
  ASSERT_FALSE(pair.left.empty() || pair.right.empty());
  int ok = 0;
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    PoseEstimator estimator(rig, hal::MarkerModel::standard(), EstimatorParams{}, seed);
    const PoseEstimate e = after_ten_frames(estimator, pair);
    ok += e.ok ? 1 : 0;
    if (e.ok) {
      EXPECT_TRUE(e.rim_refined);
      EXPECT_LT(translation_error_mm(e.T_cl_marker, pair.truth), 10.0) << "seed " << seed;
      EXPECT_LT(rotation_error_deg(e.T_cl_marker, pair.truth), 5.0) << "seed " << seed;
    }
  }
  EXPECT_GE(ok, 2);
}

// noise_jpeg/002's pose, noise and light at JPEG quality 80 (`--stream mjpg:80`; see
// tests/data/README.md), 1.35 m out: the red sphere's rim shows on its lit half only, and the rims
// fit to 0.61 px, under rim_sharp_rms_px, 6.4 deg off. Their covariance's 99 % quantile said
// 3.5 deg; a rim that fits that loosely keeps the trace's 3 sigma, which does not vouch for it.
TEST(PoseEstimator, ALooseRimFitKeepsTheTraceBound) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  const WaterPair pair = read_water_pair("noise_jpeg_q80/002", {-0.17327, -0.403619, 1.27694},
                                         {0.99630475, 0.01093526, 0.07218575, -0.04523804});
  ASSERT_FALSE(pair.left.empty() || pair.right.empty());
  EstimatorParams quantile_for_every_rim;
  quantile_for_every_rim.rim_quantile_rms_px = quantile_for_every_rim.rim_sharp_rms_px;
  int wrong_but_ok = 0, wrong_but_ok_with_quantile = 0, loose = 0;
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    PoseEstimator estimator(rig, hal::MarkerModel::standard(), EstimatorParams{}, seed);
    PoseEstimator with_quantile(rig, hal::MarkerModel::standard(), quantile_for_every_rim, seed);
    const PoseEstimate e = after_ten_frames(estimator, pair);
    const PoseEstimate q = after_ten_frames(with_quantile, pair);
    const auto wrong = [&pair](const PoseEstimate& x) {
      return translation_error_mm(x.T_cl_marker, pair.truth) >= 10.0 ||
             rotation_error_deg(x.T_cl_marker, pair.truth) >= 5.0;
    };
    wrong_but_ok += e.ok && wrong(e) ? 1 : 0;
    wrong_but_ok_with_quantile += q.ok && wrong(q) ? 1 : 0;
    if (e.rim_refined && e.rim_rms_px > EstimatorParams{}.rim_quantile_rms_px) ++loose;
  }
  EXPECT_EQ(wrong_but_ok, 0);
  EXPECT_GE(wrong_but_ok_with_quantile, 1)
      << "the pair no longer shows a loose rim fit that is wrong";
  EXPECT_GE(loose, 1);
}

// The same pair with rim_bound measured: the rims fit to 0.58-0.61 px, about 6 deg off, and their
// measured misfit (the red rim's radius off by a pixel or more) does not vouch for them.
TEST(PoseEstimator, AMeasuredBoundDoesNotVouchForARimFitOffInRadius) {
  const hal::StereoRig rig = load_stereo_calibration(testing::shipped_calibration_path());
  const WaterPair pair = read_water_pair("noise_jpeg_q80/002", {-0.17327, -0.403619, 1.27694},
                                         {0.99630475, 0.01093526, 0.07218575, -0.04523804});
  ASSERT_FALSE(pair.left.empty() || pair.right.empty());
  EstimatorParams measured;
  measured.rim_bound = "measured";
  int wrong_but_ok = 0, wrong_rims = 0;
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    PoseEstimator estimator(rig, hal::MarkerModel::standard(), measured, seed);
    const PoseEstimate e = after_ten_frames(estimator, pair);
    const double mm = translation_error_mm(e.T_cl_marker, pair.truth);
    const double deg = rotation_error_deg(e.T_cl_marker, pair.truth);
    wrong_but_ok += e.ok && (mm >= 10.0 || deg >= 5.0) ? 1 : 0;
    if (e.ok) {
      EXPECT_LE(mm, 1000.0 * e.error_bound_m) << "seed " << seed;
      EXPECT_LE(deg, e.error_bound_deg) << "seed " << seed;
    }
    wrong_rims += rotation_error_deg(e.T_cl_marker_rims, pair.truth) >= 5.0 ? 1 : 0;
  }
  EXPECT_EQ(wrong_but_ok, 0);
  EXPECT_GE(wrong_rims, 1) << "the pair no longer shows a rim fit that is wrong";
}

}  // namespace
}  // namespace rovctl::estimator
