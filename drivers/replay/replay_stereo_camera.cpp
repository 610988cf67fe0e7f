// Replay of recorded dives: index reading, pacing on the application's clock, image decoding.
#include "drivers/replay/replay_stereo_camera.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "drivers/replay/recording_format.hpp"
#include "hal/primitives/image_header.hpp"

namespace rovctl::drivers {

namespace fs = std::filesystem;

namespace {

constexpr const char* kVideoExtensions[] = {".avi", ".mp4", ".mkv", ".mov"};

std::string find_video(const fs::path& folder, const char* stem) {
  for (const char* ext : kVideoExtensions) {
    std::error_code ec;
    const fs::path p = folder / (std::string(stem) + ext);
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  return {};
}

}  // namespace

ReplayStereoCamera::ReplayStereoCamera(const ReplayCameraParams& params, hal::Clock& clock)
    : params_(params), clock_(clock) {}

ReplayStereoCamera::~ReplayStereoCamera() { close(); }

bool ReplayStereoCamera::open(std::string& error) {
  close();
  if (params_.mode != "recorded" && params_.mode != "tick") {
    error = "camera.replay.mode: '" + params_.mode + "' is not one of: recorded, tick";
    return false;
  }
  if (!(params_.fps > 0.0)) {
    error = "camera.replay.fps: must be positive";
    return false;
  }
  tick_mode_ = params_.mode == "tick";
  video_period_ = std::chrono::nanoseconds(std::llround(1e9 / params_.fps));
  const bool has_path = !params_.path.empty();
  const bool has_videos = !params_.left_video.empty() || !params_.right_video.empty();
  bool ok = false;
  if (has_path == has_videos) {
    error =
        "camera.replay: give either path (a recorded-dive folder) or left_video and "
        "right_video";
  } else if (has_videos) {
    if (params_.left_video.empty() || params_.right_video.empty()) {
      error = "camera.replay: left_video and right_video go together";
    } else {
      ok = open_videos(params_.left_video, params_.right_video, error);
    }
  } else {
    std::error_code ec;
    if (!fs::exists(params_.path, ec)) {
      error = "camera.replay.path: " + params_.path + ": no such folder";
    } else if (!fs::is_directory(params_.path, ec)) {
      error = "camera.replay.path: " + params_.path +
              ": not a folder (for video files give left_video and right_video)";
    } else if (fs::is_regular_file(fs::path(params_.path) / kFramesCsv, ec)) {
      ok = open_folder(params_.path, error);
    } else {
      const std::string l = find_video(params_.path, "left");
      const std::string r = find_video(params_.path, "right");
      if (!l.empty() && !r.empty()) {
        ok = open_videos(l, r, error);
      } else {
        error = "camera.replay.path: " + params_.path +
                ": neither a recorded dive (no frames.csv) nor a folder with left and right "
                "videos (left.avi, right.avi, ...); see deploy/recording-format.md";
      }
    }
  }
  if (!ok) {
    close();
    return false;
  }
  // A pass lasts from the first frame to one frame period after the last.
  std::chrono::nanoseconds period = video_period_;
  const auto last = video_ ? video_period_ * static_cast<std::chrono::nanoseconds::rep>(count_ - 1)
                           : entries_.back().left_rel;
  if (!video_ && count_ > 1 && last.count() > 0) {
    period = last / static_cast<std::chrono::nanoseconds::rep>(count_ - 1);
  }
  cycle_ = last + period;
  started_ = false;
  next_ = 0;
  skipped_ = 0;
  return true;
}

bool ReplayStereoCamera::open_folder(const std::string& folder, std::string& error) {
  std::vector<RecordedFrame> rows;
  image_width_px_ = image_height_px_ = 0;
  if (!read_frames_csv(folder, rows, error)) {
    error = "camera.replay.path: " + error;
    return false;
  }
  if (rows.empty()) {
    error = "camera.replay.path: " + (fs::path(folder) / kFramesCsv).string() + ": no frames";
    return false;
  }
  entries_.clear();
  entries_.reserve(rows.size());
  std::uintmax_t largest = 0;
  const auto first = rows.front().left_stamp;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const RecordedFrame& r = rows[i];
    const std::string where = "camera.replay.path: " + (fs::path(folder) / kFramesCsv).string() +
                              ":" + std::to_string(i + 2) + ": ";
    if (i > 0 && r.left_stamp < rows[i - 1].left_stamp) {
      error = where + "left_stamp_ns goes backwards";
      return false;
    }
    Entry e;
    e.left_rel = r.left_stamp - first;
    e.right_rel = r.right_stamp - first;
    e.exposure = r.exposure;
    e.left_file = (fs::path(folder) / r.left_file).string();
    e.right_file = (fs::path(folder) / r.right_file).string();
    for (const std::string* f : {&e.left_file, &e.right_file}) {
      std::error_code ec;
      const auto size = fs::file_size(*f, ec);
      if (ec) {
        error = where + *f + ": missing";
        return false;
      }
      largest = std::max(largest, size);
      // Every image's size from its header, here and not in the tick: one image declaring a
      // huge size would otherwise be decoded (gigabytes, seconds) inside the loop.
      // A frame that cannot be read at all is the grab's to report and skip (a dive is not
      // lost for one corrupt file); a readable header must declare the recording's size.
      hal::ImageHeader header;
      std::string unreadable;
      if (!hal::read_image_header(*f, header, unreadable)) continue;
      if (image_width_px_ == 0) {
        image_width_px_ = header.width_px;
        image_height_px_ = header.height_px;
      }
      const std::string problem = hal::image_size_problem(
          *f, header, image_width_px_, image_height_px_, "the recording's first image");
      if (!problem.empty()) {
        error = where + problem;
        return false;
      }
    }
    entries_.push_back(std::move(e));
  }
  file_buffer_.resize(static_cast<std::size_t>(largest));
  count_ = entries_.size();
  video_ = false;
  source_ = folder;
  return true;
}

bool ReplayStereoCamera::open_videos(const std::string& left, const std::string& right,
                                     std::string& error) {
  left_video_ = left;
  right_video_ = right;
  std::size_t counts[2] = {0, 0};
  for (int side = 0; side < 2; ++side) {
    const std::string& file = side == 0 ? left : right;
    const char* key = side == 0 ? "camera.replay.left_video: " : "camera.replay.right_video: ";
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      error = key + file + ": no such file";
      return false;
    }
    cv::VideoCapture cap;
    if (!cap.open(file) || !cap.isOpened()) {
      error = key + file + ": cannot open as a video";
      return false;
    }
    // The container's count can be missing or approximate: count the frames themselves.
    std::size_t n = 0;
    while (cap.grab()) ++n;
    if (n == 0) {
      error = key + file + ": no frames";
      return false;
    }
    counts[side] = n;
  }
  count_ = std::min(counts[0], counts[1]);
  video_ = true;
  source_ = left + " + " + right;
  return reopen_videos(error);
}

bool ReplayStereoCamera::reopen_videos(std::string& error) {
  video_position_ = 0;
  if (!left_capture_.open(left_video_) || !right_capture_.open(right_video_)) {
    error = "camera.replay: cannot reopen " + source_;
    return false;
  }
  return true;
}

void ReplayStereoCamera::close() {
  left_capture_.release();
  right_capture_.release();
  entries_.clear();
  count_ = 0;
  started_ = false;
}

std::string ReplayStereoCamera::name() const {
  return "replay " + source_ + " (" + std::to_string(count_) + " frames, " +
         (tick_mode_ ? "tick" : "recorded") + " pacing" + (params_.loop ? ", loop" : "") + ")";
}

std::chrono::nanoseconds ReplayStereoCamera::due(std::uint64_t g) const {
  const std::uint64_t pass = g / count_;
  const std::size_t i = static_cast<std::size_t>(g % count_);
  const auto rel =
      video_ ? video_period_ * static_cast<std::chrono::nanoseconds::rep>(i) : entries_[i].left_rel;
  return start_ + cycle_ * static_cast<std::chrono::nanoseconds::rep>(pass) + rel;
}

bool ReplayStereoCamera::read_image(const std::string& file, cv::Mat& bgr) {
  // The file goes into a buffer kept between frames; the pixels end in the frame's own image.
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    last_error_ = "replay: " + file + ": cannot read";
    return false;
  }
  struct stat st {};
  std::size_t size = 0;
  if (::fstat(fd, &st) == 0) size = static_cast<std::size_t>(st.st_size);
  if (size > file_buffer_.size()) file_buffer_.resize(size);
  std::size_t got = 0;
  while (got < size) {
    const ssize_t n = ::read(fd, file_buffer_.data() + got, size - got);
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (got != size || size == 0) {
    last_error_ = "replay: " + file + ": short read";
    return false;
  }
  // The header again (the file may have changed since open): never decode a size not checked.
  hal::ImageHeader header;
  std::string problem;
  if (!hal::parse_image_header(file_buffer_.data(), size, header, problem)) {
    problem = file + ": " + problem;
  } else {
    problem = hal::image_size_problem(file, header, image_width_px_, image_height_px_,
                                      "the recording's first image");
  }
  if (!problem.empty()) {
    last_error_ = "replay: " + problem;
    return false;
  }
  // OpenCV 4.6's decode-into-destination overload cannot report a failed decode (it returns the
  // destination untouched), so decode into a fresh image, check it, then copy into the frame.
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(cv::Mat(1, static_cast<int>(size), CV_8UC1, file_buffer_.data()),
                           cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    last_error_ = "replay: " + file + ": cannot decode: " + e.what();
    return false;
  }
  if (decoded.empty()) {
    last_error_ = "replay: " + file + ": cannot decode";
    return false;
  }
  decoded.copyTo(bgr);
  return true;
}

bool ReplayStereoCamera::read(std::size_t index, hal::StereoFrame& frame) {
  if (!video_) {
    return read_image(entries_[index].left_file, frame.left_bgr) &&
           read_image(entries_[index].right_file, frame.right_bgr);
  }
  if (index < video_position_ && !reopen_videos(last_error_)) return false;
  while (video_position_ < index) {
    if (!left_capture_.grab() || !right_capture_.grab()) break;
    ++video_position_;
  }
  const bool ok = video_position_ == index && left_capture_.read(frame.left_bgr) &&
                  right_capture_.read(frame.right_bgr);
  ++video_position_;
  if (!ok) {
    last_error_ = "replay: " + source_ + ": cannot read frame " + std::to_string(index);
    return false;
  }
  return true;
}

hal::GrabStatus ReplayStereoCamera::grab(hal::StereoFrame& frame) {
  if (count_ == 0) {
    last_error_ = "replay: not open";
    return hal::GrabStatus::device_lost;
  }
  std::uint64_t g = next_;
  if (!params_.loop && g >= count_) return hal::GrabStatus::end_of_stream;
  std::chrono::nanoseconds left_stamp{0};
  if (tick_mode_) {
    left_stamp = clock_.now();
  } else {
    if (!started_) {
      started_ = true;
      start_ = clock_.now();
      g = 0;
    }
    if (due(g) > clock_.now()) clock_.sleep_until(due(g));
    const auto now = clock_.now();
    // Late: hand out the newest frame that is due, as a live camera would.
    if (params_.loop && cycle_.count() > 0 && now - due(g) > cycle_) {
      const std::uint64_t passes = static_cast<std::uint64_t>((now - due(g)) / cycle_);
      g += passes * count_;
      skipped_ += passes * count_;
    }
    while ((params_.loop || g + 1 < count_) && due(g + 1) <= now) {
      ++g;
      ++skipped_;
    }
    left_stamp = due(g);
  }
  next_ = g + 1;
  const std::size_t i = static_cast<std::size_t>(g % count_);
  if (!read(i, frame)) return hal::GrabStatus::device_lost;
  const auto offset =
      video_ ? std::chrono::nanoseconds(0) : entries_[i].right_rel - entries_[i].left_rel;
  frame.left_stamp = left_stamp;
  frame.right_stamp = left_stamp + offset;
  frame.exposure = video_ ? std::chrono::nanoseconds(0) : entries_[i].exposure;
  frame.sequence = g + 1;
  return hal::GrabStatus::ok;
}

}  // namespace rovctl::drivers
