// V4L2 backend: bad devices give clear errors naming the device (run everywhere); capture from a
// real camera runs only where /dev/video* exists.
#include "drivers/v4l2/v4l2_stereo_camera.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "drivers/monotonic_clock.hpp"
#include "drivers/v4l2/reopen_backoff.hpp"

namespace rovctl::drivers {
namespace {

using std::chrono::milliseconds;

std::string device_open_error(const std::string& device) {
  V4l2DeviceConfig c;
  c.device = device;
  V4l2Device d(c);
  std::string error;
  EXPECT_FALSE(d.open(error));
  EXPECT_FALSE(d.is_open());
  return error;
}

TEST(V4l2Device, MissingDeviceNamesThePath) {
  const std::string error = device_open_error("/dev/video-rovctl-missing");
  EXPECT_NE(error.find("/dev/video-rovctl-missing"), std::string::npos) << error;
  EXPECT_NE(error.find("no such device"), std::string::npos) << error;
}

TEST(V4l2Device, MissingUdevNameListsWhereItLooked) {
  const std::string error = device_open_error("rovctl-cam-missing");
  EXPECT_NE(error.find("camera rovctl-cam-missing"), std::string::npos) << error;
  EXPECT_NE(error.find("/dev/rovctl/rovctl-cam-missing"), std::string::npos) << error;
  EXPECT_NE(error.find("/dev/v4l/by-id/rovctl-cam-missing"), std::string::npos) << error;
}

TEST(V4l2Device, RejectsWhatIsNotAV4l2Device) {
  const std::string null_error = device_open_error("/dev/null");
  EXPECT_NE(null_error.find("/dev/null"), std::string::npos) << null_error;
  EXPECT_NE(null_error.find("not a V4L2 device"), std::string::npos) << null_error;

  const std::string file =
      (std::filesystem::temp_directory_path() / ("rovctl_not_a_camera_" + std::to_string(getpid())))
          .string();
  { std::ofstream(file) << "x"; }
  const std::string file_error = device_open_error(file);
  std::filesystem::remove(file);
  EXPECT_NE(file_error.find(file), std::string::npos) << file_error;
  EXPECT_NE(file_error.find("not a character device"), std::string::npos) << file_error;
}

TEST(V4l2Device, ResolvesBareNamesAndKeepsPaths) {
  EXPECT_EQ(resolve_video_device("/dev/video3"), "/dev/video3");
  EXPECT_EQ(resolve_video_device("null"), "/dev/null");  // found in /dev
  EXPECT_EQ(resolve_video_device("rovctl-cam-missing"), "rovctl-cam-missing");
}

V4l2CameraParams params(const std::string& left, const std::string& right) {
  V4l2CameraParams p;
  p.left_device = left;
  p.right_device = right;
  return p;
}

TEST(V4l2StereoCamera, OpenNamesTheFailingDevice) {
  MonotonicClock clock;
  V4l2StereoCamera camera(params("/dev/video-rovctl-left", "/dev/video-rovctl-right"), clock);
  std::string error;
  EXPECT_FALSE(camera.open(error));
  EXPECT_NE(error.find("/dev/video-rovctl-left"), std::string::npos) << error;
  hal::StereoFrame frame;
  EXPECT_EQ(camera.grab(frame), hal::GrabStatus::device_lost);
}

TEST(V4l2StereoCamera, RejectsTheSameDeviceTwice) {
  MonotonicClock clock;
  std::string error;
  V4l2StereoCamera by_path(params("/dev/video0", "/dev/./video0"), clock);
  EXPECT_FALSE(by_path.open(error));
  EXPECT_NE(error.find("same device"), std::string::npos) << error;
  // A udev symlink and the node it points to are one camera.
  const auto link =
      std::filesystem::temp_directory_path() / ("rovctl_cam_link_" + std::to_string(getpid()));
  std::filesystem::remove(link);
  std::filesystem::create_symlink("/dev/null", link);
  V4l2StereoCamera by_link(params(link.string(), "/dev/null"), clock);
  EXPECT_FALSE(by_link.open(error));
  std::filesystem::remove(link);
  EXPECT_NE(error.find("same device"), std::string::npos) << error;
}

TEST(V4l2StereoCamera, RejectsAnUnknownFormat) {
  MonotonicClock clock;
  V4l2CameraParams p = params("/dev/video0", "/dev/video1");
  p.format = "h264";
  V4l2StereoCamera camera(p, clock);
  std::string error;
  EXPECT_FALSE(camera.open(error));
  EXPECT_NE(error.find("camera.v4l2.format"), std::string::npos) << error;
}

TEST(ReopenBackoff, DoublesUpToTheLimitAndResetsOnSuccess) {
  ReopenBackoff b(milliseconds(100), milliseconds(350));
  EXPECT_TRUE(b.due(milliseconds(0)));
  b.failed(milliseconds(1000));
  EXPECT_FALSE(b.due(milliseconds(1099)));
  EXPECT_TRUE(b.due(milliseconds(1100)));
  b.failed(milliseconds(1100));
  EXPECT_EQ(b.next_attempt(), milliseconds(1300));
  b.failed(milliseconds(1300));
  EXPECT_EQ(b.current_wait(), milliseconds(350));
  b.failed(milliseconds(1650));
  EXPECT_EQ(b.current_wait(), milliseconds(350));
  b.succeeded();
  EXPECT_TRUE(b.due(milliseconds(0)));
  b.failed(milliseconds(5000));
  EXPECT_EQ(b.next_attempt(), milliseconds(5100));
}

// Real hardware: one device on its own, and the stereo pair when ROVCTL_TEST_LEFT_CAMERA and
// ROVCTL_TEST_RIGHT_CAMERA name two cameras (on the vehicle: /dev/rovctl/cam-left and -right).
TEST(V4l2Device, CapturesFromARealCamera) {
  if (!std::filesystem::exists("/dev/video0")) {
    GTEST_SKIP() << "no /dev/video* device on this machine";
  }
  V4l2DeviceConfig c;
  c.device = "/dev/video0";
  V4l2Device device(c);
  std::string error;
  if (!device.open(error)) GTEST_SKIP() << "cannot use /dev/video0 at 640x480: " << error;
  MonotonicClock clock;
  cv::Mat bgr;
  std::chrono::nanoseconds last{0};
  int frames = 0;
  const auto deadline = clock.now() + std::chrono::seconds(3);
  while (frames < 10 && clock.now() < deadline) {
    V4l2Buffer buffer;
    const DequeueStatus s = device.dequeue(buffer, error);
    ASSERT_NE(s, DequeueStatus::lost) << error;
    if (s == DequeueStatus::empty) {
      ::usleep(2000);
      continue;
    }
    ASSERT_TRUE(convert_to_bgr(device.format(), buffer.data, buffer.bytes_used, device.width(),
                               device.height(), device.stride_bytes(), bgr, error))
        << error;
    if (buffer.monotonic_stamp) {
      EXPECT_GT(buffer.stamp, last);
      EXPECT_LE(buffer.stamp, clock.now());  // same time base as CLOCK_MONOTONIC
      EXPECT_GT(buffer.stamp, clock.now() - std::chrono::seconds(1));
    }
    last = buffer.stamp;
    ASSERT_TRUE(device.requeue(buffer.index, error)) << error;
    ++frames;
  }
  EXPECT_EQ(frames, 10) << device.summary();
  EXPECT_EQ(bgr.cols, 640);
}

TEST(V4l2StereoCamera, GrabsPairsFromRealCameras) {
  const char* left = std::getenv("ROVCTL_TEST_LEFT_CAMERA");
  const char* right = std::getenv("ROVCTL_TEST_RIGHT_CAMERA");
  if (left == nullptr || right == nullptr) {
    GTEST_SKIP() << (std::filesystem::exists("/dev/video0")
                         ? "set ROVCTL_TEST_LEFT_CAMERA and ROVCTL_TEST_RIGHT_CAMERA"
                         : "no /dev/video* device on this machine");
  }
  MonotonicClock clock;
  V4l2CameraParams p = params(left, right);
  p.pairing_tolerance_ms = 20.0;
  V4l2StereoCamera camera(p, clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  hal::StereoFrame frame;
  int ok = 0;
  for (int i = 0; i < 30; ++i) {
    const hal::GrabStatus s = camera.grab(frame);
    ASSERT_NE(s, hal::GrabStatus::device_lost) << camera.last_error();
    if (s != hal::GrabStatus::ok) continue;
    ++ok;
    const auto diff = frame.left_stamp - frame.right_stamp;
    EXPECT_LE(std::chrono::abs(diff), milliseconds(20));
    EXPECT_EQ(frame.left_bgr.type(), CV_8UC3);
  }
  EXPECT_GT(ok, 20) << camera.name() << " unpaired " << camera.stats().pairing.unpaired;
}

}  // namespace
}  // namespace rovctl::drivers
