// A camera lens's distortion from a chessboard (vision/lens.h).
#include "vision/lens.h"

#include <algorithm>
#include <filesystem>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "vision/codecs.h"
#include "vision/detect.h"

namespace vision {

cv::Point2d Lens::ideal(cv::Point2d raw) const {
  std::vector<cv::Point2d> p{raw};
  ideal(p);
  return p[0];
}

void Lens::ideal(std::vector<cv::Point2d>& points) const {
  if (!present || points.empty()) return;
  std::vector<cv::Point2d> out;
  cv::undistortPoints(points, out, camera, distortion, cv::noArray(), camera,
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 1e-9));
  points = std::move(out);
}

cv::Point2d Lens::raw(cv::Point2d ideal) const {
  if (!present) return ideal;
  const double fx = camera(0, 0), fy = camera(1, 1), cx = camera(0, 2), cy = camera(1, 2);
  const double k1 = distortion[0], k2 = distortion[1], p1 = distortion[2], p2 = distortion[3],
               k3 = distortion[4];
  const double x = (ideal.x - cx) / fx, y = (ideal.y - cy) / fy, r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
  const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
  return {fx * xd + cx, fy * yd + cy};
}

namespace {

std::vector<std::string> picture_files(const std::string& pictures) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(pictures, ec)) {
    if (!fs::is_regular_file(pictures, ec))
      throw core::InputError("--lens " + pictures + ": no such picture or directory of chessboard pictures");
    return {pictures};
  }
  std::vector<std::string> files;
  for (const fs::path& p : pictures_in(pictures)) files.push_back(p.string());
  if (files.empty())
    throw core::InputError("--lens " + pictures + ": the directory holds no picture (PNG, JPEG, BMP, TIFF)");
  return files;
}

}  // namespace

Lens lens_from_chessboard(const std::string& pictures, cv::Size pattern) {
  const std::vector<std::string> files = picture_files(pictures);
  std::vector<cv::Point3f> board;
  for (int r = 0; r < pattern.height; ++r)
    for (int c = 0; c < pattern.width; ++c)
      board.emplace_back(static_cast<float>(c), static_cast<float>(r), 0.f);
  std::vector<std::vector<cv::Point3f>> object;
  std::vector<std::vector<cv::Point2f>> image;
  cv::Size size;
  for (const std::string& f : files) {
    const cv::Mat grey = codecs().read_picture(f, cv::IMREAD_GRAYSCALE);
    if (grey.empty()) throw core::InputError("--lens " + f + ": cannot be decoded as a picture");
    if (size.area() == 0) size = grey.size();
    if (grey.size() != size)
      throw core::InputError("--lens " + f + ": " + std::to_string(grey.cols) + "x" +
                             std::to_string(grey.rows) + " where the first picture is " +
                             std::to_string(size.width) + "x" + std::to_string(size.height));
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCorners(grey, pattern, corners,
                                   cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
      throw core::InputError("--lens " + f + ": no chessboard of " + std::to_string(pattern.width) + "x" +
                             std::to_string(pattern.height) +
                             " inner corners found (--pattern COLUMNSxROWS counts the corners where four "
                             "squares meet)");
    cv::cornerSubPix(grey, corners, cv::Size(5, 5), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 40, 1e-4));
    object.push_back(board);
    image.push_back(corners);
  }
  Lens lens;
  lens.present = true;
  lens.views = static_cast<int>(image.size());
  lens.from = pictures;
  lens.size = size;
  const double f = std::max(size.width, size.height);
  lens.camera = cv::Matx33d(f, 0, 0.5 * (size.width - 1), 0, f, 0.5 * (size.height - 1), 0, 0, 1);
  cv::Mat camera(lens.camera), distortion = cv::Mat::zeros(1, 5, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_PRINCIPAL_POINT | cv::CALIB_FIX_ASPECT_RATIO |
              cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K3;
  if (lens.views < 3) flags |= cv::CALIB_FIX_FOCAL_LENGTH;
  lens.rms = cv::calibrateCamera(object, image, size, camera, distortion, rvecs, tvecs, flags);
  lens.camera = cv::Matx33d(camera);
  for (int k = 0; k < 5; ++k) lens.distortion[k] = distortion.at<double>(0, k);
  return lens;
}

cv::Mat distort_picture(const cv::Mat& ideal, const Lens& lens) {
  std::vector<cv::Point2d> at;
  at.reserve(static_cast<size_t>(ideal.rows) * ideal.cols);
  for (int y = 0; y < ideal.rows; ++y)
    for (int x = 0; x < ideal.cols; ++x) at.emplace_back(x, y);
  lens.ideal(at);  // each film pixel shows what the ideal picture has where that pixel's ray goes
  cv::Mat mx(ideal.size(), CV_32F), my(ideal.size(), CV_32F);
  for (int y = 0; y < ideal.rows; ++y)
    for (int x = 0; x < ideal.cols; ++x) {
      const cv::Point2d& p = at[static_cast<size_t>(y) * ideal.cols + x];
      mx.at<float>(y, x) = static_cast<float>(p.x);
      my.at<float>(y, x) = static_cast<float>(p.y);
    }
  cv::Mat out;
  cv::remap(ideal, out, mx, my, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

}  // namespace vision
