// Pixel-format choice and YUYV/MJPG -> BGR conversion against known patterns.
#include "drivers/v4l2/pixel_format.hpp"

#include <gtest/gtest.h>
#include <linux/videodev2.h>

#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace rovctl::drivers {
namespace {

TEST(PixelFormat, PrefersTheConfiguredFormatWhenOffered) {
  const std::vector<std::uint32_t> both = {V4L2_PIX_FMT_MJPEG, V4L2_PIX_FMT_YUYV};
  EXPECT_EQ(choose_pixel_format(both, PixelFormat::yuyv), PixelFormat::yuyv);
  EXPECT_EQ(choose_pixel_format(both, PixelFormat::mjpg), PixelFormat::mjpg);
}

TEST(PixelFormat, FallsBackToTheOtherSupportedFormat) {
  EXPECT_EQ(choose_pixel_format({V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_MJPEG}, PixelFormat::yuyv),
            PixelFormat::mjpg);
  EXPECT_EQ(choose_pixel_format({V4L2_PIX_FMT_YUYV}, PixelFormat::mjpg), PixelFormat::yuyv);
  // Some UVC drivers announce motion JPEG as JPEG.
  EXPECT_EQ(choose_pixel_format({V4L2_PIX_FMT_JPEG}, PixelFormat::yuyv), PixelFormat::mjpg);
}

TEST(PixelFormat, NoneWhenNeitherIsOffered) {
  EXPECT_FALSE(choose_pixel_format({V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_NV12}, PixelFormat::yuyv));
  EXPECT_FALSE(choose_pixel_format({}, PixelFormat::mjpg));
}

TEST(PixelFormat, NamesAndFourccs) {
  EXPECT_EQ(fourcc_to_string(V4L2_PIX_FMT_YUYV), "YUYV");
  EXPECT_EQ(fourcc_to_string(V4L2_PIX_FMT_MJPEG), "MJPG");
  EXPECT_EQ(pixel_format_from_string("mjpg"), PixelFormat::mjpg);
  EXPECT_FALSE(pixel_format_from_string("h264"));
  EXPECT_EQ(pixel_format_from_fourcc(fourcc_of(PixelFormat::yuyv)), PixelFormat::yuyv);
  EXPECT_STREQ(to_string(PixelFormat::mjpg), "mjpg");
}

// BT.601 limited range, the conversion COLOR_YUV2BGR_YUYV implements.
cv::Vec3b expected_bgr(int y, int u, int v) {
  const double c = 1.164 * (y - 16);
  const double b = c + 2.018 * (u - 128);
  const double g = c - 0.813 * (v - 128) - 0.391 * (u - 128);
  const double r = c + 1.596 * (v - 128);
  return {cv::saturate_cast<unsigned char>(b), cv::saturate_cast<unsigned char>(g),
          cv::saturate_cast<unsigned char>(r)};
}

// Four vertical bars (YUV of white, red, green, blue) with a padded line pitch.
std::vector<std::uint8_t> yuyv_bars(int width, int height, std::size_t stride,
                                    const int (&yuv)[4][3]) {
  std::vector<std::uint8_t> buf(stride * static_cast<std::size_t>(height), 0xEE);
  for (int row = 0; row < height; ++row) {
    for (int x = 0; x < width; x += 2) {
      const int* c = yuv[(x * 4) / width];
      std::uint8_t* p = buf.data() + static_cast<std::size_t>(row) * stride + x * 2;
      p[0] = static_cast<std::uint8_t>(c[0]);
      p[1] = static_cast<std::uint8_t>(c[1]);
      p[2] = static_cast<std::uint8_t>(c[0]);
      p[3] = static_cast<std::uint8_t>(c[2]);
    }
  }
  return buf;
}

TEST(PixelFormat, YuyvToBgrMatchesBt601Bars) {
  constexpr int kWidth = 64;
  constexpr int kHeight = 8;
  constexpr std::size_t kStride = kWidth * 2 + 32;  // padded lines must be honoured
  const int yuv[4][3] = {{235, 128, 128}, {81, 90, 240}, {145, 54, 34}, {41, 240, 110}};
  const auto buf = yuyv_bars(kWidth, kHeight, kStride, yuv);
  cv::Mat bgr;
  std::string error;
  ASSERT_TRUE(convert_to_bgr(PixelFormat::yuyv, buf.data(), buf.size(), kWidth, kHeight, kStride,
                             bgr, error))
      << error;
  ASSERT_EQ(bgr.type(), CV_8UC3);
  ASSERT_EQ(bgr.cols, kWidth);
  ASSERT_EQ(bgr.rows, kHeight);
  for (int bar = 0; bar < 4; ++bar) {
    const cv::Vec3b want = expected_bgr(yuv[bar][0], yuv[bar][1], yuv[bar][2]);
    for (int row : {0, kHeight - 1}) {
      const cv::Vec3b got = bgr.at<cv::Vec3b>(row, bar * kWidth / 4 + 3);
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(got[ch], want[ch], 3) << "bar " << bar << " row " << row << " channel " << ch;
      }
    }
  }
  // The bars really are white, red, green, blue.
  const cv::Vec3b white = bgr.at<cv::Vec3b>(0, 2);
  const cv::Vec3b red = bgr.at<cv::Vec3b>(0, kWidth / 4 + 2);
  const cv::Vec3b blue = bgr.at<cv::Vec3b>(0, 3 * kWidth / 4 + 2);
  EXPECT_GT(white[0], 240);
  EXPECT_GT(red[2], 200);
  EXPECT_LT(red[0], 40);
  EXPECT_GT(blue[0], 200);
  EXPECT_LT(blue[2], 40);
}

TEST(PixelFormat, YuyvConversionReusesTheFrameBuffer) {
  const int yuv[4][3] = {{100, 128, 128}, {100, 128, 128}, {100, 128, 128}, {100, 128, 128}};
  const auto buf = yuyv_bars(32, 4, 64, yuv);
  cv::Mat bgr(4, 32, CV_8UC3);
  const unsigned char* before = bgr.data;
  std::string error;
  ASSERT_TRUE(convert_to_bgr(PixelFormat::yuyv, buf.data(), buf.size(), 32, 4, 64, bgr, error));
  EXPECT_EQ(bgr.data, before);
}

TEST(PixelFormat, ShortYuyvBufferIsAnError) {
  std::vector<std::uint8_t> buf(32 * 4 * 2 - 1);
  cv::Mat bgr;
  std::string error;
  EXPECT_FALSE(convert_to_bgr(PixelFormat::yuyv, buf.data(), buf.size(), 32, 4, 0, bgr, error));
  EXPECT_NE(error.find("short YUYV buffer"), std::string::npos) << error;
}

TEST(PixelFormat, MjpgDecodesIntoTheFramesOwnBuffer) {
  cv::Mat source(48, 64, CV_8UC3, cv::Scalar(30, 60, 200));
  source(cv::Rect(0, 0, 32, 48)).setTo(cv::Scalar(200, 40, 20));
  std::vector<unsigned char> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", source, jpeg, {cv::IMWRITE_JPEG_QUALITY, 95}));
  cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar(0, 0, 0));
  const unsigned char* before = bgr.data;
  std::string error;
  ASSERT_TRUE(convert_to_bgr(PixelFormat::mjpg, jpeg.data(), jpeg.size(), 64, 48, 0, bgr, error))
      << error;
  EXPECT_EQ(bgr.data, before);
  // Away from the edge (where JPEG's chroma subsampling blurs) the colours survive.
  EXPECT_LT(cv::norm(bgr(cv::Rect(0, 0, 24, 48)), source(cv::Rect(0, 0, 24, 48)), cv::NORM_INF),
            20.0);
  EXPECT_LT(cv::norm(bgr(cv::Rect(40, 0, 24, 48)), source(cv::Rect(40, 0, 24, 48)), cv::NORM_INF),
            20.0);
  const cv::Vec3b left = bgr.at<cv::Vec3b>(24, 8);
  const cv::Vec3b right = bgr.at<cv::Vec3b>(24, 56);
  EXPECT_GT(left[0], 170);
  EXPECT_GT(right[2], 170);
}

TEST(PixelFormat, CorruptOrMisSizedMjpgIsAnError) {
  std::vector<std::uint8_t> garbage(500, 0x42);
  cv::Mat bgr(48, 64, CV_8UC3);
  std::string error;
  EXPECT_FALSE(
      convert_to_bgr(PixelFormat::mjpg, garbage.data(), garbage.size(), 64, 48, 0, bgr, error));
  EXPECT_NE(error.find("corrupt MJPG"), std::string::npos) << error;

  // A frame cut short on the USB bus must not pass for a new image.
  std::vector<unsigned char> good;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(48, 64, CV_8UC3, cv::Scalar(9, 9, 9)), good));
  good.resize(good.size() / 2);
  error.clear();
  EXPECT_FALSE(convert_to_bgr(PixelFormat::mjpg, good.data(), good.size(), 64, 48, 0, bgr, error));
  EXPECT_NE(error.find("corrupt MJPG"), std::string::npos) << error;

  std::vector<unsigned char> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(20, 30, CV_8UC3, cv::Scalar(1, 2, 3)), jpeg));
  EXPECT_FALSE(convert_to_bgr(PixelFormat::mjpg, jpeg.data(), jpeg.size(), 64, 48, 0, bgr, error));
  EXPECT_NE(error.find("30x20, expected 64x48"), std::string::npos) << error;
  EXPECT_EQ(bgr.cols, 64);  // the frame keeps its size for the next grab
}

}  // namespace
}  // namespace rovctl::drivers
