// A camera lens's distortion, found from pictures of a chessboard filmed through it (OpenCV's camera model:
// radial k1, k2 about the picture's centre, in coordinates divided by a focal length), and the film's pixels
// carried to where a camera without distortion would have them (ideal pixels), and back. The scale, origin
// and rotation to metres apply to ideal pixels (app/services/lab.h).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace vision {

struct Lens {
  bool present = false;
  cv::Matx33d camera = cv::Matx33d::eye();       // fx 0 cx / 0 fy cy / 0 0 1, px
  cv::Vec<double, 5> distortion{0, 0, 0, 0, 0};  // k1 k2 p1 p2 k3 (OpenCV's order)
  double rms = 0;    // px: the chessboard corners' distance from the fitted model (root mean square)
  int views = 0;     // pictures whose chessboard was found
  cv::Size size;     // the pictures' (the film's frames must have it)
  std::string from;  // the pictures

  cv::Point2d ideal(cv::Point2d raw) const;  // a film pixel -> where a camera without distortion has it
  cv::Point2d raw(cv::Point2d ideal) const;  // and back
  void ideal(std::vector<cv::Point2d>& points) const;  // many at once, in place
};

// The lens from pictures (files, or one directory of them in name order) of a flat chessboard with `pattern`
// inner corners (columns x rows), all of one size (the film's). With one or two pictures the focal length is
// held at the picture's larger side (one view cannot tell it from the distance; the distortion is what
// matters here); with three or more it is fitted too. Throws core::InputError naming the picture whose
// chessboard is not found, or the size that differs.
Lens lens_from_chessboard(const std::string& pictures, cv::Size pattern);

// What a camera with this lens films of an ideal picture (for tests and round trips).
cv::Mat distort_picture(const cv::Mat& ideal, const Lens& lens);

}  // namespace vision
