#include "pipeline/luminance_peak.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "core/neighbourhood.h"
#include "core/parallel.h"

namespace glarecam::pipeline {
namespace {

using calibration::PixelBound;

// The fit window's half-widths grow from 2 px while the lobe stays on its cap (above
// kCapFraction of the peak) along the row and the column through the peak, up to 64 px: sharp
// lobes get a small window (5x5 suits a lobe 4 px wide at half maximum; a wider minimum would
// reach where the background bends ln L off a quadratic), wide or elongated ones average many
// pixels along each axis, which cuts the noise and dilutes the selection bias of having
// located the peak on noisy data. The cap is wide enough for a lobe 300 px across at half
// maximum (a 10° field of view at 1224 px): at 15 px, where ln L falls by only 0.6 % across the
// window, noise of 1.5 % a pixel often bent the fitted cap upward, and the maximum fell back to
// the noisy 3x3 value (issue 23: Lmax scattered twice its uncertainty and read high).
// kCapFraction 0.9, not 0.8: glass lobes are sharper at their tip than a Gaussian (a GGX lobe
// under the sun's disc: surface/, capture/sim/surface_scene.h), and a quadratic in ln L fitted
// down to 80 % read them 0.5 % low (6σ over 8 seeds); to 90 %, 0.05 %, its noise 1.5× larger and
// still matched by the stated σ. A Gaussian lobe reads true either way.
constexpr int kMinFitRadius = 2;
constexpr int kMaxFitRadius = 64;
constexpr double kCapFraction = 0.9;
constexpr int kMinFitSamples = 12;
// A fit whose ln L residuals exceed this RMS (about 5 % in L, several times a good merge's
// per-pixel noise) is no cap of a smooth lobe: a glint, a plateau edge or clutter.
constexpr double kMaxFitResidualRms = 0.05;

bool isBound(const calibration::MergedImage& merged, int x, int y, PixelBound bound) {
  return merged.bound.at(x, y) == static_cast<std::uint8_t>(bound);
}

// A pixel that may be bright: a measurement or a lower bound (upper bounds are not bright, and a
// masked hot pixel's value is only its neighbours').
bool mayBeBright(std::uint8_t flag) {
  return flag == std::uint8_t(PixelBound::kMeasured) ||
         flag == std::uint8_t(PixelBound::kLowerBound);
}

// Second-largest of a pixel's 3x3 neighbourhood (outside the image counts as 0), over the
// pixels that may be bright.
float secondLargestAt(const calibration::MergedImage& merged, int x, int y) {
  const FloatImage& image = merged.luminance_cd_m2;
  float first = 0, second = 0;
  forEach3x3(image.width(), image.height(), x, y, [&](int xx, int yy) {
    const float v = image.at(xx, yy);
    if (!(v > second) || !mayBeBright(merged.bound.at(xx, yy))) return;
    second = std::min(v, first);
    first = std::max(v, first);
  });
  return second;
}

struct Located {
  std::size_t index = 0;
  float value = 0;
  bool beats(const Located& other) const {  // larger; the first in raster order on ties
    return value > other.value || (value == other.value && index < other.index);
  }
};

// Each row's best value of secondLargestAt, computed at every pixel (`everywhere`) or only at
// the row's brightest pixel that may be bright. On all cores.
std::vector<Located> rowBests(const calibration::MergedImage& merged, bool everywhere) {
  const FloatImage& image = merged.luminance_cd_m2;
  const auto width = static_cast<std::size_t>(image.width());
  std::vector<Located> bests(static_cast<std::size_t>(image.height()));
  parallelRows(image.height(), availableThreads(), [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      const std::size_t first = static_cast<std::size_t>(y) * width;
      Located best{first, 0};
      const auto row = image.row(y);
      const auto bound = merged.bound.row(y);
      for (std::size_t x = 0; x < width; ++x) {
        if (everywhere) {
          const Located here{first + x, secondLargestAt(merged, static_cast<int>(x), y)};
          if (here.beats(best)) best = here;
        } else if (row[x] > best.value && mayBeBright(bound[x])) {
          best = {first + x, row[x]};
        }
      }
      if (!everywhere)
        best.value = secondLargestAt(merged, static_cast<int>(best.index - first), y);
      bests[static_cast<std::size_t>(y)] = best;
    }
  });
  return bests;
}

Located bestOf(const std::vector<Located>& candidates) {
  Located best;
  for (const Located& c : candidates)
    if (c.beats(best)) best = c;
  return best;
}

// Beyond this share of the image, searching around bright pixels costs more than computing the
// statistic everywhere (an image of hot pixels on a dark field).
constexpr std::size_t kMaxSearchShare = 8;

// The maximum of secondLargestAt over the image, without computing it everywhere. Start from
// its best value t at the rows' brightest pixels; it can only exceed t where two pixels of a
// neighbourhood exceed t, so only the neighbourhoods of pixels brighter than t are searched
// (the lobe's top, not 5 MP).
Located locatePeak(const calibration::MergedImage& merged) {
  const FloatImage& image = merged.luminance_cd_m2;
  const int width = image.width(), height = image.height();
  Located best = bestOf(rowBests(merged, false));
  std::vector<std::vector<std::size_t>> bright(static_cast<std::size_t>(height));
  parallelRows(height, availableThreads(), [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      const auto row = image.row(y);
      for (std::size_t x = 0; x < row.size(); ++x)
        if (row[x] > best.value) bright[static_cast<std::size_t>(y)].push_back(x);
    }
  });
  std::vector<std::size_t> candidates;
  for (int y = 0; y < height; ++y) {
    for (const std::size_t bx : bright[static_cast<std::size_t>(y)]) {
      forEach3x3(width, height, static_cast<int>(bx), y, [&](int xx, int yy) {
        candidates.push_back(static_cast<std::size_t>(yy) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(xx));
      });
    }
    if (candidates.size() > image.pixelCount() / kMaxSearchShare)
      return bestOf(rowBests(merged, true));
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (const std::size_t index : candidates) {
    const int x = static_cast<int>(index % static_cast<std::size_t>(width));
    const int y = static_cast<int>(index / static_cast<std::size_t>(width));
    const Located here{index, secondLargestAt(merged, x, y)};
    if (here.beats(best)) best = here;
  }
  return best;
}

// How far along one axis the located values stay above `level`, within the radius limits.
int capRadius(const calibration::MergedImage& merged, int x, int y, int dx, int dy, double level) {
  const FloatImage& image = merged.luminance_cd_m2;
  int radius = kMinFitRadius;
  while (radius < kMaxFitRadius) {
    const int next = radius + 1;
    const int x1 = x - next * dx, y1 = y - next * dy, x2 = x + next * dx, y2 = y + next * dy;
    const bool inside = x1 >= 0 && y1 >= 0 && x2 < image.width() && y2 < image.height();
    if (!inside || secondLargestAt(merged, x1, y1) < level ||
        secondLargestAt(merged, x2, y2) < level)
      break;
    radius = next;
  }
  return radius;
}

struct FitWindow {
  int cx, cy, rx, ry;
};

// Least-squares fit of ln L = c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y² over the window;
// returns the vertex when the surface fits the data and is a cap whose top lies inside.
bool fitQuadraticCap(const calibration::MergedImage& merged, const FitWindow& w,
                     LuminancePeak& peak) {
  const FloatImage& image = merged.luminance_cd_m2;
  cv::Mat a(0, 6, CV_64F), b(0, 1, CV_64F);
  std::vector<double> variances;  // of each sample's ln L: its relative uncertainty squared
  for (int dy = -w.ry; dy <= w.ry; ++dy) {
    for (int dx = -w.rx; dx <= w.rx; ++dx) {
      const int x = w.cx + dx, y = w.cy + dy;
      if (x < 0 || y < 0 || x >= image.width() || y >= image.height()) continue;
      const float v = image.at(x, y);
      if (!isBound(merged, x, y, PixelBound::kMeasured) || !(v > 0)) continue;
      double row[6] = {
          1.0, double(dx), double(dy), double(dx * dx), double(dx * dy), double(dy * dy)};
      // ln of a noisy value falls short of ln of the value by u²/2 on average (u its relative
      // uncertainty): added back, the fitted top is not biased low by 1e-4 at 1.5 % noise.
      const double u2 = std::pow(static_cast<double>(merged.relative_uncertainty.at(x, y)), 2);
      a.push_back(cv::Mat(1, 6, CV_64F, row));
      b.push_back(std::log(static_cast<double>(v)) + (std::isfinite(u2) ? u2 / 2 : 0.0));
      variances.push_back(u2);
    }
  }
  if (a.rows < kMinFitSamples) return false;
  cv::Mat c;
  if (!cv::solve(a, b, c, cv::DECOMP_SVD)) return false;
  if (cv::norm(a * c - b) / std::sqrt(static_cast<double>(a.rows)) > kMaxFitResidualRms)
    return false;
  const double c1 = c.at<double>(1), c2 = c.at<double>(2), c3 = c.at<double>(3),
               c4 = c.at<double>(4), c5 = c.at<double>(5);
  // Vertex: gradient zero. Hessian [[2c3, c4], [c4, 2c5]] must be negative definite.
  const double det = 4 * c3 * c5 - c4 * c4;
  if (!(c3 < 0 && det > 0)) return false;
  const double vx = (-2 * c5 * c1 + c4 * c2) / det;
  const double vy = (-2 * c3 * c2 + c4 * c1) / det;
  if (std::abs(vx) > w.rx || std::abs(vy) > w.ry) return false;
  const cv::Mat at_vertex = (cv::Mat_<double>(6, 1) << 1, vx, vy, vx * vx, vx * vy, vy * vy);
  const double ln_peak = at_vertex.dot(c);
  // Var(ln peak) = g^T (A^T A)^-1 A^T V A (A^T A)^-1 g, V the samples' own variances (the merge's
  // noise model): the estimate is a fixed linear combination h = A (A^T A)^-1 g of the samples'
  // ln L, whose variance is sum h_i² V_i. (The residuals' scatter would count the lobe's departure
  // from the quadratic as noise too: twice the scatter over noise seeds, issue 23.) The vertex's
  // own shift is second order: the surface's gradient vanishes there.
  const cv::Mat h = a * ((a.t() * a).inv(cv::DECOMP_SVD) * at_vertex);
  double variance = 0;
  bool noise_known = true;
  for (int i = 0; i < h.rows; ++i) {
    noise_known = noise_known && std::isfinite(variances[static_cast<std::size_t>(i)]);
    variance += std::pow(h.at<double>(i), 2) * variances[static_cast<std::size_t>(i)];
  }
  if (!noise_known) {  // a sample without a noise figure: the residuals' scatter, as before
    const double residual_variance = std::pow(cv::norm(a * c - b), 2) / (a.rows - a.cols);
    variance = residual_variance *
               cv::Mat(at_vertex.t() * (a.t() * a).inv(cv::DECOMP_SVD) * at_vertex).at<double>(0);
  }
  peak = {std::exp(ln_peak), w.cx + vx, w.cy + vy, std::sqrt(variance), PeakMethod::kQuadraticFit};
  return true;
}

// The centroid of the saturated plateau (8-connected lower-bound pixels) next to (cx, cy): where
// the clipped top is, rather than the plateau's first pixel in raster order.
std::pair<double, double> clippedCentroid(const calibration::MergedImage& merged, int cx, int cy) {
  const int width = merged.bound.width(), height = merged.bound.height();
  const auto clipped = [&](int x, int y) { return isBound(merged, x, y, PixelBound::kLowerBound); };
  ByteImage seen(width, height);
  double sum_x = 0, sum_y = 0, count = 0;
  forEach3x3(width, height, cx, cy, [&](int x, int y) {
    if (!clipped(x, y)) return;
    count += static_cast<double>(floodFill8(seen, x, y, clipped, [&](int px, int py) {
      sum_x += px;
      sum_y += py;
    }));
  });
  return {sum_x / count, sum_y / count};
}

// A top saturated in every frame: at least two lower-bound pixels in the 3x3 neighbourhood of
// the located top (one alone, a stuck pixel, is an outlier like any other). The true maximum
// is then only known to exceed the larger of the located value and those bounds' second
// largest (measured neighbours of a clipped plateau may even read higher).
bool saturatedTop(const calibration::MergedImage& merged, int cx, int cy, LuminancePeak& peak) {
  const FloatImage& image = merged.luminance_cd_m2;
  float first = 0, second = 0;
  int clipped = 0;
  forEach3x3(image.width(), image.height(), cx, cy, [&](int x, int y) {
    if (!isBound(merged, x, y, PixelBound::kLowerBound)) return;
    ++clipped;
    const float v = image.at(x, y);
    second = std::max(second, std::min(v, first));
    first = std::max(first, v);
  });
  if (clipped < 2) return false;
  const auto centre = clippedCentroid(merged, cx, cy);
  peak = {std::max(static_cast<double>(second), peak.value_cd_m2), centre.first, centre.second,
          std::nan(""), PeakMethod::kLowerBound};
  return true;
}

// An image under-exposed in every pixel: its maximum is at most the largest upper bound.
// Masked hot pixels and values that are not numbers (a masked cluster) do not count.
LuminancePeak darkImagePeak(const calibration::MergedImage& merged) {
  const FloatImage& image = merged.luminance_cd_m2;
  std::size_t index = 0;
  float top = -std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    const float v = image.data()[i];
    if (merged.bound.data()[i] == std::uint8_t(PixelBound::kMasked) || !std::isfinite(v)) continue;
    if (v > top) {
      top = v;
      index = i;
    }
  }
  if (!std::isfinite(top)) top = 0;  // every pixel masked: nothing to bound
  const auto width = static_cast<std::size_t>(image.width());
  return {top, double(index % width), double(index / width), std::nan(""), PeakMethod::kUpperBound};
}

}  // namespace

const char* toString(PeakMethod method) {
  switch (method) {
    case PeakMethod::kQuadraticFit:
      return "quadratic_fit";
    case PeakMethod::kNeighbourhood3x3:
      return "neighbourhood_3x3";
    case PeakMethod::kLowerBound:
      return "lower_bound";
    case PeakMethod::kUpperBound:
      return "upper_bound";
  }
  return "unknown";
}

std::optional<PeakMethod> peakMethodFromString(std::string_view text) {
  for (PeakMethod method : {PeakMethod::kQuadraticFit, PeakMethod::kNeighbourhood3x3,
                            PeakMethod::kLowerBound, PeakMethod::kUpperBound}) {
    if (text == toString(method)) return method;
  }
  return std::nullopt;
}

LocatedPeak locateLuminancePeak(const calibration::MergedImage& merged) {
  if (merged.luminance_cd_m2.empty()) return {};
  const Located top = locatePeak(merged);
  const auto width = static_cast<std::size_t>(merged.luminance_cd_m2.width());
  return {static_cast<int>(top.index % width), static_cast<int>(top.index / width), top.value};
}

LuminancePeak findLuminancePeak(const calibration::MergedImage& merged) {
  if (merged.luminance_cd_m2.empty()) return {};
  const LocatedPeak top = locateLuminancePeak(merged);
  if (!(top.value > 0)) return darkImagePeak(merged);
  const int cx = top.x, cy = top.y;
  const double level = kCapFraction * top.value;
  const FitWindow window{cx, cy, capRadius(merged, cx, cy, 1, 0, level),
                         capRadius(merged, cx, cy, 0, 1, level)};
  LuminancePeak peak{top.value, double(cx), double(cy), merged.relative_uncertainty.at(cx, cy),
                     PeakMethod::kNeighbourhood3x3};
  if (saturatedTop(merged, cx, cy, peak)) return peak;
  fitQuadraticCap(merged, window, peak);
  return peak;
}

}  // namespace glarecam::pipeline
