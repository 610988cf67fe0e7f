// An image's size read from its PNG or JPEG header, before anything is decoded: a 200-byte PNG
// can declare 30000 x 30000 pixels, which cv::imread would spend 2.6 GB and 20 s decoding before
// any size check could reject it. Every place rovctl reads an image file checks it here first.
#pragma once

#include <cstddef>
#include <string>

namespace rovctl::hal {

// The largest width or height, in pixels, of an image rovctl decodes (8192: twice a 4K frame; a
// BGR image at the limit is 200 MB). The calibration's image size is held to the same limit.
constexpr int kMaxImageSidePx = 8192;

struct ImageHeader {
  const char* format = "";  // "PNG" or "JPEG"
  int width_px = 0;
  int height_px = 0;
};

// From the first bytes of a file (a JPEG's frame header may follow its metadata segments: give
// all of it that is at hand). False with `error` when the bytes are neither PNG nor JPEG or end
// before the size.
bool parse_image_header(const unsigned char* data, std::size_t size, ImageHeader& header,
                        std::string& error);

// Reads the file's header. False with `error` naming the file when it cannot.
bool read_image_header(const std::string& file, ImageHeader& header, std::string& error);

// The check before decoding: "" when `header` is within kMaxImageSidePx and, when
// expected_width_px > 0, exactly the expected size; else the problem, naming the file, the size and
// `expected_what` (e.g. "the calibration cal.yaml").
std::string image_size_problem(const std::string& file, const ImageHeader& header,
                               int expected_width_px = 0, int expected_height_px = 0,
                               const std::string& expected_what = "");

// read_image_header and image_size_problem in one: "" when the file may be decoded.
std::string check_image_file(const std::string& file, int expected_width_px = 0,
                             int expected_height_px = 0, const std::string& expected_what = "");

}  // namespace rovctl::hal
