// The recorded-dive format shared by DiveRecorder and ReplayStereoCamera (documented in
// deploy/recording-format.md): left/NNNNNN.png, right/NNNNNN.png and an index, frames.csv.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace rovctl::drivers {

inline constexpr const char* kFramesCsv = "frames.csv";
inline constexpr const char* kFramesCsvHeader =
    "sequence,left_stamp_ns,right_stamp_ns,left_file,right_file,exposure_ns";
// Recordings without the exposure column (written by other tools) read as exposure unknown.
inline constexpr const char* kFramesCsvHeaderWithoutExposure =
    "sequence,left_stamp_ns,right_stamp_ns,left_file,right_file";
inline constexpr const char* kRecordedCalibration = "stereo_calibration.yaml";

struct RecordedFrame {
  std::uint64_t sequence = 0;  // the camera's sequence number when recorded
  std::chrono::nanoseconds left_stamp{0};
  std::chrono::nanoseconds right_stamp{0};
  std::string left_file;  // relative to the recording folder
  std::string right_file;
  std::chrono::nanoseconds exposure{0};  // how long both images were exposed; 0: not known
};

// One frames.csv line (with its newline).
std::string frames_csv_row(const RecordedFrame& frame);

// Reads `folder`/frames.csv, with or without its exposure column. An unterminated last line (a
// recorder killed mid-row) is ignored. False with `error` naming the file and line on a bad
// header, a malformed row or a file name that leaves the folder.
bool read_frames_csv(const std::string& folder, std::vector<RecordedFrame>& frames,
                     std::string& error);

}  // namespace rovctl::drivers
