// Writes a recorded dive (deploy/recording-format.md) from any StereoCamera's frames. Each pair
// is written to temporary names and renamed, then indexed in frames.csv (flushed per row), so a
// recording cut short by a crash or power loss is still readable up to its last complete pair.
#pragma once

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

#include "hal/interfaces/stereo_camera.hpp"

namespace rovctl::drivers {

class DiveRecorder {
 public:
  DiveRecorder() = default;
  ~DiveRecorder() { close(); }
  DiveRecorder(const DiveRecorder&) = delete;
  DiveRecorder& operator=(const DiveRecorder&) = delete;

  // Creates `folder` (absent or empty: a recording is never overwritten), left/, right/ and
  // frames.csv; copies `calibration_file` in as stereo_calibration.yaml unless it is empty.
  // False with `error` naming the folder or file.
  bool open(const std::string& folder, const std::string& calibration_file, std::string& error);
  // Appends one pair (PNG, lossless; left and right encoded in parallel). Not for the
  // real-time path: encoding allocates.
  bool write(const hal::StereoFrame& frame, std::string& error);
  void close();

  bool is_open() const { return csv_.is_open(); }
  std::size_t frames_written() const { return frames_written_; }
  const std::string& folder() const { return folder_; }

 private:
  bool store(const std::vector<unsigned char>& png, const std::string& relative,
             std::string& error);

  std::string folder_;
  std::ofstream csv_;
  std::size_t frames_written_ = 0;
  std::vector<unsigned char> encoded_[2];  // left, right; reused between frames
};

}  // namespace rovctl::drivers
