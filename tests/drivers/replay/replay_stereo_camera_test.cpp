// Recorded dives for real: written by DiveRecorder, played back by ReplayStereoCamera in tick and
// recorded pacing on a fake clock, looping, video files, and every kind of bad input.
#include "drivers/replay/replay_stereo_camera.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <vector>

#include "drivers/camera_factory.hpp"
#include "drivers/replay/dive_recorder.hpp"
#include "drivers/replay/recording_format.hpp"

namespace rovctl::drivers {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

class FakeClock final : public hal::Clock {
 public:
  nanoseconds now() const override { return now_; }
  void sleep_until(nanoseconds deadline) override {
    sleeps.push_back(deadline);
    if (deadline > now_) now_ = deadline;
  }
  void advance(nanoseconds dt) { now_ += dt; }
  std::vector<nanoseconds> sleeps;

 private:
  nanoseconds now_{std::chrono::seconds(500)};
};

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() /
            ("rovctl_replay_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  static inline int counter_ = 0;
};

constexpr int kFrames = 5;
const nanoseconds kFirstStamp = std::chrono::seconds(1234);
const nanoseconds kPeriod = milliseconds(33);
const nanoseconds kRightOffset = milliseconds(2);
const nanoseconds kManualExposure = std::chrono::microseconds(4000);

hal::StereoFrame synthetic_frame(int i) {
  hal::StereoFrame f;
  f.left_bgr.create(24, 32, CV_8UC3);
  f.right_bgr.create(24, 32, CV_8UC3);
  cv::RNG rng(static_cast<std::uint64_t>(100 + i));
  rng.fill(f.left_bgr, cv::RNG::UNIFORM, 0, 256);
  rng.fill(f.right_bgr, cv::RNG::UNIFORM, 0, 256);
  f.left_stamp = kFirstStamp + kPeriod * i;
  f.right_stamp = f.left_stamp + kRightOffset;
  f.sequence = static_cast<std::uint64_t>(40 + i);
  // A manual exposure read back from the camera, then the camera's auto exposure (not known).
  f.exposure = i < 3 ? kManualExposure : nanoseconds(0);
  return f;
}

std::string record(const TempDir& dir, const std::string& calibration = "") {
  DiveRecorder recorder;
  std::string error;
  const std::string folder = dir / "dive";
  EXPECT_TRUE(recorder.open(folder, calibration, error)) << error;
  for (int i = 0; i < kFrames; ++i) EXPECT_TRUE(recorder.write(synthetic_frame(i), error)) << error;
  EXPECT_EQ(recorder.frames_written(), static_cast<std::size_t>(kFrames));
  return folder;
}

ReplayCameraParams replay_params(const std::string& path, const std::string& mode, bool loop) {
  ReplayCameraParams p;
  p.path = path;
  p.mode = mode;
  p.loop = loop;
  return p;
}

bool same_image(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

std::string read_text(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(DiveRecorder, WritesTheRecordingFormat) {
  TempDir dir;
  { std::ofstream(dir / "calib.yaml") << "%YAML:1.0\nK1: 1\n"; }
  const std::string folder = record(dir, dir / "calib.yaml");
  EXPECT_TRUE(fs::is_regular_file(folder + "/left/000000.png"));
  EXPECT_TRUE(fs::is_regular_file(folder + "/right/000004.png"));
  EXPECT_EQ(read_text(folder + "/stereo_calibration.yaml"), "%YAML:1.0\nK1: 1\n");
  const std::string csv = read_text(folder + "/frames.csv");
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "sequence,left_stamp_ns,right_stamp_ns,left_file,right_file,exposure_ns");
  std::getline(lines, line);
  EXPECT_EQ(line, "40,1234000000000,1234002000000,left/000000.png,right/000000.png,4000000");
  int rows = 1;
  while (std::getline(lines, line)) ++rows;
  EXPECT_EQ(rows, kFrames);
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(DiveRecorder, NeverOverwritesARecording) {
  TempDir dir;
  const std::string folder = record(dir);
  DiveRecorder again;
  std::string error;
  EXPECT_FALSE(again.open(folder, "", error));
  EXPECT_NE(error.find(folder), std::string::npos) << error;
  EXPECT_NE(error.find("not empty"), std::string::npos) << error;
  EXPECT_FALSE(again.open(dir / "other", dir / "missing_calibration.yaml", error));
  EXPECT_NE(error.find("missing_calibration.yaml"), std::string::npos) << error;
}

TEST(ReplayStereoCamera, ARecordingWithoutTheExposureColumnPlaysWithExposureUnknown) {
  TempDir dir;
  const std::string folder = record(dir);
  // As other tools write it: the five columns before exposure_ns.
  std::string csv = std::string(kFramesCsvHeaderWithoutExposure) + "\n";
  for (int i = 0; i < kFrames; ++i) {
    char row[128];
    std::snprintf(row, sizeof row, "%d,%d,%d,left/%06d.png,right/%06d.png\n", i, 33 * i, 33 * i, i,
                  i);
    csv += row;
  }
  { std::ofstream(folder + "/frames.csv", std::ios::trunc) << csv; }
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "tick", false), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  hal::StereoFrame frame;
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok) << camera.last_error();
  EXPECT_FALSE(frame.exposure_known());
  EXPECT_TRUE(same_image(frame.left_bgr, synthetic_frame(0).left_bgr));
}

TEST(ReplayStereoCamera, TickModePlaysEveryPairOnceThenEndOfStream) {
  TempDir dir;
  const std::string folder = record(dir);
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "tick", false), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  EXPECT_EQ(camera.frame_count(), static_cast<std::size_t>(kFrames));
  hal::StereoFrame frame;
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok) << camera.last_error();
    const hal::StereoFrame want = synthetic_frame(i);
    EXPECT_TRUE(same_image(frame.left_bgr, want.left_bgr)) << "frame " << i;  // PNG is lossless
    EXPECT_TRUE(same_image(frame.right_bgr, want.right_bgr)) << "frame " << i;
    EXPECT_EQ(frame.sequence, static_cast<std::uint64_t>(i + 1));
    EXPECT_EQ(frame.left_stamp, clock.now());
    EXPECT_EQ(frame.right_stamp - frame.left_stamp, kRightOffset);
    EXPECT_EQ(frame.exposure, want.exposure) << "frame " << i;  // what the camera said, or unknown
    clock.advance(milliseconds(1));
  }
  EXPECT_TRUE(clock.sleeps.empty());
  EXPECT_EQ(camera.grab(frame), hal::GrabStatus::end_of_stream);
  EXPECT_EQ(camera.grab(frame), hal::GrabStatus::end_of_stream);
}

TEST(ReplayStereoCamera, GrabReusesTheFrameBuffers) {
  TempDir dir;
  const std::string folder = record(dir);
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "tick", true), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  hal::StereoFrame frame;
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  const unsigned char* left = frame.left_bgr.data;
  const unsigned char* right = frame.right_bgr.data;
  for (int i = 0; i < 7; ++i) ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(frame.left_bgr.data, left);
  EXPECT_EQ(frame.right_bgr.data, right);
}

TEST(ReplayStereoCamera, TickModeLoops) {
  TempDir dir;
  const std::string folder = record(dir);
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "tick", true), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  hal::StereoFrame frame;
  for (int g = 0; g < 2 * kFrames + 2; ++g) {
    ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok) << g;
    EXPECT_TRUE(same_image(frame.left_bgr, synthetic_frame(g % kFrames).left_bgr)) << g;
    EXPECT_EQ(frame.sequence, static_cast<std::uint64_t>(g + 1));
  }
}

TEST(ReplayStereoCamera, RecordedModeIsPacedByTheRecordedStamps) {
  TempDir dir;
  const std::string folder = record(dir);
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "recorded", false), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  clock.advance(milliseconds(250));  // opening long before the first grab does not matter
  const nanoseconds start = clock.now();
  hal::StereoFrame frame;
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(frame.left_stamp, start);
  EXPECT_EQ(frame.right_stamp, start + kRightOffset);
  EXPECT_TRUE(same_image(frame.left_bgr, synthetic_frame(0).left_bgr));
  // A prompt consumer waits on the clock for each recorded frame.
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  ASSERT_EQ(clock.sleeps.size(), 1U);
  EXPECT_EQ(clock.sleeps.back(), start + kPeriod);
  EXPECT_EQ(frame.left_stamp, start + kPeriod);
  EXPECT_EQ(frame.sequence, 2U);
  EXPECT_TRUE(same_image(frame.left_bgr, synthetic_frame(1).left_bgr));
  // A late consumer gets the newest due frame; the ones in between are skipped.
  clock.advance(kPeriod * 2 + milliseconds(5));  // now frame 3 is due, frame 4 is not
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(clock.sleeps.size(), 1U);
  EXPECT_EQ(frame.sequence, 4U);
  EXPECT_EQ(frame.left_stamp, start + kPeriod * 3);
  EXPECT_TRUE(same_image(frame.right_bgr, synthetic_frame(3).right_bgr));
  EXPECT_EQ(camera.skipped(), 1U);
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(clock.sleeps.back(), start + kPeriod * 4);
  EXPECT_EQ(frame.sequence, 5U);
  EXPECT_EQ(camera.grab(frame), hal::GrabStatus::end_of_stream);
}

TEST(ReplayStereoCamera, RecordedModeLoopsOnePeriodAfterTheLastFrame) {
  TempDir dir;
  const std::string folder = record(dir);
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "recorded", true), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  const nanoseconds start = clock.now();
  hal::StereoFrame frame;
  for (int i = 0; i < kFrames; ++i) ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(frame.left_stamp, start + kPeriod * kFrames);
  EXPECT_EQ(frame.sequence, static_cast<std::uint64_t>(kFrames + 1));
  EXPECT_TRUE(same_image(frame.left_bgr, synthetic_frame(0).left_bgr));
  // Stalled for several passes: still the frame due now, never a burst of old ones.
  clock.advance(kPeriod * kFrames * 3 + kPeriod * 2 + milliseconds(1));
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_TRUE(same_image(frame.left_bgr, synthetic_frame(2).left_bgr));
  EXPECT_EQ(frame.left_stamp, start + kPeriod * (kFrames * 4 + 2));
}

TEST(ReplayStereoCamera, IgnoresARowCutOffByACrash) {
  TempDir dir;
  const std::string folder = record(dir);
  {
    std::ofstream csv(folder + "/frames.csv", std::ios::app);
    csv << "45,1234165000000,12341";  // no newline: the recorder died here
  }
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "tick", false), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  EXPECT_EQ(camera.frame_count(), static_cast<std::size_t>(kFrames));
}

TEST(ReplayStereoCamera, AnUnreadableFrameIsReportedAndSkipped) {
  TempDir dir;
  const std::string folder = record(dir);
  { std::ofstream(folder + "/left/000001.png", std::ios::trunc) << "not a png"; }
  FakeClock clock;
  ReplayStereoCamera camera(replay_params(folder, "tick", false), clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  hal::StereoFrame frame;
  EXPECT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(camera.grab(frame), hal::GrabStatus::device_lost);
  EXPECT_NE(camera.last_error().find("left/000001.png"), std::string::npos) << camera.last_error();
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_EQ(frame.sequence, 3U);
}

std::string open_error(const ReplayCameraParams& p) {
  FakeClock clock;
  ReplayStereoCamera camera(p, clock);
  std::string error;
  EXPECT_FALSE(camera.open(error));
  return error;
}

// A PNG whose header declares `w` x `h` and holds no pixels: decoding it would cost gigabytes.
void write_png_header(const std::string& file, unsigned w, unsigned h) {
  std::string png = "\x89PNG\r\n\x1a\n" + std::string("\0\0\0\x0d", 4) + "IHDR";
  for (unsigned v : {w, h}) {
    for (int s = 24; s >= 0; s -= 8) png += static_cast<char>((v >> s) & 0xFF);
  }
  png += std::string("\x08\x02\0\0\0\0\0\0\0", 9);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << png;
}

TEST(ReplayStereoCamera, ImageSizesAreCheckedFromTheHeadersAtOpen) {
  TempDir dir;
  const std::string folder = record(dir);
  write_png_header(folder + "/left/000002.png", 30000, 30000);
  const std::string huge = open_error(replay_params(folder, "tick", false));
  EXPECT_NE(huge.find("frames.csv:4: "), std::string::npos) << huge;
  EXPECT_NE(huge.find("left/000002.png: PNG header declares 30000x30000 pixels, beyond the limit"),
            std::string::npos)
      << huge;
  write_png_header(folder + "/left/000002.png", 64, 48);
  const std::string other = open_error(replay_params(folder, "tick", false));
  EXPECT_NE(other.find("left/000002.png: image is 64x48 but the recording's first image says"),
            std::string::npos)
      << other;
}

TEST(ReplayStereoCamera, BadInputIsAClearError) {
  TempDir dir;
  EXPECT_NE(
      open_error(replay_params(dir / "nowhere", "tick", false)).find("nowhere: no such folder"),
      std::string::npos);
  { std::ofstream(dir / "file.txt") << "x"; }
  EXPECT_NE(open_error(replay_params(dir / "file.txt", "tick", false)).find("not a folder"),
            std::string::npos);
  fs::create_directories(dir / "empty");
  EXPECT_NE(open_error(replay_params(dir / "empty", "tick", false)).find("no frames.csv"),
            std::string::npos);
  EXPECT_NE(open_error(ReplayCameraParams{}).find("give either path"), std::string::npos);

  const std::string folder = record(dir);
  ReplayCameraParams both = replay_params(folder, "tick", false);
  both.left_video = dir / "file.txt";
  both.right_video = dir / "file.txt";
  EXPECT_NE(open_error(both).find("give either path"), std::string::npos);

  fs::remove(folder + "/right/000003.png");
  const std::string missing = open_error(replay_params(folder, "tick", false));
  EXPECT_NE(missing.find("frames.csv:5"), std::string::npos) << missing;
  EXPECT_NE(missing.find("right/000003.png: missing"), std::string::npos) << missing;

  { std::ofstream(folder + "/frames.csv", std::ios::trunc) << "seq,left,right\n"; }
  const std::string header = open_error(replay_params(folder, "tick", false));
  EXPECT_NE(header.find("frames.csv:1: expected the header"), std::string::npos) << header;

  {
    std::ofstream(folder + "/frames.csv", std::ios::trunc)
        << kFramesCsvHeader << "\n0,12,13,../../etc/passwd,right/000000.png\n";
  }
  EXPECT_NE(open_error(replay_params(folder, "tick", false)).find("frames.csv:2"),
            std::string::npos);
  {
    std::ofstream(folder + "/frames.csv", std::ios::trunc)
        << kFramesCsvHeader << "\n0,12,13,left/000000.png,right/000000.png,4ms\n";
  }
  const std::string exposure = open_error(replay_params(folder, "tick", false));
  EXPECT_NE(exposure.find("frames.csv:2: exposure_ns: not a non-negative integer: '4ms'"),
            std::string::npos)
      << exposure;
  {
    std::ofstream(folder + "/frames.csv", std::ios::trunc)
        << kFramesCsvHeader << "\n0,12,13,left/000000.png,right/000000.png\n";
  }
  const std::string short_row = open_error(replay_params(folder, "tick", false));
  EXPECT_NE(short_row.find("frames.csv:2: expected 6 fields, got 5"), std::string::npos)
      << short_row;
  { std::ofstream(folder + "/frames.csv", std::ios::trunc) << kFramesCsvHeader << "\n"; }
  EXPECT_NE(open_error(replay_params(folder, "tick", false)).find("no frames"), std::string::npos);

  ReplayCameraParams videos;
  videos.left_video = dir / "missing_left.avi";
  videos.right_video = dir / "missing_right.avi";
  const std::string no_video = open_error(videos);
  EXPECT_NE(no_video.find("left_video"), std::string::npos) << no_video;
  EXPECT_NE(no_video.find("missing_left.avi: no such file"), std::string::npos) << no_video;
  videos.left_video = dir / "file.txt";
  videos.right_video = dir / "file.txt";
  EXPECT_NE(open_error(videos).find("cannot open as a video"), std::string::npos);
  videos.right_video.clear();
  EXPECT_NE(open_error(videos).find("go together"), std::string::npos);
}

// Grey level of video frame i: far enough apart to survive MJPEG.
int video_grey(int i) { return 20 + 40 * i; }

void write_videos(const std::string& left, const std::string& right, int frames) {
  cv::VideoWriter l(left, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 20.0, cv::Size(32, 24));
  cv::VideoWriter r(right, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 20.0, cv::Size(32, 24));
  ASSERT_TRUE(l.isOpened() && r.isOpened());
  for (int i = 0; i < frames; ++i) {
    l.write(cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(video_grey(i))));
    r.write(cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(255 - video_grey(i))));
  }
}

TEST(ReplayStereoCamera, PlaysTwoVideoFilesByFrameIndex) {
  TempDir dir;
  fs::create_directories(dir / "videos");
  write_videos(dir / "videos/left.avi", dir / "videos/right.avi", 6);
  FakeClock clock;
  ReplayCameraParams p = replay_params(dir / "videos", "recorded", true);  // found by name
  p.fps = 20.0;
  ReplayStereoCamera camera(p, clock);
  std::string error;
  ASSERT_TRUE(camera.open(error)) << error;
  EXPECT_EQ(camera.frame_count(), 6U);
  const nanoseconds start = clock.now();
  hal::StereoFrame frame;
  for (int g = 0; g < 8; ++g) {
    ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok) << camera.last_error();
    EXPECT_EQ(frame.left_stamp, start + milliseconds(50) * g);
    EXPECT_NEAR(cv::mean(frame.left_bgr)[0], video_grey(g % 6), 4.0) << g;
    EXPECT_NEAR(cv::mean(frame.right_bgr)[1], 255 - video_grey(g % 6), 4.0) << g;
  }
  // Skipping ahead in a video.
  clock.advance(milliseconds(101));  // frames 8 and 9 are due: 9 is frame 3 of the second pass
  ASSERT_EQ(camera.grab(frame), hal::GrabStatus::ok);
  EXPECT_NEAR(cv::mean(frame.left_bgr)[0], video_grey(3), 4.0);
  EXPECT_EQ(frame.sequence, 10U);
  EXPECT_EQ(camera.skipped(), 1U);

  ReplayCameraParams explicit_files;
  explicit_files.left_video = dir / "videos/left.avi";
  explicit_files.right_video = dir / "videos/right.avi";
  explicit_files.mode = "tick";
  ReplayStereoCamera by_file(explicit_files, clock);
  ASSERT_TRUE(by_file.open(error)) << error;
  for (int i = 0; i < 6; ++i) ASSERT_EQ(by_file.grab(frame), hal::GrabStatus::ok);
  EXPECT_NEAR(cv::mean(frame.left_bgr)[2], video_grey(5), 4.0);
  EXPECT_EQ(by_file.grab(frame), hal::GrabStatus::end_of_stream);
}

TEST(CameraFactory, BuildsTheConfiguredBackend) {
  FakeClock clock;
  CameraParams p;
  EXPECT_EQ(make_stereo_camera(p, clock), nullptr);  // mock: built by the application
  p.backend = "v4l2";
  p.v4l2.left_device = "/dev/video7";
  const auto v4l2 = make_stereo_camera(p, clock);
  ASSERT_NE(v4l2, nullptr);
  EXPECT_NE(v4l2->name().find("/dev/video7"), std::string::npos) << v4l2->name();
  p.backend = "replay";
  const auto replay = make_stereo_camera(p, clock);
  ASSERT_NE(replay, nullptr);
  EXPECT_NE(replay->name().find("replay"), std::string::npos);
  p.backend = "gopro";
  EXPECT_THROW(make_stereo_camera(p, clock), std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::drivers
