// Camera controls through a fake V4L2 device: exposure, gain and white balance are set, read back
// and reported; a missing control is a WARN; a value the camera cannot honour is refused.
#include "drivers/v4l2/camera_controls.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "drivers/v4l2/fake_v4l2_device.hpp"

namespace rovctl::drivers {
namespace {

using std::chrono::microseconds;

CameraControlSettings manual(int exposure_us) {
  CameraControlSettings s;
  s.auto_exposure = false;
  s.exposure_time_us = exposure_us;
  return s;
}

// The one line whose text starts with `what`.
const ControlReportLine& line(const CameraControlReport& r, const std::string& what) {
  const auto it = std::find_if(r.lines.begin(), r.lines.end(), [&](const ControlReportLine& l) {
    return l.text.rfind(what, 0) == 0;
  });
  EXPECT_NE(it, r.lines.end()) << what;
  static const ControlReportLine none{};
  return it == r.lines.end() ? none : *it;
}

bool was_set(const FakeV4l2Device& d, std::uint32_t id) {
  return std::any_of(d.sets.begin(), d.sets.end(), [id](const auto& s) { return s.first == id; });
}

TEST(CameraControls, ManualExposureIsSetAfterManualModeAndReadBack) {
  auto camera = FakeV4l2Device::uvc_camera();
  CameraControlReport report;
  ASSERT_TRUE(apply_camera_controls(camera, 3, manual(4000), report));
  ASSERT_GE(camera.sets.size(), 2u);
  // Manual mode first: a UVC camera ignores the exposure time while its auto exposure owns it.
  EXPECT_EQ(camera.sets[0], std::make_pair(std::uint32_t{V4L2_CID_EXPOSURE_AUTO},
                                           static_cast<int>(V4L2_EXPOSURE_MANUAL)));
  EXPECT_EQ(camera.sets[1], std::make_pair(std::uint32_t{V4L2_CID_EXPOSURE_ABSOLUTE}, 40));
  const ControlReportLine& l = line(report, "exposure");
  EXPECT_EQ(l.level, ControlLevel::pass);
  EXPECT_EQ(l.text, "exposure: 4.0 ms set, 4.0 ms read back");
  EXPECT_EQ(report.exposure, microseconds(4000));
  EXPECT_FALSE(report.refused());
}

TEST(CameraControls, AutoExposureFallsBackToAperturePriorityAndLeavesTheTimeUnknown) {
  auto camera = FakeV4l2Device::uvc_camera();
  camera.controls[V4L2_CID_EXPOSURE_AUTO].value = V4L2_EXPOSURE_MANUAL;
  CameraControlReport report;
  ASSERT_TRUE(apply_camera_controls(camera, 3, CameraControlSettings{}, report));
  EXPECT_EQ(camera.value(V4L2_CID_EXPOSURE_AUTO), V4L2_EXPOSURE_APERTURE_PRIORITY);
  EXPECT_FALSE(was_set(camera, V4L2_CID_EXPOSURE_ABSOLUTE));
  EXPECT_EQ(line(report, "exposure").level, ControlLevel::pass);
  EXPECT_EQ(report.exposure.count(), 0);
}

TEST(CameraControls, AReadBackThatDiffersIsAWarningAndTheFrameTimeIsTheCamerasOwn) {
  auto camera = FakeV4l2Device::uvc_camera();
  // This camera exposes in steps of 0.5 ms whatever it is asked.
  camera.controls[V4L2_CID_EXPOSURE_ABSOLUTE].read_back = [](int v) { return v / 5 * 5; };
  CameraControlReport report;
  ASSERT_TRUE(apply_camera_controls(camera, 3, manual(4240), report));
  const ControlReportLine& l = line(report, "exposure");
  EXPECT_EQ(l.level, ControlLevel::warn);
  EXPECT_NE(l.text.find("4.2 ms set, 4.0 ms read back"), std::string::npos) << l.text;
  EXPECT_NE(l.text.find("4240 us rounded to the camera's 100 us unit"), std::string::npos)
      << l.text;
  EXPECT_EQ(report.exposure, microseconds(4000));
}

TEST(CameraControls, AnExposureBeyondTheCamerasRangeIsRefusedAndNotSet) {
  auto camera = FakeV4l2Device::uvc_camera();
  CameraControlReport report;
  EXPECT_FALSE(apply_camera_controls(camera, 3, manual(30000), report));
  EXPECT_TRUE(report.refused());
  const ControlReportLine& l = line(report, "exposure");
  EXPECT_EQ(l.level, ControlLevel::fail);
  EXPECT_EQ(l.text,
            "exposure: camera.v4l2.exposure_time_us 30.0 ms is outside what the camera offers "
            "(0.3 ms to 20.0 ms): refused");
  EXPECT_FALSE(was_set(camera, V4L2_CID_EXPOSURE_ABSOLUTE));
  EXPECT_EQ(report.exposure.count(), 0);
}

TEST(CameraControls, ACameraThatRefusesManualExposureFails) {
  auto camera = FakeV4l2Device::uvc_camera();
  camera.controls[V4L2_CID_EXPOSURE_AUTO].refused.insert(V4L2_EXPOSURE_MANUAL);
  CameraControlReport report;
  EXPECT_FALSE(apply_camera_controls(camera, 3, manual(4000), report));
  EXPECT_NE(line(report, "exposure").text.find("auto_exposure false cannot be honoured"),
            std::string::npos);
}

TEST(CameraControls, MissingControlsAreWarningsNotFailures) {
  auto camera = FakeV4l2Device::uvc_camera();
  camera.controls.erase(V4L2_CID_EXPOSURE_ABSOLUTE);
  camera.controls.erase(V4L2_CID_GAIN);
  CameraControlSettings s = manual(4000);
  s.gain = 32;
  CameraControlReport report;
  EXPECT_TRUE(apply_camera_controls(camera, 3, s, report));
  EXPECT_EQ(line(report, "exposure").level, ControlLevel::warn);
  EXPECT_NE(line(report, "exposure").text.find("camera.v4l2.exposure_time_us 4.0 ms is not set"),
            std::string::npos);
  EXPECT_EQ(line(report, "gain").level, ControlLevel::warn);
  EXPECT_EQ(report.exposure.count(), 0);  // not known: the frames do not claim it
}

TEST(CameraControls, NoAutoExposureControlWarnsThatTheSmearBudgetIsNotEnforced) {
  auto camera = FakeV4l2Device::uvc_camera();
  camera.controls.erase(V4L2_CID_EXPOSURE_AUTO);
  CameraControlReport report;
  EXPECT_TRUE(apply_camera_controls(camera, 3, manual(4000), report));
  const ControlReportLine& l = line(report, "exposure");
  EXPECT_EQ(l.level, ControlLevel::warn);
  EXPECT_NE(l.text.find("smear budget is not enforced"), std::string::npos) << l.text;
}

TEST(CameraControls, GainIsSetReadBackOrRefusedAndLeftAloneAtMinusOne) {
  auto camera = FakeV4l2Device::uvc_camera();
  CameraControlSettings s;
  s.gain = 100;
  CameraControlReport report;
  ASSERT_TRUE(apply_camera_controls(camera, 3, s, report));
  EXPECT_EQ(camera.value(V4L2_CID_GAIN), 100);
  EXPECT_EQ(line(report, "gain").text, "gain: 100 set, 100 read back");

  s.gain = 300;
  EXPECT_FALSE(apply_camera_controls(camera, 3, s, report));
  EXPECT_EQ(line(report, "gain").text,
            "gain: camera.v4l2.gain 300 is outside what the camera offers (0 to 255): refused");
  EXPECT_EQ(camera.value(V4L2_CID_GAIN), 100);

  auto untouched = FakeV4l2Device::uvc_camera();
  ASSERT_TRUE(apply_camera_controls(untouched, 3, CameraControlSettings{}, report));
  EXPECT_FALSE(was_set(untouched, V4L2_CID_GAIN));
}

TEST(CameraControls, WhiteBalanceLocksAtATemperatureOrAtTheCurrentOne) {
  auto camera = FakeV4l2Device::uvc_camera();
  CameraControlSettings s;
  s.white_balance = "lock";
  s.white_balance_temperature_k = 5000;
  CameraControlReport report;
  ASSERT_TRUE(apply_camera_controls(camera, 3, s, report));
  EXPECT_EQ(camera.value(V4L2_CID_AUTO_WHITE_BALANCE), 0);
  EXPECT_EQ(camera.value(V4L2_CID_WHITE_BALANCE_TEMPERATURE), 5000);
  EXPECT_EQ(line(report, "white balance").text, "white balance: 5000 K set, 5000 K read back");

  s.white_balance_temperature_k = 0;
  auto current = FakeV4l2Device::uvc_camera();
  ASSERT_TRUE(apply_camera_controls(current, 3, s, report));
  EXPECT_EQ(line(report, "white balance").text,
            "white balance: locked at the camera's current 4600 K");
  EXPECT_FALSE(was_set(current, V4L2_CID_WHITE_BALANCE_TEMPERATURE));

  s.white_balance_temperature_k = 9000;
  EXPECT_FALSE(apply_camera_controls(current, 3, s, report));
  EXPECT_EQ(line(report, "white balance").level, ControlLevel::fail);

  current.controls.erase(V4L2_CID_AUTO_WHITE_BALANCE);
  s.white_balance_temperature_k = 0;
  EXPECT_TRUE(apply_camera_controls(current, 3, s, report));
  EXPECT_EQ(line(report, "white balance").level, ControlLevel::warn);
}

}  // namespace
}  // namespace rovctl::drivers
