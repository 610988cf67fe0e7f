// PoseTracker: coasting through a gap on a turning camera within its bound, two spheres of a
// partial view carrying the translation (and spheres that disagree vouching for nothing), a
// shaking camera's estimates taken, a single sure and wrong estimate rejected, the bound's growth
// and the coast's end, agreement tightening the bound, and the track moving to a new pose only when
// a second estimate confirms it.
#include "control/pose_tracker.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace rovctl::control {
namespace {

using std::chrono::nanoseconds;
constexpr double kDeg = M_PI / 180.0;

nanoseconds at_s(double s) { return nanoseconds(static_cast<long long>(s * 1e9)); }

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return std::abs(Eigen::AngleAxisd(a.transpose() * b).angle()) / kDeg;
}

// A camera (= body: T_body_cl identity) approaching a still marker at 0.2 m/s and yawing at
// 15 deg/s, the marker's pose in the camera and the camera's attitude at time t.
struct Scene {
  Eigen::Quaterniond q_world_cam(double t) const {
    return Eigen::Quaterniond(Eigen::AngleAxisd(15.0 * kDeg * t, Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()));
  }
  Eigen::Isometry3d T_cl_marker(double t) const {
    const Eigen::Vector3d p_world_cam(0.05 - 0.2 * t * std::sin(0.3), 0.02,
                                      -1.2 + 0.2 * t * std::cos(0.3));
    const Eigen::Matrix3d R_cw = q_world_cam(t).toRotationMatrix().transpose();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R_cw;  // the marker frame is the world's
    T.translation() = -(R_cw * p_world_cam);
    return T;
  }
  // The estimate at t, off by a small error that flips sign frame to frame (within its bound).
  PoseMeasurement measure(double t, int frame, double bound_m = 0.004,
                          double bound_deg = 1.0) const {
    PoseMeasurement m;
    m.sound = true;
    m.T_cl_marker = T_cl_marker(t);
    const double sign = frame % 2 == 0 ? 1.0 : -1.0;
    m.T_cl_marker.translation() += sign * Eigen::Vector3d(0.001, -0.001, 0.0015);
    m.T_cl_marker.linear() =
        m.T_cl_marker.linear() * Eigen::AngleAxisd(sign * 0.3 * kDeg, Eigen::Vector3d::UnitZ());
    m.bound_m = bound_m;
    m.bound_deg = bound_deg;
    return m;
  }
};

PoseTrackerParams params() {
  PoseTrackerParams p;
  p.max_coast_s = 1.5;
  p.accel_mps2 = 0.05;
  p.velocity_window_s = 0.5;
  p.fused_bound_share = 0.0;  // the estimates here are independent draws
  return p;
}

constexpr double kOkM = 0.010, kOkDeg = 5.0;

// Feeds frames [from, to) at 30 Hz, each with an estimate; returns the last output.
TrackedPose feed(PoseTracker& tracker, const Scene& scene, int from, int to) {
  TrackedPose out;
  for (int f = from; f < to; ++f) {
    const double t = f / 30.0;
    out = tracker.update(at_s(t), scene.q_world_cam(t), true, scene.measure(t, f));
  }
  return out;
}

TEST(PoseTracker, CoastsThroughAOneSecondGapOnATurningCameraWithinItsBound) {
  const Scene scene;
  PoseTracker tracker(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  EXPECT_EQ(feed(tracker, scene, 0, 30).source, TrackSource::fused);
  int ok = 0;
  for (int f = 30; f < 60; ++f) {  // 1 s without an estimate; the camera turns 15 deg meanwhile
    const double t = f / 30.0;
    const TrackedPose out = tracker.update(at_s(t), scene.q_world_cam(t), true, PoseMeasurement{});
    EXPECT_EQ(out.source, TrackSource::coasting);
    const Eigen::Isometry3d truth = scene.T_cl_marker(t);
    EXPECT_LE((out.T_cl_marker.translation() - truth.translation()).norm(), out.bound_m) << f;
    EXPECT_LE(angle_deg(out.T_cl_marker.linear(), truth.linear()), out.bound_deg) << f;
    // Carried by the attitude: without it the marker would be 15 deg and 0.3 m off by now.
    EXPECT_LE(angle_deg(out.T_cl_marker.linear(), truth.linear()), 1.0) << f;
    // ok exactly while the bound is within the estimator's limits (the gap is within max_coast).
    EXPECT_EQ(out.ok, out.bound_m <= kOkM && out.bound_deg <= kOkDeg) << f;
    if (out.ok) ++ok;
  }
  EXPECT_GE(ok, 6);                                                    // the first 0.2 s at least
  EXPECT_EQ(feed(tracker, scene, 60, 61).source, TrackSource::fused);  // caught again at once
}

// A partial view: two spheres on the marker's x axis, placed by T_cl_marker.
PoseMeasurement partial(const Eigen::Isometry3d& T_cl_marker) {
  PoseMeasurement m;
  m.points = 2;
  m.points_marker_m[0] = Eigen::Vector3d(-0.06, 0.0, 0.0);
  m.points_marker_m[1] = Eigen::Vector3d(0.06, 0.0, 0.0);
  m.T_cl_marker = T_cl_marker;
  return m;
}

// Two spheres where the track's rotation puts them relative to each other vouch for the
// translation: a second of a hidden sphere is ridden through, ok, the truth within the bound, and
// a partial view that disagrees with the prediction moves nothing.
TEST(PoseTracker, TwoSpheresThatAgreeCarryTheTrackThroughAHiddenSphere) {
  const Scene scene;
  PoseTracker tracker(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  feed(tracker, scene, 0, 30);
  int aided = 0;
  for (int f = 30; f < 60; ++f) {
    const double t = f / 30.0;
    // Free to turn about the line through them: 20 deg off, the two spheres still in place.
    Eigen::Isometry3d T =
        scene.T_cl_marker(t) * Eigen::AngleAxisd(20.0 * kDeg, Eigen::Vector3d::UnitX());
    if (f == 35) T.translation() += Eigen::Vector3d(0.05, 0.0, 0.0);  // a misfit
    const TrackedPose out = tracker.update(at_s(t), scene.q_world_cam(t), true, partial(T));
    const Eigen::Isometry3d truth = scene.T_cl_marker(t);
    EXPECT_LE((out.T_cl_marker.translation() - truth.translation()).norm(), out.bound_m) << f;
    EXPECT_LE(angle_deg(out.T_cl_marker.linear(), truth.linear()), out.bound_deg) << f;
    EXPECT_EQ(out.source, f == 35 ? TrackSource::coasting : TrackSource::aided) << f;
    EXPECT_TRUE(out.ok) << f;
    if (out.source == TrackSource::aided) ++aided;
  }
  EXPECT_EQ(aided, 29);
  EXPECT_LE(tracker.last().bound_m, 0.006);
}

// Spheres that do not agree with each other under the track's rotation (an occluder across one
// shifts its centre, and so its depth) move the track but vouch for nothing: the bound grows as
// the coast's from the last sound estimate, and so does a single sphere's.
TEST(PoseTracker, SpheresThatDisagreeMoveTheTrackWhileItsBoundGrowsAsTheCoasts) {
  const Scene scene;
  PoseTracker nudged_tracker(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  PoseTracker coasting_tracker(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  feed(nudged_tracker, scene, 0, 30);
  feed(coasting_tracker, scene, 0, 30);
  for (int f = 30; f < 50; ++f) {
    const double t = f / 30.0;
    // Turned 20 deg about the marker's y axis: one sphere 20 mm nearer, the other 20 mm further.
    PoseMeasurement m =
        partial(scene.T_cl_marker(t) * Eigen::AngleAxisd(20.0 * kDeg, Eigen::Vector3d::UnitY()));
    if (f >= 40) {  // then a single sphere, in place
      m = partial(scene.T_cl_marker(t));
      m.points = 1;
    }
    const TrackedPose out = nudged_tracker.update(at_s(t), scene.q_world_cam(t), true, m);
    const TrackedPose coast =
        coasting_tracker.update(at_s(t), scene.q_world_cam(t), true, PoseMeasurement{});
    EXPECT_EQ(out.source, TrackSource::nudged) << f;
    EXPECT_NEAR(out.bound_m, coast.bound_m, 1e-4) << f;  // the turn's share scales with the range
    EXPECT_NEAR(out.bound_deg, coast.bound_deg, 1e-9) << f;
    EXPECT_EQ(out.ok, coast.ok) << f;
  }
  EXPECT_FALSE(nudged_tracker.last().ok);  // the coast's bound is past the ok limit by now
}

// A camera that shakes on its mount (1.5 deg at 8 Hz) where the attitude sensor does not see it:
// its estimates disagree with the prediction until the unexplained motion widens the prediction's
// bounds; then they are fused and the track is ok with the truth within its bound. Without that
// estimate (unexplained_window_s 0), most are rejected.
TEST(PoseTracker, AShakingCameraWidensThePredictionSoItsEstimatesAreTaken) {
  const Scene scene;
  const auto run = [&scene](double window_s, int& ok, int& fused, int& covered) {
    PoseTrackerParams p = params();
    p.unexplained_window_s = window_s;
    PoseTracker tracker(p, Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
    ok = fused = covered = 0;
    for (int f = 0; f < 90; ++f) {
      const double t = f / 30.0;
      const Eigen::Matrix3d S(
          Eigen::AngleAxisd(1.5 * kDeg * std::sin(2.0 * M_PI * 8.0 * t), Eigen::Vector3d::UnitY()));
      PoseMeasurement m = scene.measure(t, f, 0.003, 0.5);
      m.T_cl_marker.prerotate(S.transpose());  // the marker in the camera as it really points
      const TrackedPose out = tracker.update(at_s(t), scene.q_world_cam(t), true, m);
      if (f < 30) continue;  // the first second: the shake is being learnt
      Eigen::Isometry3d truth = scene.T_cl_marker(t);
      truth.prerotate(S.transpose());
      ok += out.ok;
      fused += out.source == TrackSource::fused;
      covered += out.ok &&
                 (out.T_cl_marker.translation() - truth.translation()).norm() <= out.bound_m &&
                 angle_deg(out.T_cl_marker.linear(), truth.linear()) <= out.bound_deg;
    }
  };
  int ok = 0, fused = 0, covered = 0;
  run(0.0, ok, fused, covered);
  EXPECT_LT(ok, 40) << "without the unexplained motion, the track rejects the shaking estimates";
  run(1.0, ok, fused, covered);
  EXPECT_GE(ok, 57);
  EXPECT_GE(fused, 57);
  EXPECT_EQ(covered, ok);
}

TEST(PoseTracker, ASingleSureAndWrongEstimateIsRejected) {
  const Scene scene;
  PoseTracker tracker(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  feed(tracker, scene, 0, 20);
  const double t = 20 / 30.0;
  PoseMeasurement wrong = scene.measure(t, 20, 0.002, 1.0);  // sure: a 2 mm, 1 deg bound
  wrong.T_cl_marker.translation() += Eigen::Vector3d(0.012, 0.0, 0.0);
  wrong.T_cl_marker.linear() =
      wrong.T_cl_marker.linear() * Eigen::AngleAxisd(12.0 * kDeg, Eigen::Vector3d::UnitX());
  const TrackedPose out = tracker.update(at_s(t), scene.q_world_cam(t), true, wrong);
  EXPECT_TRUE(out.rejected);
  EXPECT_EQ(out.source, TrackSource::coasting);
  EXPECT_FALSE(out.ok) << "the track and a sound estimate disagree: neither is ok";
  const Eigen::Isometry3d truth = scene.T_cl_marker(t);
  EXPECT_LE((out.T_cl_marker.translation() - truth.translation()).norm(), 0.004);
  EXPECT_LE(angle_deg(out.T_cl_marker.linear(), truth.linear()), 1.0);
  // A lone estimate beyond its gate is chance, not a shaking camera: the prediction is as wide
  // as a twin's that never saw it.
  PoseTracker twin(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  feed(twin, scene, 0, 20);
  twin.update(at_s(t), scene.q_world_cam(t), true, PoseMeasurement{});
  const double t1 = 21 / 30.0;
  EXPECT_NEAR(tracker.predict(at_s(t1), scene.q_world_cam(t1), true).bound_m,
              twin.predict(at_s(t1), scene.q_world_cam(t1), true).bound_m, 1e-9);
  // The next right one is fused into the track, not the wrong one's.
  const TrackedPose next = feed(tracker, scene, 21, 22);
  EXPECT_EQ(next.source, TrackSource::fused);
  EXPECT_FALSE(next.rejected);
}

TEST(PoseTracker, TheBoundGrowsWhileCoastingAndTheCoastEndsAtMaxCoast) {
  const Scene scene;
  PoseTrackerParams p = params();
  // Loose ok limits, so that max_coast, not the bound, ends the coast.
  PoseTracker tracker(p, Eigen::Isometry3d::Identity(), 0.5, 45.0);
  const double fused_bound_m = feed(tracker, scene, 0, 30).bound_m;
  double last_m = fused_bound_m, last_deg = 0.0;
  bool ended = false;
  for (int f = 30; f < 90; ++f) {
    const double t = f / 30.0;
    const TrackedPose out = tracker.update(at_s(t), scene.q_world_cam(t), true, PoseMeasurement{});
    const double age_s = (f - 29) / 30.0;  // since the last fused estimate
    if (age_s <= p.max_coast_s) {
      EXPECT_GT(out.bound_m, last_m) << f;
      EXPECT_GT(out.bound_deg, last_deg) << f;
      EXPECT_TRUE(out.ok) << f;
      last_m = out.bound_m;
      last_deg = out.bound_deg;
    } else {
      EXPECT_FALSE(out.ok) << f;
      EXPECT_EQ(out.source, TrackSource::none) << f;
      ended = true;
    }
  }
  EXPECT_TRUE(ended);
  EXPECT_GT(last_m, fused_bound_m);
}

TEST(PoseTracker, AgreeingEstimatesTightenTheBoundDownToTheFloor) {
  const Scene scene;
  PoseTrackerParams p = params();
  PoseTracker tracker(p, Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  const double t0 = 0.0, t1 = 1.0 / 30.0;
  EXPECT_EQ(tracker.update(at_s(t0), scene.q_world_cam(t0), true, scene.measure(t0, 0)).source,
            TrackSource::none);  // one estimate is not a track
  const TrackedPose second =
      tracker.update(at_s(t1), scene.q_world_cam(t1), true, scene.measure(t1, 1));
  EXPECT_EQ(second.source, TrackSource::fused);
  EXPECT_LT(second.bound_m, 0.004);  // tighter than either estimate's own
  EXPECT_LT(second.bound_deg, 1.0);
  const TrackedPose later = feed(tracker, scene, 2, 30);
  EXPECT_LT(later.bound_m, second.bound_m);
  EXPECT_LT(later.bound_deg, second.bound_deg);
  EXPECT_GE(later.bound_m, p.floor_mm / 1000.0);
  EXPECT_GE(later.bound_deg, p.floor_deg);
  const Eigen::Isometry3d truth = scene.T_cl_marker(29 / 30.0);
  EXPECT_LE((later.T_cl_marker.translation() - truth.translation()).norm(), later.bound_m);
  EXPECT_LE(angle_deg(later.T_cl_marker.linear(), truth.linear()), later.bound_deg);
}

TEST(PoseTracker, WithSharedErrorsAgreementTightensACoastedBoundToTheEstimates) {
  const Scene scene;
  PoseTrackerParams p = params();
  p.fused_bound_share = 1.0;
  PoseTracker tracker(p, Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  EXPECT_DOUBLE_EQ(feed(tracker, scene, 0, 10).bound_m, 0.004);  // never below the estimate's
  TrackedPose coasted;
  for (int f = 10; f < 16; ++f) {
    const double t = f / 30.0;
    coasted = tracker.update(at_s(t), scene.q_world_cam(t), true, PoseMeasurement{});
  }
  EXPECT_GT(coasted.bound_m, 0.004);
  const TrackedPose back = feed(tracker, scene, 16, 17);
  EXPECT_EQ(back.source, TrackSource::fused);
  EXPECT_LT(back.bound_m, coasted.bound_m);
  EXPECT_DOUBLE_EQ(back.bound_m, 0.004);
}

TEST(PoseTracker, TheTrackMovesToANewPoseOnlyWhenASecondEstimateConfirmsIt) {
  const Scene scene;
  PoseTracker tracker(params(), Eigen::Isometry3d::Identity(), kOkM, kOkDeg);
  feed(tracker, scene, 0, 20);
  // From frame 20 on the estimates say the marker is 5 cm further (the track was the wrong one).
  const Eigen::Vector3d shift(0.0, 0.0, 0.05);
  TrackedPose out;
  for (int f = 20; f < 22; ++f) {
    const double t = f / 30.0;
    PoseMeasurement m = scene.measure(t, f);
    m.T_cl_marker.translation() += shift;
    out = tracker.update(at_s(t), scene.q_world_cam(t), true, m);
    const Eigen::Vector3d moved = scene.T_cl_marker(t).translation() + shift;
    if (f == 20) {
      EXPECT_TRUE(out.rejected);
      EXPECT_GT((out.T_cl_marker.translation() - moved).norm(), 0.04);
    } else {
      EXPECT_FALSE(out.rejected);
      EXPECT_EQ(out.source, TrackSource::fused);
      EXPECT_LE((out.T_cl_marker.translation() - moved).norm(), out.bound_m);
    }
  }
}

}  // namespace
}  // namespace rovctl::control
