// Camera pixel formats rovctl understands (YUYV, MJPG): which one to ask a device for, given what
// it offers, and the conversion of one captured buffer into the frame's BGR image.
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rovctl::drivers {

enum class PixelFormat { yuyv, mjpg };

const char* to_string(PixelFormat f);  // "yuyv" / "mjpg", as in the config
// Parses the config spelling; nullopt for anything else.
std::optional<PixelFormat> pixel_format_from_string(std::string_view name);

// The V4L2 fourcc of a format (V4L2_PIX_FMT_YUYV, V4L2_PIX_FMT_MJPEG), and back. JPEG is
// accepted as MJPG: some UVC drivers announce their motion-JPEG stream under that code.
std::uint32_t fourcc_of(PixelFormat f);
std::optional<PixelFormat> pixel_format_from_fourcc(std::uint32_t fourcc);
// "YUYV", "MJPG", ... for messages.
std::string fourcc_to_string(std::uint32_t fourcc);

// The format to negotiate: `preferred` when offered, otherwise the other supported one;
// nullopt when the device offers neither.
std::optional<PixelFormat> choose_pixel_format(const std::vector<std::uint32_t>& offered_fourccs,
                                               PixelFormat preferred);

// Converts one captured image into `bgr` (CV_8UC3, width x height), reusing its buffer when it
// already has that size. YUYV: `stride_bytes` is the line pitch (V4L2 bytesperline, >= 2*width).
// MJPG allocates on every frame: libjpeg's decoder state, and a decoded image that is then
// copied into `bgr` (OpenCV 4.6's decode-into-destination overload cannot report a corrupt
// frame). Prefer YUYV where the USB bandwidth allows it: that path allocates nothing.
// Returns false and fills `error` on a short buffer, a corrupt JPEG or a size mismatch.
bool convert_to_bgr(PixelFormat format, const std::uint8_t* data, std::size_t bytes_used, int width,
                    int height, std::size_t stride_bytes, cv::Mat& bgr, std::string& error);

}  // namespace rovctl::drivers
