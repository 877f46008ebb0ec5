#include "calibration/camera_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/calib3d.hpp>

namespace glarecam::calibration {
namespace {

// Fixed-point iterations of the undistortion: OpenCV's default of 5 leaves visible error at
// the corners of a strongly distorted lens; 50 converges to well below 1e-6 px in practice.
constexpr int kUndistortIterations = 50;
constexpr double kUndistortEpsilon = 1e-12;

Ray normalised(double x, double y) {
  const double norm = std::sqrt(x * x + y * y + 1.0);
  return {x / norm, y / norm, 1.0 / norm};
}

}  // namespace

double angleBetweenDeg(const Ray& a, const Ray& b) {
  // atan2 of cross and dot products: accurate for small angles, unlike acos.
  const double cx = a.y * b.z - a.z * b.y;
  const double cy = a.z * b.x - a.x * b.z;
  const double cz = a.x * b.y - a.y * b.x;
  const double dot = a.x * b.x + a.y * b.y + a.z * b.z;
  // (θ·180)/π rather than core/angles.h's θ·(180/π): the last bit of every measured axis, and the
  // published sweeps, stay as they were.
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * 180.0 / std::numbers::pi;
}

bool CameraModel::hasDistortion() const {
  return std::any_of(intrinsics_.distortion.begin(), intrinsics_.distortion.end(),
                     [](double k) { return k != 0.0; });
}

std::vector<Ray> CameraModel::rays(std::span<const PixelPoint> pixels) const {
  std::vector<Ray> result(pixels.size());
  if (pixels.empty()) return result;  // cv::undistortPoints throws on an empty input
  const auto& k = intrinsics_;
  if (!hasDistortion()) {
    for (std::size_t i = 0; i < pixels.size(); ++i) {
      result[i] = normalised((pixels[i].x - k.cx) / k.fx, (pixels[i].y - k.cy) / k.fy);
    }
    return result;
  }
  std::vector<cv::Point2d> source(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) source[i] = {pixels[i].x, pixels[i].y};
  const cv::Matx33d camera(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  const cv::Matx<double, 1, 5> distortion(k.distortion[0], k.distortion[1], k.distortion[2],
                                          k.distortion[3], k.distortion[4]);
  std::vector<cv::Point2d> undistorted;
  cv::undistortPoints(source, undistorted, camera, distortion, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                       kUndistortIterations, kUndistortEpsilon));
  for (std::size_t i = 0; i < pixels.size(); ++i)
    result[i] = normalised(undistorted[i].x, undistorted[i].y);
  return result;
}

Ray CameraModel::ray(const PixelPoint& pixel) const { return rays(std::span(&pixel, 1)).front(); }

PixelPoint CameraModel::project(const Ray& ray) const {
  const auto& k = intrinsics_;
  const double x = ray.x / ray.z, y = ray.y / ray.z;
  const double r2 = x * x + y * y;
  const auto& d = k.distortion;  // k1, k2, p1, p2, k3
  const double radial = 1 + d[0] * r2 + d[1] * r2 * r2 + d[4] * r2 * r2 * r2;
  const double xd = x * radial + 2 * d[2] * x * y + d[3] * (r2 + 2 * x * x);
  const double yd = y * radial + d[2] * (r2 + 2 * y * y) + 2 * d[3] * x * y;
  return {k.fx * xd + k.cx, k.fy * yd + k.cy};
}

}  // namespace glarecam::calibration
