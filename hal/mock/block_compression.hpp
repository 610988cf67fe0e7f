// A JPEG-like lossy round trip of an 8-bit image, in place and without the heap allocations of
// cv::imencode/imdecode, so that it can run inside the simulated tick.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace rovctl::hal::mock {

// YCbCr, optional 4:2:0 chroma subsampling, 8x8 DCT, quantisation by the scaled JPEG Annex K
// tables, and back: JPEG's block seams, ringing and colour bleeding. No entropy coding, which is
// lossless and would change nothing in the image.
class BlockCompression {
 public:
  // quality in [1, 100] as libjpeg's (IJG) scaling of the standard tables.
  BlockCompression(int quality, bool chroma_subsampling);

  // Compresses and decompresses bgr (CV_8UC3) in place, one minimum coded unit at a time.
  void apply(cv::Mat& bgr) const;

 private:
  using Block = Eigen::Matrix<float, 8, 8, Eigen::RowMajor>;
  // DCT, quantisation to multiples of `quant`, inverse DCT, in place.
  void round_trip(Block& samples, const Block& quant, const Block& inv_quant) const;

  bool subsample_;
  Block dct_;  // orthonormal DCT-II: F = D X D^T
  Block luma_quant_, luma_inv_;
  Block chroma_quant_, chroma_inv_;
};

}  // namespace rovctl::hal::mock
