#include "pipeline/iso_contour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace glarecam::pipeline {
namespace {

// An elliptical Gaussian lobe peak * exp(-r²/2), r² = ((x - cx)/sx)² + ((y - cy)/sy)²,
// point-sampled at the integer pixel centres, on a constant background.
struct Lobe {
  double cx = 0, cy = 0;  // centre (px)
  double sx = 1, sy = 1;  // standard deviations along x and y (px)
  double peak = 1000;

  double value(double x, double y) const {
    const double u = (x - cx) / sx, v = (y - cy) / sy;
    return peak * std::exp(-(u * u + v * v) / 2);
  }
  // The level whose iso-line is the ellipse r = r_level (semi-axes r_level sx, r_level sy).
  double levelAt(double r_level) const { return peak * std::exp(-r_level * r_level / 2); }
  // Euclidean distance (first order) from (x, y) to the iso-line r = r_level: g / |grad g| for
  // g = r² - r_level², whose second-order error (d² times the curvature, ~1e-5 px for d up to
  // 0.02 px on a 5 px ellipse) is far below any tolerance used here.
  double distanceToIsoLine(double x, double y, double r_level) const {
    const double u = (x - cx) / sx, v = (y - cy) / sy;
    const double g = u * u + v * v - r_level * r_level;
    const double gx = 2 * u / sx, gy = 2 * v / sy;
    return std::abs(g) / std::hypot(gx, gy);
  }
};

FloatImage render(const Lobe& lobe, int width, int height, float background = 0.0f) {
  FloatImage image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      image.at(x, y) = static_cast<float>(lobe.value(x, y)) + background;
  return image;
}

// A rectangle [x0, x1] x [y0, y1] (inclusive) set to `value`.
void fill(FloatImage& image, int x0, int y0, int x1, int y1, float value) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) image.at(x, y) = value;
}

PixelIndex nearestPixel(double x, double y) {
  return {static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y))};
}

// The inside pixel of a contour point (slot 1 of its pixels).
PixelIndex insidePixel(const ContourPoint& p, const FloatImage& image) {
  const auto width = static_cast<std::size_t>(image.width());
  return {static_cast<int>(p.pixels[1] % width), static_cast<int>(p.pixels[1] / width)};
}

bool inImage(const FloatImage& image, int x, int y) {
  return x >= 0 && y >= 0 && x < image.width() && y < image.height();
}

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

double shoelaceArea(const RegionContour& contour) {
  double twice = 0;
  const std::size_t n = contour.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ContourPoint& a = contour.points[i];
    const ContourPoint& b = contour.points[(i + 1) % n];
    twice += a.x_px * b.y_px - b.x_px * a.y_px;
  }
  return std::abs(twice) / 2;
}

// Invariants of every contour: a closed loop whose consecutive points (last to first too)
// lie on the edges of one marching-squares cell, i.e. at most one pixel apart in x and in y,
// each point on the segment from its inside pixel along its unit step.
void expectWellFormedLoop(const RegionContour& contour, const FloatImage& image) {
  ASSERT_GE(contour.points.size(), 4u);
  const std::size_t n = contour.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const ContourPoint& p = contour.points[i];
    const ContourPoint& q = contour.points[(i + 1) % n];
    // Points are sums of integers and a fraction in [0, 1]: 1e-12 allows for rounding only.
    EXPECT_LE(std::abs(p.x_px - q.x_px), 1.0 + 1e-12) << "point " << i;
    EXPECT_LE(std::abs(p.y_px - q.y_px), 1.0 + 1e-12) << "point " << i;
    EXPECT_EQ(std::abs(p.step_x) + std::abs(p.step_y), 1) << "point " << i;
    const PixelIndex in = insidePixel(p, image);
    const double t = (p.x_px - in.x) * p.step_x + (p.y_px - in.y) * p.step_y;
    EXPECT_GE(t, -1e-12) << "point " << i;
    EXPECT_LE(t, 1.0 + 1e-12) << "point " << i;
    // The point stays on the line through its inside pixel along its step.
    EXPECT_NEAR((p.x_px - in.x) * p.step_y - (p.y_px - in.y) * p.step_x, 0.0, 1e-12);
  }
}

// The contour point crossing from `inside` along (step_x, step_y), if any.
std::optional<ContourPoint> findPoint(const RegionContour& contour, std::size_t inside, int step_x,
                                      int step_y) {
  for (const ContourPoint& p : contour.points)
    if (p.pixels[1] == inside && p.step_x == step_x && p.step_y == step_y) return p;
  return std::nullopt;
}

// The distance of a point along its step from its inside pixel.
double alongStep(const ContourPoint& p, const FloatImage& image) {
  const PixelIndex in = insidePixel(p, image);
  return (p.x_px - in.x) * p.step_x + (p.y_px - in.y) * p.step_y;
}

// Central finite differences of every observed point's position along its step with respect
// to each of its in-image pixels and to the level, against the reported derivatives.
// `relative_delta` scales each perturbation by the perturbed value (or level).
void expectDerivativesMatchFiniteDifferences(const FloatImage& image, double level, PixelIndex seed,
                                             double relative_delta) {
  const auto base = traceRegionContour(image, level, seed);
  ASSERT_TRUE(base.has_value());
  // Newton stops at |t step| < 1e-12, the positions are exact to ~1e-12 px; a perturbation
  // moving a point by ~1e-5 px leaves ~1e-7 of noise, and the O(delta²) truncation error of
  // central differences is smaller still: 1e-4 relative plus 1e-6 absolute (for derivatives
  // that are 0 or tiny) is far above both and far below any real error in a derivative.
  constexpr double kRelativeTolerance = 1e-4, kAbsoluteTolerance = 1e-6;
  int checked = 0;
  for (const ContourPoint& p : base->points) {
    if (p.on_border) continue;  // not observed: no derivatives
    const PixelIndex in = insidePixel(p, image);
    const double t0 = alongStep(p, image);
    for (std::size_t k = 0; k < 4; ++k) {
      const int x = in.x + (static_cast<int>(k) - 1) * p.step_x;
      const int y = in.y + (static_cast<int>(k) - 1) * p.step_y;
      if (!inImage(image, x, y)) {
        EXPECT_EQ(p.dt_dvalue[k], 0.0) << "slot " << k << " is outside the image";
        continue;
      }
      const float value = image.at(x, y);
      if (!std::isfinite(value)) continue;
      const double delta = relative_delta * std::max(std::abs(static_cast<double>(value)), 1.0);
      FloatImage plus = image, minus = image;
      plus.at(x, y) = static_cast<float>(value + delta);
      minus.at(x, y) = static_cast<float>(value - delta);
      // The perturbation actually applied, after rounding to float.
      const double applied = static_cast<double>(plus.at(x, y)) - minus.at(x, y);
      const auto cp = traceRegionContour(plus, level, seed);
      const auto cm = traceRegionContour(minus, level, seed);
      ASSERT_TRUE(cp && cm);
      const auto pp = findPoint(*cp, p.pixels[1], p.step_x, p.step_y);
      const auto pm = findPoint(*cm, p.pixels[1], p.step_x, p.step_y);
      ASSERT_TRUE(pp && pm) << "the perturbation changed the region";
      const double numeric = (alongStep(*pp, image) - alongStep(*pm, image)) / applied;
      EXPECT_NEAR(p.dt_dvalue[k], numeric,
                  kRelativeTolerance * std::abs(numeric) + kAbsoluteTolerance)
          << "pixel (" << x << ", " << y << ") slot " << k << " of the point at (" << p.x_px << ", "
          << p.y_px << "), t = " << t0;
      ++checked;
    }
    const double delta = relative_delta * level;
    const auto cp = traceRegionContour(image, level + delta, seed);
    const auto cm = traceRegionContour(image, level - delta, seed);
    ASSERT_TRUE(cp && cm);
    const auto pp = findPoint(*cp, p.pixels[1], p.step_x, p.step_y);
    const auto pm = findPoint(*cm, p.pixels[1], p.step_x, p.step_y);
    ASSERT_TRUE(pp && pm) << "the level perturbation changed the region";
    const double numeric = (alongStep(*pp, image) - alongStep(*pm, image)) / (2 * delta);
    EXPECT_NEAR(p.dt_dlevel, numeric, kRelativeTolerance * std::abs(numeric) + 1e-9)
        << "level derivative of the point at (" << p.x_px << ", " << p.y_px << ")";
  }
  EXPECT_GT(checked, 0);
}

TEST(IsoContour, GaussianLobeContourIsOnTheAnalyticIsoLine) {
  // Semi-axes 5.3 and 4.1 px at r = 2 (level = peak / e²), centre between pixels.
  constexpr double kRLevel = 2.0;
  const Lobe lobe{20.37, 18.71, 5.3 / kRLevel, 4.1 / kRLevel, 1000};
  const FloatImage image = render(lobe, 40, 38);
  const double level = lobe.levelAt(kRLevel);
  const auto contour = traceRegionContour(image, level, nearestPixel(lobe.cx, lobe.cy));
  ASSERT_TRUE(contour.has_value());
  expectWellFormedLoop(*contour, image);
  EXPECT_FALSE(contour->touches_border);
  // ln L of a Gaussian is exactly quadratic along any row or column, which the cubic through
  // four pixels reproduces: its crossings are exact up to the float rounding of the pixels
  // (~1e-7 px; CubicCrossingsAreExactOnAGaussianLobe holds them to 1e-5 px). The fallback to
  // linear interpolation of ln L, taken at grazing crossings where the cubic is flat, errs by
  // up to ~1e-4 px on a lobe this round (~0.01-0.03 px only on elongated lobes). 0.02 px bounds
  // both with room to spare and is still 25 times below the half pixel of a binary mask.
  constexpr double kMaxDistancePx = 0.02;
  double worst = 0;
  for (const ContourPoint& p : contour->points) {
    ASSERT_FALSE(p.on_border);
    const double d = lobe.distanceToIsoLine(p.x_px, p.y_px, kRLevel);
    worst = std::max(worst, d);
    EXPECT_LT(d, kMaxDistancePx) << "point (" << p.x_px << ", " << p.y_px << ")";
  }
  // The contour goes all the way round: every point is ~5 px from the centre.
  EXPECT_GE(contour->points.size(), 30u);
  // The pixels at or above the level are exactly the region (no holes to fill here).
  std::size_t above = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) above += image.at(x, y) >= level ? 1 : 0;
  EXPECT_EQ(contour->region_pixels, above);
  RecordProperty("worst_distance_px", format(worst));
}

TEST(IsoContour, CubicCrossingsAreExactOnAGaussianLobe) {
  // Where the cubic through four pixels is used (the pixels behind and beyond have non-zero
  // derivatives), it reproduces ln L of a Gaussian exactly, so its root is the analytic
  // crossing up to the float rounding of the pixels (6e-8 relative, i.e. 6e-8 in ln L, over a
  // slope of ln L along the step that the cubic's acceptance keeps above ~0.05 per px here:
  // ~1e-6 px) and the root finder's 1e-12. 1e-5 px is ten times that, and catches a root
  // finder that stops short (the linear estimate is ~0.02 px off).
  constexpr double kRLevel = 2.0;
  constexpr double kMaxDistancePx = 1e-5;
  for (const auto& [cx, cy] :
       {std::pair{20.37, 18.71}, std::pair{20.0, 18.0}, std::pair{19.52, 18.23},
        std::pair{20.11, 17.86}, std::pair{19.77, 18.49}}) {
    for (const auto& [ax, ay] : {std::pair{5.3, 4.1}, std::pair{3.2, 3.2}, std::pair{7.9, 4.4}}) {
      const Lobe lobe{cx, cy, ax / kRLevel, ay / kRLevel, 1000};
      const FloatImage image = render(lobe, 40, 38);
      const auto contour =
          traceRegionContour(image, lobe.levelAt(kRLevel), nearestPixel(lobe.cx, lobe.cy));
      ASSERT_TRUE(contour.has_value());
      int cubic = 0;
      for (const ContourPoint& p : contour->points) {
        if (p.dt_dvalue[0] == 0 && p.dt_dvalue[3] == 0) continue;  // linear fallback
        ++cubic;
        EXPECT_LT(lobe.distanceToIsoLine(p.x_px, p.y_px, kRLevel), kMaxDistancePx)
            << "lobe at (" << cx << ", " << cy << "), semi-axes " << ax << ", " << ay << ": point ("
            << p.x_px << ", " << p.y_px << ") step (" << p.step_x << ", " << p.step_y << ")";
      }
      // Most crossings use the cubic.
      EXPECT_GT(cubic, static_cast<int>(contour->points.size()) / 2);
    }
  }
}

TEST(IsoContour, ContourAreaBeatsBinaryMaskArea) {
  // Semi-axes ~10 px at the level, several sub-pixel centres. The contour polygon's vertices
  // lie on the ellipse, ~1 px apart: the polygon misses the circular segments between them,
  // about pi s² / 6 ~ 0.5 px² in all (s ~ 1 px), 0.2 % of the ~270 px² area, so < 0.5 %. The
  // count of pixels at or above the level quantises the boundary to whole pixels: its error
  // swings by ~ the perimeter's worth of half pixels depending on where the centre falls.
  constexpr double kRLevel = 2.0;
  constexpr double kContourTolerance = 0.005;
  double worst_contour = 0, worst_binary = 0;
  for (const auto& [cx, cy] :
       {std::pair{32.0, 31.0}, std::pair{32.5, 31.5}, std::pair{32.37, 31.21},
        std::pair{31.81, 32.46}, std::pair{32.13, 31.77}, std::pair{32.5, 32.0}}) {
    const Lobe lobe{cx, cy, 10.3 / kRLevel, 8.6 / kRLevel, 1000};
    const FloatImage image = render(lobe, 64, 64);
    const double level = lobe.levelAt(kRLevel);
    const auto contour = traceRegionContour(image, level, nearestPixel(cx, cy));
    ASSERT_TRUE(contour.has_value());
    expectWellFormedLoop(*contour, image);
    const double truth = std::numbers::pi * 10.3 * 8.6;
    const double contour_error = std::abs(shoelaceArea(*contour) / truth - 1);
    std::size_t above = 0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) above += image.at(x, y) >= level ? 1 : 0;
    const double binary_error = std::abs(static_cast<double>(above) / truth - 1);
    EXPECT_LT(contour_error, kContourTolerance) << "centre " << cx << ", " << cy;
    worst_contour = std::max(worst_contour, contour_error);
    worst_binary = std::max(worst_binary, binary_error);
  }
  // Over the centres, the binary count's worst error is well above the contour's: at least
  // 1 % and at least three times the contour's.
  EXPECT_GT(worst_binary, 0.01);
  EXPECT_GT(worst_binary, 3 * worst_contour);
  RecordProperty("worst_contour_area_error", format(worst_contour));
  RecordProperty("worst_binary_area_error", format(worst_binary));
}

TEST(IsoContour, NothingForASeedBelowTheLevelOutsideTheImageOrABadLevel) {
  FloatImage image(10, 8, 1.0f);
  fill(image, 3, 3, 5, 5, 100.0f);
  image.at(4, 4) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(traceRegionContour(image, 50, {3, 3}).has_value());
  EXPECT_FALSE(traceRegionContour(image, 50, {0, 0}).has_value());   // below the level
  EXPECT_FALSE(traceRegionContour(image, 50, {4, 4}).has_value());   // NaN seed
  EXPECT_FALSE(traceRegionContour(image, 50, {-1, 3}).has_value());  // out of the image
  EXPECT_FALSE(traceRegionContour(image, 50, {3, -1}).has_value());
  EXPECT_FALSE(traceRegionContour(image, 50, {10, 3}).has_value());
  EXPECT_FALSE(traceRegionContour(image, 50, {3, 8}).has_value());
  EXPECT_FALSE(traceRegionContour(image, 0, {3, 3}).has_value());  // level <= 0
  EXPECT_FALSE(traceRegionContour(image, -5, {3, 3}).has_value());
  EXPECT_FALSE(traceRegionContour(image, std::nan(""), {3, 3}).has_value());
  // A seed exactly at the level is at or above it.
  EXPECT_TRUE(traceRegionContour(image, 100, {3, 3}).has_value());
}

TEST(IsoContour, HoleIsFilledWithoutAnInnerLoop) {
  FloatImage image(21, 21, 1.0f);
  fill(image, 6, 6, 14, 14, 100.0f);  // 9 x 9, centre (10, 10)
  image.at(10, 10) = 1.0f;            // a dip below the level
  image.at(8, 12) = 2.0f;             // and another one
  const auto contour = traceRegionContour(image, 50, {6, 6});
  ASSERT_TRUE(contour.has_value());
  expectWellFormedLoop(*contour, image);
  EXPECT_EQ(contour->region_pixels, 81u);  // the holes count
  EXPECT_FALSE(contour->touches_border);
  // One crossing per boundary edge of the square: 4 x 9, all on the outer boundary, between
  // the outermost ring (Chebyshev distance 4 from the centre) and the background (5).
  EXPECT_EQ(contour->points.size(), 36u);
  for (const ContourPoint& p : contour->points) {
    const double chebyshev = std::max(std::abs(p.x_px - 10), std::abs(p.y_px - 10));
    EXPECT_GT(chebyshev, 4.0) << p.x_px << ", " << p.y_px;
    EXPECT_LT(chebyshev, 5.0) << p.x_px << ", " << p.y_px;
  }
}

TEST(IsoContour, HoleFilledWhenSeededNextToIt) {
  // A ring whose hole is large: the contour is still the outer boundary only.
  FloatImage image(20, 20, 1.0f);
  fill(image, 4, 4, 15, 15, 100.0f);
  fill(image, 7, 7, 12, 12, 1.0f);
  const auto contour = traceRegionContour(image, 50, {6, 10});
  ASSERT_TRUE(contour.has_value());
  expectWellFormedLoop(*contour, image);
  EXPECT_EQ(contour->region_pixels, 144u);
  EXPECT_EQ(contour->points.size(), 48u);
  for (const ContourPoint& p : contour->points) {
    const double chebyshev = std::max(std::abs(p.x_px - 9.5), std::abs(p.y_px - 9.5));
    EXPECT_GT(chebyshev, 5.5) << p.x_px << ", " << p.y_px;
  }
}

TEST(IsoContour, DiagonalNeighboursAreOneRegion) {
  // Two 3 x 3 squares touching at one corner, both ways round (both saddle configurations).
  for (const bool anti_diagonal : {false, true}) {
    FloatImage image(20, 20, 1.0f);
    fill(image, 5, 5, 7, 7, 100.0f);
    if (anti_diagonal) {
      fill(image, 2, 8, 4, 10, 100.0f);
    } else {
      fill(image, 8, 8, 10, 10, 100.0f);
    }
    const auto contour = traceRegionContour(image, 50, {6, 6});
    ASSERT_TRUE(contour.has_value()) << anti_diagonal;
    expectWellFormedLoop(*contour, image);
    EXPECT_EQ(contour->region_pixels, 18u) << anti_diagonal;
    // One loop round both squares: every boundary edge of both, 12 + 12.
    EXPECT_EQ(contour->points.size(), 24u) << anti_diagonal;
    int near_second = 0;
    for (const ContourPoint& p : contour->points)
      near_second += insidePixel(p, image).y > 7 ? 1 : 0;
    EXPECT_EQ(near_second, 12) << anti_diagonal;
    // Seeded in the other square: the same region.
    const auto other =
        traceRegionContour(image, 50, anti_diagonal ? PixelIndex{3, 9} : PixelIndex{9, 9});
    ASSERT_TRUE(other.has_value());
    EXPECT_EQ(other->region_pixels, 18u);
    EXPECT_EQ(other->points.size(), 24u);
    EXPECT_EQ(countRegions(image, 50, 1), 1) << anti_diagonal;
  }
}

TEST(IsoContour, OtherRegionsAreIgnored) {
  FloatImage image(20, 12, 1.0f);
  fill(image, 2, 2, 5, 5, 100.0f);
  fill(image, 7, 2, 9, 4, 100.0f);  // one background column apart
  const auto contour = traceRegionContour(image, 50, {3, 3});
  ASSERT_TRUE(contour.has_value());
  EXPECT_EQ(contour->region_pixels, 16u);
  EXPECT_EQ(contour->points.size(), 16u);
  for (const ContourPoint& p : contour->points) EXPECT_LT(p.x_px, 6.0);
}

TEST(IsoContour, RegionAtTheImageBorder) {
  FloatImage image(20, 20, 1.0f);
  fill(image, 0, 5, 3, 8, 100.0f);  // 4 x 4 against the left edge
  const auto contour = traceRegionContour(image, 50, {1, 6});
  ASSERT_TRUE(contour.has_value());
  expectWellFormedLoop(*contour, image);
  EXPECT_TRUE(contour->touches_border);
  EXPECT_EQ(contour->region_pixels, 16u);
  EXPECT_EQ(contour->points.size(), 16u);
  int on_border = 0;
  for (const ContourPoint& p : contour->points) {
    const PixelIndex in = insidePixel(p, image);
    const bool leaves = !inImage(image, in.x + p.step_x, in.y + p.step_y);
    EXPECT_EQ(p.on_border, leaves) << p.x_px << ", " << p.y_px;
    if (!p.on_border) continue;
    ++on_border;
    EXPECT_EQ(in.x, 0);
    EXPECT_EQ(p.step_x, -1);
    // Not observed: placed half a pixel out, with no derivatives.
    EXPECT_DOUBLE_EQ(p.x_px, -0.5);
    EXPECT_EQ(p.dt_dlevel, 0.0);
    for (const double d : p.dt_dvalue) EXPECT_EQ(d, 0.0);
  }
  EXPECT_EQ(on_border, 4);
}

TEST(IsoContour, RegionInACornerTouchesTwoBorders) {
  FloatImage image(12, 10, 1.0f);
  fill(image, 9, 7, 11, 9, 100.0f);  // bottom-right corner, 3 x 3
  const auto contour = traceRegionContour(image, 50, {11, 9});
  ASSERT_TRUE(contour.has_value());
  expectWellFormedLoop(*contour, image);
  EXPECT_TRUE(contour->touches_border);
  EXPECT_EQ(contour->points.size(), 12u);
  int on_border = 0;
  for (const ContourPoint& p : contour->points) {
    const PixelIndex in = insidePixel(p, image);
    EXPECT_EQ(p.on_border, !inImage(image, in.x + p.step_x, in.y + p.step_y));
    on_border += p.on_border ? 1 : 0;
  }
  EXPECT_EQ(on_border, 6);
}

TEST(IsoContour, NanNextToTheRegionGivesFinitePoints) {
  constexpr double kRLevel = 2.0;
  const Lobe lobe{12.4, 11.7, 4.0 / kRLevel, 3.5 / kRLevel, 500};
  FloatImage image = render(lobe, 26, 24, 1.0f);
  const double level = lobe.levelAt(kRLevel) + 1.0;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // NaN as an outside pixel (right of the lobe), as the pixel beyond an outside one (left),
  // as the pixel behind an inside one (bottom), inside the region (a hole), and an infinity as
  // an outside pixel (below).
  image.at(17, 12) = nan;
  image.at(7, 12) = nan;
  image.at(13, 14) = nan;
  image.at(12, 12) = nan;
  image.at(12, 16) = std::numeric_limits<float>::infinity();
  const auto contour = traceRegionContour(image, level, {11, 11});
  ASSERT_TRUE(contour.has_value());
  expectWellFormedLoop(*contour, image);
  EXPECT_FALSE(contour->touches_border);
  for (const ContourPoint& p : contour->points) {
    EXPECT_TRUE(std::isfinite(p.x_px) && std::isfinite(p.y_px)) << p.x_px << ", " << p.y_px;
    EXPECT_TRUE(std::isfinite(p.dt_dlevel));
    for (const double d : p.dt_dvalue) EXPECT_TRUE(std::isfinite(d));
  }
  // The NaN holes count as part of the region, the infinity does not.
  std::size_t above = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      above += std::isfinite(image.at(x, y)) && image.at(x, y) >= level ? 1 : 0;
  EXPECT_EQ(contour->region_pixels, above + 2);
}

TEST(IsoContour, DerivativesMatchFiniteDifferencesOnAGaussianLobe) {
  // Cubic interpolation of ln L nearly everywhere.
  constexpr double kRLevel = 2.0;
  const Lobe lobe{15.37, 14.71, 5.3 / kRLevel, 4.1 / kRLevel, 1000};
  const FloatImage image = render(lobe, 32, 30, 2.0f);
  expectDerivativesMatchFiniteDifferences(image, lobe.levelAt(kRLevel) + 2.0, {15, 15}, 1e-4);
}

TEST(IsoContour, DerivativesMatchFiniteDifferencesNearTheImageEdge) {
  // The lobe's contour passes between the last two columns and rows: there the pixel beyond
  // is missing and ln L is interpolated linearly.
  constexpr double kRLevel = 2.0;
  const Lobe lobe{7.3, 6.6, 4.6 / kRLevel, 4.2 / kRLevel, 1000};
  const FloatImage image = render(lobe, 13, 12, 1.0f);
  const double level = lobe.levelAt(kRLevel) + 1.0;
  const auto contour = traceRegionContour(image, level, {7, 7});
  ASSERT_TRUE(contour.has_value());
  ASSERT_FALSE(contour->touches_border);
  int linear = 0;
  for (const ContourPoint& p : contour->points) {
    linear += p.dt_dvalue[0] == 0 && p.dt_dvalue[3] == 0 ? 1 : 0;
  }
  EXPECT_GT(linear, 0) << "no point uses the linear fallback";
  expectDerivativesMatchFiniteDifferences(image, level, {7, 7}, 1e-4);
}

TEST(IsoContour, DerivativesMatchFiniteDifferencesWithANonPositiveBackground) {
  // Outside values <= 0: L itself is interpolated linearly.
  FloatImage image(12, 12, -3.0f);
  for (int y = 3; y <= 8; ++y)
    for (int x = 3; x <= 8; ++x) image.at(x, y) = static_cast<float>(60 + 7 * x + 3 * y);
  const auto contour = traceRegionContour(image, 50, {5, 5});
  ASSERT_TRUE(contour.has_value());
  for (const ContourPoint& p : contour->points) {
    // t = (inside - level) / (inside - outside)
    const PixelIndex in = insidePixel(p, image);
    const double a = image.at(in.x, in.y);
    // Exact up to double rounding.
    EXPECT_NEAR(alongStep(p, image), (a - 50) / (a + 3), 1e-12);
  }
  expectDerivativesMatchFiniteDifferences(image, 50, {5, 5}, 1e-4);
}

TEST(IsoContour, CountRegions) {
  FloatImage image(30, 20, 1.0f);
  EXPECT_EQ(countRegions(image, 50, 1), 0);  // nothing reaches the level
  EXPECT_EQ(countRegions(image, 50, 0), 0);
  fill(image, 2, 2, 6, 6, 100.0f);
  fill(image, 15, 10, 18, 14, 100.0f);
  EXPECT_EQ(countRegions(image, 50, 9), 2);  // two separated blobs
  EXPECT_EQ(countRegions(image, 200, 1), 0);
  image.at(25, 3) = 1000.0f;                 // a single hot pixel
  EXPECT_EQ(countRegions(image, 50, 9), 2);  // too small to count
  EXPECT_EQ(countRegions(image, 50, 1), 3);
  // Only the hot pixel reaches 500, and it is a single pixel.
  EXPECT_EQ(countRegions(image, 500, 9), 0);
  EXPECT_EQ(countRegions(image, 500, 1), 1);
  // A blob of exactly min_pixels counts (3 x 3 = 9).
  FloatImage small(10, 10, 1.0f);
  fill(small, 3, 3, 5, 5, 100.0f);
  EXPECT_EQ(countRegions(small, 50, 9), 1);
  EXPECT_EQ(countRegions(small, 50, 10), 0);
  // NaN pixels never reach the level.
  small.at(0, 0) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(countRegions(small, 50, 1), 1);
}

}  // namespace
}  // namespace glarecam::pipeline
