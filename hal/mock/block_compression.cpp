// Baseline JPEG codes each minimum coded unit (16x16 pixels with subsampled chroma) on its own, so
// the round trip runs MCU by MCU on the stack; chroma comes back by replication, not libjpeg's
// smoother "fancy" upsampling.
#include "hal/mock/block_compression.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rovctl::hal::mock {
namespace {

// ITU-T T.81 Annex K, tables K.1 (luminance) and K.2 (chrominance), row-major.
constexpr int kLuma[64] = {16, 11, 10, 16, 24,  40,  51,  61,  12, 12, 14, 19, 26,  58,  60,  55,
                           14, 13, 16, 24, 40,  57,  69,  56,  14, 17, 22, 29, 51,  87,  80,  62,
                           18, 22, 37, 56, 68,  109, 103, 77,  24, 35, 55, 64, 81,  104, 113, 92,
                           49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99};
constexpr int kChroma[64] = {17, 18, 24, 47, 99, 99, 99, 99, 18, 21, 26, 66, 99, 99, 99, 99,
                             24, 26, 56, 99, 99, 99, 99, 99, 47, 66, 99, 99, 99, 99, 99, 99,
                             99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99,
                             99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99};

constexpr int kMcu = 16;

// Clamped as an integer (conditional moves): the values are noisy, so a branch would mispredict.
inline std::uint8_t saturate(float x) {
  const int v = static_cast<int>(x + 0.5f);
  return static_cast<std::uint8_t>(v < 0 ? 0 : v > 255 ? 255 : v);
}

}  // namespace

BlockCompression::BlockCompression(int quality, bool chroma_subsampling)
    : subsample_(chroma_subsampling) {
  const int q = std::clamp(quality, 1, 100);
  const int scale = q < 50 ? 5000 / q : 200 - 2 * q;  // libjpeg's jpeg_quality_scaling
  for (int r = 0; r < 8; ++r) {
    for (int c = 0; c < 8; ++c) {
      const int i = r * 8 + c;
      luma_quant_(r, c) = static_cast<float>(std::clamp((kLuma[i] * scale + 50) / 100, 1, 255));
      chroma_quant_(r, c) = static_cast<float>(std::clamp((kChroma[i] * scale + 50) / 100, 1, 255));
      const double a = r == 0 ? std::sqrt(1.0 / 8.0) : std::sqrt(2.0 / 8.0);
      dct_(r, c) = static_cast<float>(a * std::cos((2 * c + 1) * r * M_PI / 16.0));
    }
  }
  luma_inv_ = luma_quant_.cwiseInverse();
  chroma_inv_ = chroma_quant_.cwiseInverse();
}

void BlockCompression::round_trip(Block& samples, const Block& quant,
                                  const Block& inv_quant) const {
  // lazyProduct: the unrolled small-matrix kernel, not the general (and slower) GEMM path.
  Block f = dct_.lazyProduct(samples).lazyProduct(dct_.transpose());
  for (int i = 0; i < 64; ++i) {
    const float x = f(i) * inv_quant(i);
    // Round half away from zero, as libjpeg's quantiser does.
    f(i) = static_cast<float>(static_cast<int>(x + (x >= 0.0f ? 0.5f : -0.5f))) * quant(i);
  }
  samples = dct_.transpose().lazyProduct(f).lazyProduct(dct_);
}

void BlockCompression::apply(cv::Mat& bgr) const {
  const int mcu = subsample_ ? 16 : 8;
  const int w = bgr.cols, h = bgr.rows;
  // One MCU: its pixels (edges replicated), its level-shifted luma blocks and one block of each
  // chroma (at half resolution when subsampled).
  float r[kMcu][kMcu], g[kMcu][kMcu], b[kMcu][kMcu];
  Block y[2][2], cb, cr;
  for (int by = 0; by < h; by += mcu) {
    for (int bx = 0; bx < w; bx += mcu) {
      const int rows = std::min(mcu, h - by), cols = std::min(mcu, w - bx);
      for (int j = 0; j < mcu; ++j) {
        const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(by + std::min(j, rows - 1)) + bx;
        for (int i = 0; i < mcu; ++i) {
          const cv::Vec3b& p = row[std::min(i, cols - 1)];
          b[j][i] = p[0];
          g[j][i] = p[1];
          r[j][i] = p[2];
        }
      }
      for (int j = 0; j < mcu; ++j) {
        for (int i = 0; i < mcu; ++i) {
          y[j / 8][i / 8](j % 8, i % 8) =
              0.299f * r[j][i] + 0.587f * g[j][i] + 0.114f * b[j][i] - 128.0f;
        }
      }
      if (subsample_) {
        for (int j = 0; j < 8; ++j) {
          for (int i = 0; i < 8; ++i) {
            const int y0 = 2 * j, x0 = 2 * i;
            const float rr =
                0.25f * (r[y0][x0] + r[y0][x0 + 1] + r[y0 + 1][x0] + r[y0 + 1][x0 + 1]);
            const float gg =
                0.25f * (g[y0][x0] + g[y0][x0 + 1] + g[y0 + 1][x0] + g[y0 + 1][x0 + 1]);
            const float bb =
                0.25f * (b[y0][x0] + b[y0][x0 + 1] + b[y0 + 1][x0] + b[y0 + 1][x0 + 1]);
            cb(j, i) = -0.168736f * rr - 0.331264f * gg + 0.5f * bb;
            cr(j, i) = 0.5f * rr - 0.418688f * gg - 0.081312f * bb;
          }
        }
      } else {
        for (int j = 0; j < 8; ++j) {
          for (int i = 0; i < 8; ++i) {
            cb(j, i) = -0.168736f * r[j][i] - 0.331264f * g[j][i] + 0.5f * b[j][i];
            cr(j, i) = 0.5f * r[j][i] - 0.418688f * g[j][i] - 0.081312f * b[j][i];
          }
        }
      }
      const int n = mcu / 8;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) round_trip(y[j][i], luma_quant_, luma_inv_);
      }
      round_trip(cb, chroma_quant_, chroma_inv_);
      round_trip(cr, chroma_quant_, chroma_inv_);
      const int shift = subsample_ ? 1 : 0;
      for (int j = 0; j < rows; ++j) {
        cv::Vec3b* row = bgr.ptr<cv::Vec3b>(by + j) + bx;
        for (int i = 0; i < cols; ++i) {
          const float yy = y[j / 8][i / 8](j % 8, i % 8) + 128.0f;
          const float u = cb(j >> shift, i >> shift), v = cr(j >> shift, i >> shift);
          row[i] =
              cv::Vec3b(saturate(yy + 1.772f * u), saturate(yy - 0.344136f * u - 0.714136f * v),
                        saturate(yy + 1.402f * v));
        }
      }
    }
  }
}

}  // namespace rovctl::hal::mock
