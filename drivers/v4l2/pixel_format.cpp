// Format choice and YUYV/MJPG -> BGR conversion with OpenCV.
#include "drivers/v4l2/pixel_format.hpp"

#include <linux/videodev2.h>

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace rovctl::drivers {

const char* to_string(PixelFormat f) { return f == PixelFormat::yuyv ? "yuyv" : "mjpg"; }

std::optional<PixelFormat> pixel_format_from_string(std::string_view name) {
  if (name == "yuyv") return PixelFormat::yuyv;
  if (name == "mjpg") return PixelFormat::mjpg;
  return std::nullopt;
}

std::uint32_t fourcc_of(PixelFormat f) {
  return f == PixelFormat::yuyv ? V4L2_PIX_FMT_YUYV : V4L2_PIX_FMT_MJPEG;
}

std::optional<PixelFormat> pixel_format_from_fourcc(std::uint32_t fourcc) {
  if (fourcc == V4L2_PIX_FMT_YUYV) return PixelFormat::yuyv;
  if (fourcc == V4L2_PIX_FMT_MJPEG || fourcc == V4L2_PIX_FMT_JPEG) return PixelFormat::mjpg;
  return std::nullopt;
}

std::string fourcc_to_string(std::uint32_t fourcc) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((fourcc >> (8 * i)) & 0xFFU);
    s += (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

std::optional<PixelFormat> choose_pixel_format(const std::vector<std::uint32_t>& offered_fourccs,
                                               PixelFormat preferred) {
  const auto offers = [&offered_fourccs](PixelFormat f) {
    return std::any_of(offered_fourccs.begin(), offered_fourccs.end(),
                       [f](std::uint32_t c) { return pixel_format_from_fourcc(c) == f; });
  };
  if (offers(preferred)) return preferred;
  const PixelFormat other = preferred == PixelFormat::yuyv ? PixelFormat::mjpg : PixelFormat::yuyv;
  if (offers(other)) return other;
  return std::nullopt;
}

bool convert_to_bgr(PixelFormat format, const std::uint8_t* data, std::size_t bytes_used, int width,
                    int height, std::size_t stride_bytes, cv::Mat& bgr, std::string& error) {
  if (data == nullptr || width <= 0 || height <= 0) {
    error = "empty buffer";
    return false;
  }
  bgr.create(height, width, CV_8UC3);
  if (format == PixelFormat::yuyv) {
    const std::size_t row_bytes = static_cast<std::size_t>(width) * 2;
    const std::size_t stride = stride_bytes == 0 ? row_bytes : stride_bytes;
    const std::size_t needed = stride * static_cast<std::size_t>(height - 1) + row_bytes;
    if (stride < row_bytes || bytes_used < needed) {
      error = "short YUYV buffer: " + std::to_string(bytes_used) + " bytes, expected " +
              std::to_string(needed) + " for " + std::to_string(width) + "x" +
              std::to_string(height);
      return false;
    }
    // The device's buffer is wrapped, not copied.
    const cv::Mat yuyv(height, width, CV_8UC2, const_cast<std::uint8_t*>(data), stride);
    cv::cvtColor(yuyv, bgr, cv::COLOR_YUV2BGR_YUYV);
    return true;
  }
  if (bytes_used == 0) {
    error = "empty MJPG buffer";
    return false;
  }
  // OpenCV 4.6's imdecode(buf, flags, &dst) returns `dst` untouched when decoding fails, so a
  // corrupt frame would pass for a new one. Decode into a fresh image instead (one allocation
  // per frame, on top of libjpeg's own), check it, then copy into the frame's buffer.
  const cv::Mat jpeg(1, static_cast<int>(bytes_used), CV_8UC1, const_cast<std::uint8_t*>(data));
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(jpeg, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    error = std::string("corrupt MJPG frame: ") + e.what();
    return false;
  }
  if (decoded.empty()) {
    error = "corrupt MJPG frame (" + std::to_string(bytes_used) + " bytes)";
    return false;
  }
  if (decoded.cols != width || decoded.rows != height || decoded.type() != CV_8UC3) {
    error = "MJPG frame is " + std::to_string(decoded.cols) + "x" + std::to_string(decoded.rows) +
            ", expected " + std::to_string(width) + "x" + std::to_string(height);
    return false;
  }
  decoded.copyTo(bgr);
  return true;
}

}  // namespace rovctl::drivers
