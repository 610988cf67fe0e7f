// OpenCV stereo calibration YAML <-> hal::StereoRig. Accepts image size as `image_size` ([w, h])
// or `image_width`/`image_height`, and D with 4, 5 or more coefficients (extra ones must be 0).
#include "estimator/stereo_calibration.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "hal/primitives/image_header.hpp"

namespace rovctl::estimator {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw std::invalid_argument(file + ": " + what);
}

// The top-level key starting a line ("K1: !!opencv-matrix" -> "K1"), or empty.
std::string top_level_key(const std::string& line) {
  std::size_t n = 0;
  while (n < line.size() && (std::isalnum(static_cast<unsigned char>(line[n])) || line[n] == '_'))
    ++n;
  std::size_t colon = n;
  while (colon < line.size() && line[colon] == ' ') ++colon;
  return n > 0 && colon < line.size() && line[colon] == ':' ? line.substr(0, n) : std::string();
}

// Each top-level key's first line. cv::FileStorage keeps one of two equal keys without a word,
// so a key given twice is an error here, naming both lines.
std::map<std::string, int> top_level_key_lines(const std::string& file) {
  std::map<std::string, int> lines;
  std::ifstream in(file);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string key = top_level_key(line);
    if (key.empty()) continue;
    const auto [it, first] = lines.emplace(key, number);
    if (!first) {
      fail(file + ":" + std::to_string(number),
           "key '" + key + "' given twice (the first is line " + std::to_string(it->second) + ")");
    }
  }
  return lines;
}

// "file:line: what" where the key's line is known.
[[noreturn]] void fail_key(const std::string& file, const std::string& key,
                           const std::string& what) {
  const int line = calibration_key_line(file, key);
  fail(line > 0 ? file + ":" + std::to_string(line) : file, what);
}

cv::Mat read_matrix(const cv::FileStorage& fs, const std::string& file, const std::string& key,
                    int rows, int cols_min, int cols_max) {
  const cv::FileNode n = fs[key];
  if (n.empty()) fail(file, "missing key '" + key + "'");
  cv::Mat m;
  try {
    n >> m;
  } catch (const cv::Exception&) {
    fail_key(file, key, "key '" + key + "' is not an OpenCV matrix");
  }
  if (m.empty()) fail_key(file, key, "key '" + key + "' is not an OpenCV matrix");
  m.convertTo(m, CV_64F);
  if (m.rows == 1 && rows != 1 && m.cols == rows) m = m.t();  // a row vector where a column is due
  if (rows == 1 && m.cols == 1) m = m.t();                    // distortion given as a column
  if (m.rows != rows || m.cols < cols_min || m.cols > cols_max) {
    fail_key(file, key,
             "key '" + key + "' has shape " + std::to_string(m.rows) + "x" +
                 std::to_string(m.cols) + ", expected " + std::to_string(rows) + "x" +
                 std::to_string(cols_min) +
                 (cols_max != cols_min ? ".." + std::to_string(cols_max) : ""));
  }
  for (int r = 0; r < m.rows; ++r) {
    for (int c = 0; c < m.cols; ++c) {
      if (!std::isfinite(m.at<double>(r, c)))
        fail_key(file, key, "key '" + key + "' has a non-finite value");
    }
  }
  return m;
}

hal::CameraModel camera_from(const std::string& file, const cv::Mat& K, const cv::Mat& D,
                             const std::string& kname, const std::string& dname, int width,
                             int height) {
  hal::CameraModel cam;
  cam.fx_px = K.at<double>(0, 0);
  cam.fy_px = K.at<double>(1, 1);
  cam.cx_px = K.at<double>(0, 2);
  cam.cy_px = K.at<double>(1, 2);
  if (!(cam.fx_px > 0 && cam.fy_px > 0))
    fail_key(file, kname, "key '" + kname + "': focal lengths must be > 0");
  if (K.at<double>(2, 2) != 1.0) fail_key(file, kname, "key '" + kname + "': K(2,2) must be 1");
  // The camera model has no skew and no other terms: a value off the pattern would be dropped
  // without a word, moving every projection.
  for (const auto& [r, c] : {std::pair{1, 0}, {2, 0}, {2, 1}, {0, 1}}) {
    if (K.at<double>(r, c) != 0.0) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "key '%s': K(%d,%d) = %g, but a camera matrix is [fx 0 cx; 0 fy cy; 0 0 1] "
                    "(upper-triangular, no skew)",
                    kname.c_str(), r, c, K.at<double>(r, c));
      fail_key(file, kname, text);
    }
  }
  const double* d = D.ptr<double>(0);
  cam.k1 = d[0];
  cam.k2 = d[1];
  cam.p1 = d[2];
  cam.p2 = d[3];
  cam.k3 = D.cols > 4 ? d[4] : 0.0;
  for (int i = 5; i < D.cols; ++i) {
    if (d[i] != 0.0)
      fail_key(file, dname,
               "key '" + dname +
                   "': distortion coefficients beyond k3 (rational/thin prism) are not supported");
  }
  cam.width_px = width;
  cam.height_px = height;
  return cam;
}

// The right camera's centre in the left camera's frame is -R^T T: it must lie to the right (+x,
// OpenCV's x right, y down), which makes T.x negative for a level rig, and the cameras must stand
// side by side, not one behind the other.
void check_side_by_side(const std::string& file, const hal::StereoRig& rig) {
  const Eigen::Vector3d centre = rig.T_cr_cl.inverse().translation();
  const Eigen::Vector3d T = rig.T_cr_cl.translation();
  char text[320];
  if (std::abs(centre.x()) < 0.5 * centre.norm()) {
    std::snprintf(text, sizeof text,
                  "key 'T': T = [%g, %g, %g] puts the right camera %.3f m from the left one but "
                  "only %.3f m to its side: the cameras must stand side by side (the sideways "
                  "part at least half the baseline)",
                  T.x(), T.y(), T.z(), centre.norm(), std::abs(centre.x()));
    fail_key(file, "T", text);
  }
  if (centre.x() < 0.0) {
    std::snprintf(text, sizeof text,
                  "key 'T': T = [%g, %g, %g] puts the right camera %.3f m to the LEFT of the left "
                  "one (centre -R^T T); in OpenCV's x_right = R * x_left + T a right camera has "
                  "T.x < 0: are the left and right images or the sign of T swapped?",
                  T.x(), T.y(), T.z(), -centre.x());
    fail_key(file, "T", text);
  }
}

}  // namespace

int calibration_key_line(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (top_level_key(line) == key) return number;
  }
  return 0;
}

hal::StereoRig load_stereo_calibration(const std::string& file) {
  if (!std::filesystem::is_regular_file(file))
    fail(file, "cannot read calibration file (no such file)");
  top_level_key_lines(file);  // no key given twice
  cv::FileStorage fs;
  try {
    if (!fs.open(file, cv::FileStorage::READ)) fail(file, "cannot open calibration file");
  } catch (const cv::Exception& e) {
    fail(file, std::string("malformed calibration YAML: ") + e.what());
  }
  int width = 0, height = 0;
  if (!fs["image_size"].empty()) {
    cv::FileNode s = fs["image_size"];
    if (!s.isSeq() || s.size() != 2)
      fail_key(file, "image_size", "key 'image_size' must be [width, height]");
    width = static_cast<int>(s[0]);
    height = static_cast<int>(s[1]);
  } else if (!fs["image_width"].empty() && !fs["image_height"].empty()) {
    width = static_cast<int>(fs["image_width"]);
    height = static_cast<int>(fs["image_height"]);
  } else {
    fail(file, "missing key 'image_size' (or image_width/image_height)");
  }
  if (width < 16 || height < 16 || width > hal::kMaxImageSidePx || height > hal::kMaxImageSidePx) {
    fail_key(
        file, fs["image_size"].empty() ? "image_width" : "image_size",
        "key 'image_size': implausible " + std::to_string(width) + "x" + std::to_string(height));
  }
  const cv::Mat K1 = read_matrix(fs, file, "K1", 3, 3, 3);
  const cv::Mat D1 = read_matrix(fs, file, "D1", 1, 4, 14);
  const cv::Mat K2 = read_matrix(fs, file, "K2", 3, 3, 3);
  const cv::Mat D2 = read_matrix(fs, file, "D2", 1, 4, 14);
  const cv::Mat R = read_matrix(fs, file, "R", 3, 3, 3);
  const cv::Mat T = read_matrix(fs, file, "T", 3, 1, 1);

  hal::StereoRig rig;
  rig.left = camera_from(file, K1, D1, "K1", "D1", width, height);
  rig.right = camera_from(file, K2, D2, "K2", "D2", width, height);
  Eigen::Matrix3d Rm;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) Rm(r, c) = R.at<double>(r, c);
  }
  if ((Rm * Rm.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-3 ||
      Rm.determinant() < 0.99) {
    fail_key(file, "R", "key 'R' is not a rotation matrix");
  }
  rig.T_cr_cl.linear() = Eigen::Quaterniond(Rm).normalized().toRotationMatrix();
  rig.T_cr_cl.translation() = Eigen::Vector3d(T.at<double>(0), T.at<double>(1), T.at<double>(2));
  if (rig.baseline_m() < 1e-3 || rig.baseline_m() > 5.0) {
    fail_key(file, "T",
             "key 'T': baseline " + std::to_string(rig.baseline_m()) +
                 " m is implausible (units must be metres)");
  }
  check_side_by_side(file, rig);
  return rig;
}

CalibrationFigures load_calibration_figures(const std::string& file) {
  CalibrationFigures f;
  cv::FileStorage fs;
  try {
    if (!fs.open(file, cv::FileStorage::READ)) return f;
  } catch (const cv::Exception&) {
    return f;
  }
  if (fs["rms_reprojection_px"].isReal()) f.rms_reprojection_px = fs["rms_reprojection_px"];
  if (fs["epipolar_rms_px"].isReal()) f.epipolar_rms_px = fs["epipolar_rms_px"];
  if (fs["views_used"].isInt()) f.views_used = fs["views_used"];
  if (fs["calibrated_utc"].isString())
    f.calibrated_utc = static_cast<std::string>(fs["calibrated_utc"]);
  return f;
}

void write_stereo_rig(cv::FileStorage& fs, const hal::StereoRig& rig) {
  auto K = [](const hal::CameraModel& c) -> cv::Mat {
    return (cv::Mat_<double>(3, 3) << c.fx_px, 0, c.cx_px, 0, c.fy_px, c.cy_px, 0, 0, 1);
  };
  auto D = [](const hal::CameraModel& c) -> cv::Mat {
    return (cv::Mat_<double>(1, 5) << c.k1, c.k2, c.p1, c.p2, c.k3);
  };
  cv::Mat R(3, 3, CV_64F), T(3, 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R.at<double>(r, c) = rig.T_cr_cl.linear()(r, c);
    T.at<double>(r) = rig.T_cr_cl.translation()(r);
  }
  fs << "K1" << K(rig.left) << "D1" << D(rig.left) << "K2" << K(rig.right) << "D2" << D(rig.right);
  fs << "R" << R << "T" << T;
}

void save_stereo_calibration(const std::string& file, const hal::StereoRig& rig) {
  const std::string tmp = file + ".tmp";
  {
    cv::FileStorage fs(tmp, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw std::runtime_error(file + ": cannot write calibration file");
    fs << "image_size" << std::vector<int>{rig.left.width_px, rig.left.height_px};
    write_stereo_rig(fs, rig);
  }
  std::filesystem::rename(tmp, file);  // never a half-written calibration
}

}  // namespace rovctl::estimator
