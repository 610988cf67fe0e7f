// StereoCamera that plays a recorded dive (a recording folder, or two video files) either at
// the recorded pace on the application's clock, or one pair per grab.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "drivers/camera_params.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/interfaces/stereo_camera.hpp"

namespace rovctl::drivers {

class ReplayStereoCamera final : public hal::StereoCamera {
 public:
  // `clock` is the application's (monotonic on the bench, virtual in simulations): recorded
  // pacing sleeps on it, and every stamp handed out is on it.
  ReplayStereoCamera(const ReplayCameraParams& params, hal::Clock& clock);
  ~ReplayStereoCamera() override;

  // Source: `path` holding frames.csv (a recorded dive) or left.<ext> and right.<ext> videos,
  // or `left_video` + `right_video`. Reads the index and checks that every image exists.
  bool open(std::string& error) override;
  // recorded: sleeps on the clock until the next frame is due; a late grab gets the newest due
  // frame (the ones passed over are counted in skipped()). Stamps: the recorded ones shifted to
  // the clock time of the first grab. tick: the next pair at once, stamped clock.now() (the
  // right stamp keeps its recorded offset from the left). At the end: loop, or end_of_stream.
  // A frame that cannot be read gives device_lost (naming the file); the next grab goes on.
  // Decoding allocates (replay is a bench tool); the pixels are copied into the frame's buffers.
  hal::GrabStatus grab(hal::StereoFrame& frame) override;
  void close() override;
  std::string name() const override;

  std::size_t frame_count() const { return count_; }
  std::uint64_t skipped() const { return skipped_; }
  const std::string& last_error() const { return last_error_; }

 private:
  struct Entry {
    std::chrono::nanoseconds left_rel{0};  // from the first frame's left stamp
    std::chrono::nanoseconds right_rel{0};
    std::string left_file;  // image-sequence source only
    std::string right_file;
    std::chrono::nanoseconds exposure{0};  // as recorded; 0: not known (and for videos)
  };
  bool open_folder(const std::string& folder, std::string& error);
  bool open_videos(const std::string& left, const std::string& right, std::string& error);
  bool reopen_videos(std::string& error);
  bool read(std::size_t index, hal::StereoFrame& frame);
  bool read_image(const std::string& file, cv::Mat& bgr);
  std::chrono::nanoseconds due(std::uint64_t global_index) const;

  ReplayCameraParams params_;
  hal::Clock& clock_;
  bool tick_mode_ = false;
  bool video_ = false;
  std::string source_;  // for name() and errors
  // The size of a recording's images (from the first image's header); every other must match.
  int image_width_px_ = 0;
  int image_height_px_ = 0;
  std::string left_video_;
  std::string right_video_;
  std::vector<Entry> entries_;  // image sequence: one per frame; video: empty
  std::size_t count_ = 0;
  std::chrono::nanoseconds video_period_{0};
  std::chrono::nanoseconds cycle_{0};  // one pass, including the gap back to the first frame
  cv::VideoCapture left_capture_;
  cv::VideoCapture right_capture_;
  std::size_t video_position_ = 0;  // index the captures return next
  std::vector<unsigned char> file_buffer_;
  bool started_ = false;
  std::chrono::nanoseconds start_{0};  // clock time of frame 0, first pass
  std::uint64_t next_ = 0;             // global index (passes * count + index) of the next frame
  std::uint64_t skipped_ = 0;
  std::string last_error_;
};

}  // namespace rovctl::drivers
