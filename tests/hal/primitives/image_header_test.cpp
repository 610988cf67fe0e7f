// Image sizes from PNG and JPEG headers, before decoding: a tiny file declaring a huge image is
// rejected naming the file and the size, without a byte of pixels read.
#include "hal/primitives/image_header.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace rovctl::hal {
namespace {

void put32(std::vector<unsigned char>& b, unsigned long v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<unsigned char>((v >> s) & 0xFF));
}

// A PNG signature and IHDR declaring w x h, and nothing else: what the 2.6 GB bomb looked like.
std::vector<unsigned char> png_header(unsigned long w, unsigned long h) {
  std::vector<unsigned char> b = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  put32(b, 13);
  for (char c : std::string("IHDR")) b.push_back(static_cast<unsigned char>(c));
  put32(b, w);
  put32(b, h);
  b.insert(b.end(), {8, 2, 0, 0, 0, 0, 0, 0, 0});  // depth, colour type, ..., CRC (unchecked)
  return b;
}

// SOI, an APP0 segment, a fill byte, then a baseline frame header (SOF0) declaring w x h.
std::vector<unsigned char> jpeg_header(unsigned w, unsigned h) {
  std::vector<unsigned char> b = {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10};
  for (int i = 0; i < 14; ++i) b.push_back(0);
  b.insert(b.end(), {0xFF, 0xFF, 0xC0, 0x00, 0x11, 0x08});
  b.insert(b.end(), {static_cast<unsigned char>(h >> 8), static_cast<unsigned char>(h & 0xFF),
                     static_cast<unsigned char>(w >> 8), static_cast<unsigned char>(w & 0xFF)});
  return b;
}

std::string write(const std::string& name, const std::vector<unsigned char>& bytes) {
  const std::string path = ::testing::TempDir() + "rovctl_" + std::to_string(::getpid()) + name;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return path;
}

TEST(ImageHeader, ReadsPngAndJpegSizes) {
  ImageHeader h;
  std::string error;
  const auto png = png_header(640, 480);
  ASSERT_TRUE(parse_image_header(png.data(), png.size(), h, error)) << error;
  EXPECT_STREQ(h.format, "PNG");
  EXPECT_EQ(h.width_px, 640);
  EXPECT_EQ(h.height_px, 480);
  const auto jpeg = jpeg_header(1280, 720);
  ASSERT_TRUE(parse_image_header(jpeg.data(), jpeg.size(), h, error)) << error;
  EXPECT_STREQ(h.format, "JPEG");
  EXPECT_EQ(h.width_px, 1280);
  EXPECT_EQ(h.height_px, 720);
}

TEST(ImageHeader, RejectsJunkAndTruncatedHeaders) {
  ImageHeader h;
  std::string error;
  const std::vector<unsigned char> junk = {'h', 'e', 'l', 'l', 'o'};
  EXPECT_FALSE(parse_image_header(junk.data(), junk.size(), h, error));
  EXPECT_EQ(error, "not a PNG or JPEG image");
  const auto png = png_header(640, 480);
  EXPECT_FALSE(parse_image_header(png.data(), 20, h, error));
  const auto jpeg = jpeg_header(640, 480);
  EXPECT_FALSE(parse_image_header(jpeg.data(), 12, h, error));
}

TEST(ImageHeader, AHugeDeclaredSizeIsRejectedNamingFileAndSize) {
  const std::string bomb = write("bomb.png", png_header(30000, 30000));
  const std::string problem = check_image_file(bomb);
  EXPECT_EQ(problem, bomb +
                         ": PNG header declares 30000x30000 pixels, beyond the limit of 8192 a "
                         "side (not decoded)");
  const std::string small = write("small.jpg", jpeg_header(320, 240));
  EXPECT_EQ(check_image_file(small), "");
  EXPECT_EQ(check_image_file(small, 640, 480, "the calibration c.yaml"),
            small + ": image is 320x240 but the calibration c.yaml says 640x480");
  EXPECT_NE(check_image_file("/nonexistent/x.png").find("/nonexistent/x.png: cannot read image"),
            std::string::npos);
  std::remove(bomb.c_str());
  std::remove(small.c_str());
}

}  // namespace
}  // namespace rovctl::hal
