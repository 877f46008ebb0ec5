#include "pipeline/luminance_peak.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace glarecam::pipeline {
namespace {

using calibration::PixelBound;

// The quadratic-fit window grows from 7x7 while its whole border stays on the cap of the lobe
// (above kCapFraction of the peak), up to 31x31: sharp lobes get a small window, wide ones
// average many pixels, which both cuts the noise and dilutes the selection bias of having
// located the peak on noisy data.
constexpr int kMinFitRadius = 3;
constexpr int kMaxFitRadius = 15;
constexpr double kCapFraction = 0.8;
constexpr int kMinFitSamples = 12;

bool ringAbove(const cv::Mat& image, int cx, int cy, int radius, double level) {
  for (int d = -radius; d <= radius; ++d) {
    const cv::Point ring[4] = {
        {cx + d, cy - radius}, {cx + d, cy + radius}, {cx - radius, cy + d}, {cx + radius, cy + d}};
    for (const cv::Point& p : ring) {
      if (p.x < 0 || p.y < 0 || p.x >= image.cols || p.y >= image.rows ||
          image.at<float>(p) < level)
        return false;
    }
  }
  return true;
}

int fitRadius(const cv::Mat& median, cv::Point peak, double peak_value) {
  int radius = kMinFitRadius;
  while (radius < kMaxFitRadius &&
         ringAbove(median, peak.x, peak.y, radius + 1, kCapFraction * peak_value))
    ++radius;
  return radius;
}

// Luminance with non-measurements zeroed, as an OpenCV view for the median filter.
cv::Mat measuredLuminance(const calibration::MergedImage& merged) {
  const FloatImage& image = merged.luminance_cd_m2;
  cv::Mat out(image.height(), image.width(), CV_32F);
  for (int y = 0; y < image.height(); ++y) {
    auto in = image.row(y);
    auto bound = merged.bound.row(y);
    float* row = out.ptr<float>(y);
    for (int x = 0; x < image.width(); ++x) {
      const float v = in[static_cast<std::size_t>(x)];
      const bool usable = bound[static_cast<std::size_t>(x)] !=
                              static_cast<std::uint8_t>(PixelBound::kUpperBound) &&
                          std::isfinite(v);
      row[x] = usable ? v : 0.0f;
    }
  }
  return out;
}

// Least-squares fit of ln L = c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y² around (cx, cy);
// returns the vertex when the surface is a cap whose top lies inside the window.
bool fitQuadraticCap(const calibration::MergedImage& merged, int cx, int cy, int radius,
                     LuminancePeak& peak) {
  const FloatImage& image = merged.luminance_cd_m2;
  cv::Mat a(0, 6, CV_64F), b(0, 1, CV_64F);
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const int x = cx + dx, y = cy + dy;
      if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) continue;
      const float v = image.at(x, y);
      if (merged.bound.at(x, y) != static_cast<std::uint8_t>(PixelBound::kMeasured) || !(v > 0))
        continue;
      double row[6] = {
          1.0, double(dx), double(dy), double(dx * dx), double(dx * dy), double(dy * dy)};
      a.push_back(cv::Mat(1, 6, CV_64F, row));
      b.push_back(std::log(static_cast<double>(v)));
    }
  }
  if (a.rows < kMinFitSamples) return false;
  cv::Mat c;
  if (!cv::solve(a, b, c, cv::DECOMP_SVD)) return false;
  const double c1 = c.at<double>(1), c2 = c.at<double>(2), c3 = c.at<double>(3),
               c4 = c.at<double>(4), c5 = c.at<double>(5);
  // Vertex: gradient zero. Hessian [[2c3, c4], [c4, 2c5]] must be negative definite.
  const double det = 4 * c3 * c5 - c4 * c4;
  if (!(c3 < 0 && det > 0)) return false;
  const double vx = (-2 * c5 * c1 + c4 * c2) / det;
  const double vy = (-2 * c3 * c2 + c4 * c1) / det;
  if (std::abs(vx) > radius || std::abs(vy) > radius) return false;
  const double ln_peak =
      c.at<double>(0) + c1 * vx + c2 * vy + c3 * vx * vx + c4 * vx * vy + c5 * vy * vy;
  peak = {std::exp(ln_peak), cx + vx, cy + vy, PeakMethod::kQuadraticFit};
  return true;
}

// A top saturated in every frame: the true maximum is only known to exceed the largest lower
// bound around it (measured neighbours of a clipped plateau may even read higher).
bool saturatedTop(const calibration::MergedImage& merged, cv::Point location, int radius,
                  LuminancePeak& peak) {
  const FloatImage& image = merged.luminance_cd_m2;
  bool saturated = false;
  for (int y = std::max(0, location.y - radius);
       y <= std::min(image.height() - 1, location.y + radius); ++y) {
    for (int x = std::max(0, location.x - radius);
         x <= std::min(image.width() - 1, location.x + radius); ++x) {
      if (merged.bound.at(x, y) != static_cast<std::uint8_t>(PixelBound::kLowerBound)) continue;
      if (!saturated || image.at(x, y) > peak.value_cd_m2)
        peak = {image.at(x, y), double(x), double(y), PeakMethod::kLowerBound};
      saturated = true;
    }
  }
  if (saturated)
    peak.value_cd_m2 =
        std::max(peak.value_cd_m2, static_cast<double>(image.at(location.x, location.y)));
  return saturated;
}

}  // namespace

const char* toString(PeakMethod method) {
  switch (method) {
    case PeakMethod::kQuadraticFit:
      return "quadratic_fit";
    case PeakMethod::kMedian3x3:
      return "median_3x3";
    case PeakMethod::kLowerBound:
      return "lower_bound";
  }
  return "unknown";
}

LuminancePeak findLuminancePeak(const calibration::MergedImage& merged) {
  if (merged.luminance_cd_m2.empty()) return {};
  cv::Mat median;
  cv::medianBlur(measuredLuminance(merged), median, 3);
  cv::Point location;
  double value = 0;
  cv::minMaxLoc(median, nullptr, &value, nullptr, &location);
  LuminancePeak peak{value, double(location.x), double(location.y), PeakMethod::kMedian3x3};
  const int radius = fitRadius(median, location, value);
  if (saturatedTop(merged, location, radius, peak)) return peak;
  fitQuadraticCap(merged, location.x, location.y, radius, peak);
  return peak;
}

}  // namespace glarecam::pipeline
