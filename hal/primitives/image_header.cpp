// PNG (IHDR, the first chunk) and JPEG (the first SOFn frame header) sizes, without decoding.
#include "hal/primitives/image_header.hpp"

#include <algorithm>
#include <fstream>
#include <vector>

namespace rovctl::hal {
namespace {

// A JPEG's frame header follows its metadata; EXIF segments are at most 64 KiB each, and a
// camera writes a handful: 1 MiB holds them.
constexpr std::size_t kHeaderSearchBytes = 1 << 20;

unsigned be16(const unsigned char* p) { return (unsigned(p[0]) << 8) | p[1]; }
unsigned long be32(const unsigned char* p) {
  return (static_cast<unsigned long>(be16(p)) << 16) | be16(p + 2);
}

bool parse_jpeg(const unsigned char* d, std::size_t n, ImageHeader& h, std::string& error) {
  std::size_t i = 2;  // after SOI
  while (i + 4 <= n) {
    if (d[i] != 0xFF) {
      error = "JPEG: no marker where a segment should start";
      return false;
    }
    const unsigned char marker = d[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {  // no length
      i += 2;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) break;  // end of image / start of scan: no frame yet
    const std::size_t length = be16(d + i + 2);
    const bool sof =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (i + 9 > n) break;
      h.format = "JPEG";
      h.height_px = static_cast<int>(be16(d + i + 5));
      h.width_px = static_cast<int>(be16(d + i + 7));
      return true;
    }
    i += 2 + length;
  }
  error = "JPEG: no frame header (SOF) within the first " + std::to_string(n) + " bytes";
  return false;
}

}  // namespace

bool parse_image_header(const unsigned char* d, std::size_t n, ImageHeader& h, std::string& error) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (n >= 8 && std::equal(kPng, kPng + 8, d)) {
    if (n < 24 || !std::equal(d + 12, d + 16, reinterpret_cast<const unsigned char*>("IHDR"))) {
      error = "PNG: no IHDR header";
      return false;
    }
    const unsigned long w = be32(d + 16), hgt = be32(d + 20);
    // PNG allows up to 2^31 - 1: clamp what an int holds, the limit check rejects it anyway.
    h.format = "PNG";
    h.width_px = static_cast<int>(w > 0x7FFFFFFFul ? 0x7FFFFFFFul : w);
    h.height_px = static_cast<int>(hgt > 0x7FFFFFFFul ? 0x7FFFFFFFul : hgt);
    return true;
  }
  if (n >= 3 && d[0] == 0xFF && d[1] == 0xD8 && d[2] == 0xFF) return parse_jpeg(d, n, h, error);
  error = "not a PNG or JPEG image";
  return false;
}

bool read_image_header(const std::string& file, ImageHeader& header, std::string& error) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    error = file + ": cannot read image";
    return false;
  }
  std::vector<unsigned char> bytes(kHeaderSearchBytes);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  const auto got = static_cast<std::size_t>(in.gcount());
  if (!parse_image_header(bytes.data(), got, header, error)) {
    error = file + ": cannot read image (" + error + ")";
    return false;
  }
  return true;
}

std::string image_size_problem(const std::string& file, const ImageHeader& h, int expected_width_px,
                               int expected_height_px, const std::string& expected_what) {
  const std::string size = std::to_string(h.width_px) + "x" + std::to_string(h.height_px);
  if (h.width_px <= 0 || h.height_px <= 0 || h.width_px > kMaxImageSidePx ||
      h.height_px > kMaxImageSidePx) {
    return file + ": " + h.format + " header declares " + size + " pixels, beyond the limit of " +
           std::to_string(kMaxImageSidePx) + " a side (not decoded)";
  }
  if (expected_width_px > 0 &&
      (h.width_px != expected_width_px || h.height_px != expected_height_px)) {
    return file + ": image is " + size + " but " + expected_what + " says " +
           std::to_string(expected_width_px) + "x" + std::to_string(expected_height_px);
  }
  return "";
}

std::string check_image_file(const std::string& file, int expected_width_px, int expected_height_px,
                             const std::string& expected_what) {
  ImageHeader header;
  std::string error;
  if (!read_image_header(file, header, error)) return error;
  return image_size_problem(file, header, expected_width_px, expected_height_px, expected_what);
}

}  // namespace rovctl::hal
