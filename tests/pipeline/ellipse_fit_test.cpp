#include "pipeline/ellipse_fit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/angles.h"

namespace glarecam::pipeline {
namespace {

constexpr double kPi = std::numbers::pi;

Ellipse makeEllipse(double cx, double cy, double a, double b, double angle_rad) {
  Ellipse e;
  e.centre = {cx, cy};
  e.semi_major = a;
  e.semi_minor = b;
  e.angle_rad = angle_rad;
  return e;
}

// n points at evenly spaced parameters over [t0, t0 + span).
std::vector<Point2> sample(const Ellipse& e, int n, double t0 = 0.3, double span = 2 * kPi) {
  std::vector<Point2> points;
  for (int i = 0; i < n; ++i) points.push_back(e.pointAt(t0 + span * i / n));
  return points;
}

// Difference of two axis orientations modulo a half turn, in [0, pi/2].
double orientationDifference(double a, double b) {
  const double d = std::abs(std::remainder(a - b, kPi));
  return d;
}

void expectSameEllipse(const Ellipse& fitted, const Ellipse& truth, double relative,
                       const char* what) {
  const double scale = truth.semi_major;
  EXPECT_NEAR(fitted.centre.x, truth.centre.x, relative * scale) << what;
  EXPECT_NEAR(fitted.centre.y, truth.centre.y, relative * scale) << what;
  EXPECT_NEAR(fitted.semi_major, truth.semi_major, relative * truth.semi_major) << what;
  EXPECT_NEAR(fitted.semi_minor, truth.semi_minor, relative * truth.semi_minor) << what;
  if (truth.semi_major != truth.semi_minor) {  // a circle has no orientation
    // The orientation is determined to ~relative * a / (a - b) rad.
    EXPECT_LE(orientationDifference(fitted.angle_rad, truth.angle_rad),
              relative * truth.semi_major / (truth.semi_major - truth.semi_minor))
        << what << ": " << fitted.angle_rad << " vs " << truth.angle_rad;
  }
  EXPECT_GT(fitted.angle_rad, -kPi / 2) << what;
  EXPECT_LE(fitted.angle_rad, kPi / 2) << what;
  EXPECT_GE(fitted.semi_major, fitted.semi_minor) << what;
}

// Implicit value ((u/a)² + (v/b)² - 1) of a point in the ellipse's frame: < 0 inside.
double implicitValue(const Ellipse& e, const Point2& p) {
  const double c = std::cos(e.angle_rad), s = std::sin(e.angle_rad);
  const double dx = p.x - e.centre.x, dy = p.y - e.centre.y;
  const double u = (c * dx + s * dy) / e.semi_major, v = (-s * dx + c * dy) / e.semi_minor;
  return u * u + v * v - 1;
}

struct Case {
  const char* name;
  Ellipse truth;
};

std::vector<Case> exactCases() {
  return {{"0 deg", makeEllipse(12.3, -4.7, 20, 12, 0)},
          {"30 deg", makeEllipse(-3.1, 7.9, 25, 9, radians(30))},
          {"89 deg", makeEllipse(100.25, 80.5, 18, 11, radians(89))},
          {"-60 deg", makeEllipse(0.4, -0.2, 7, 3.5, radians(-60))},
          {"90 deg", makeEllipse(5, 5, 16, 10, kPi / 2)},
          {"elongated", makeEllipse(640, 512, 40, 4, radians(12))},
          {"circle", makeEllipse(31.7, 28.2, 15, 15, 0)}};
}

TEST(EllipseFit, RecoversExactEllipses) {
  // Exact points: both fits should return the ellipse to rounding error, which for these
  // well-conditioned full ellipses is ~1e-13 relative; 1e-9 leaves room for the Eigen solvers.
  constexpr double kRelative = 1e-9;
  for (const Case& c : exactCases()) {
    const std::vector<Point2> points = sample(c.truth, 40);
    // The direct fit alone: the same curve (whatever it calls its axes, see
    // DirectFitReportsTheMajorAxis).
    const auto direct = fitEllipseDirect(points);
    ASSERT_TRUE(direct.has_value()) << c.name;
    EXPECT_NEAR(direct->centre.x, c.truth.centre.x, kRelative * c.truth.semi_major) << c.name;
    EXPECT_NEAR(direct->centre.y, c.truth.centre.y, kRelative * c.truth.semi_major) << c.name;
    EXPECT_NEAR(std::max(direct->semi_major, direct->semi_minor), c.truth.semi_major,
                kRelative * c.truth.semi_major)
        << c.name;
    EXPECT_NEAR(std::min(direct->semi_major, direct->semi_minor), c.truth.semi_minor,
                kRelative * c.truth.semi_major)
        << c.name;
    for (const Point2& p : points) EXPECT_NEAR(implicitValue(*direct, p), 0.0, 1e-8) << c.name;
    // The geometric fit, everything.
    const auto fit = fitEllipse(points);
    ASSERT_TRUE(fit.has_value()) << c.name;
    expectSameEllipse(fit->ellipse, c.truth, kRelative, c.name);
    // Exact points: no residual (rounding only, relative to the size).
    EXPECT_NEAR(fit->rms_residual, 0.0, 1e-9 * c.truth.semi_major) << c.name;
    ASSERT_EQ(fit->residuals.size(), points.size());
    for (const double r : fit->residuals) EXPECT_NEAR(r, 0.0, 1e-9 * c.truth.semi_major);
    ASSERT_EQ(fit->normals.size(), points.size());
    ASSERT_EQ(fit->axis_sensitivity.size(), points.size());
  }
}

TEST(EllipseFit, DirectFitReportsTheMajorAxis) {
  // fitEllipseDirect returns an Ellipse, whose contract is semi_major >= semi_minor and
  // angle_rad the orientation of the major axis in (-pi/2, pi/2]. Exact points: rounding only.
  constexpr double kRelative = 1e-9;
  for (const Case& c : exactCases()) {
    const auto direct = fitEllipseDirect(sample(c.truth, 40));
    ASSERT_TRUE(direct.has_value()) << c.name;
    expectSameEllipse(*direct, c.truth, kRelative, c.name);
  }
}

TEST(EllipseFit, AngleAtTheEndsOfItsRange) {
  // The orientation is reported in (-pi/2, pi/2]: a major axis along y is +pi/2, and a
  // true angle outside the range (or a fit whose first axis is the minor one) is wrapped.
  // Rounding errors only: 1e-9 rad.
  constexpr double kTolerance = 1e-9;
  const auto vertical = fitEllipse(sample(makeEllipse(0, 0, 10, 20, 0), 30));  // b > a
  ASSERT_TRUE(vertical.has_value());
  EXPECT_NEAR(vertical->ellipse.semi_major, 20, kTolerance * 20);
  EXPECT_NEAR(vertical->ellipse.semi_minor, 10, kTolerance * 10);
  EXPECT_LE(orientationDifference(vertical->ellipse.angle_rad, kPi / 2), kTolerance);
  EXPECT_GT(vertical->ellipse.angle_rad, -kPi / 2);
  EXPECT_LE(vertical->ellipse.angle_rad, kPi / 2);
  for (const double angle_deg : {-179.0, -120.0, -91.0, 91.0, 135.0, 179.5, 270.0}) {
    const auto fit = fitEllipse(sample(makeEllipse(3, -2, 14, 6, radians(angle_deg)), 30));
    ASSERT_TRUE(fit.has_value()) << angle_deg;
    EXPECT_GT(fit->ellipse.angle_rad, -kPi / 2) << angle_deg;
    EXPECT_LE(fit->ellipse.angle_rad, kPi / 2) << angle_deg;
    EXPECT_LE(orientationDifference(fit->ellipse.angle_rad, radians(angle_deg)), kTolerance)
        << angle_deg;
  }
}

TEST(EllipseFit, RandomEllipsesKeepTheConventions) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> angle(-kPi, kPi), axis(2, 50), centre(-100, 100);
  for (int trial = 0; trial < 50; ++trial) {
    const double a = axis(rng), b = axis(rng);  // either may be the larger
    if (std::abs(a - b) < 0.5) continue;        // the orientation of a near-circle is fragile
    const Ellipse truth = makeEllipse(centre(rng), centre(rng), a, b, angle(rng));
    const auto fit = fitEllipse(sample(truth, 24));
    ASSERT_TRUE(fit.has_value()) << trial;
    const Ellipse& e = fit->ellipse;
    EXPECT_GT(e.angle_rad, -kPi / 2) << trial;
    EXPECT_LE(e.angle_rad, kPi / 2) << trial;
    EXPECT_GE(e.semi_major, e.semi_minor) << trial;
    // Same ellipse whichever axis was given first (rounding only: 1e-9 relative).
    EXPECT_NEAR(e.semi_major, std::max(a, b), 1e-9 * std::max(a, b)) << trial;
    EXPECT_NEAR(e.semi_minor, std::min(a, b), 1e-9 * std::max(a, b)) << trial;
    for (const Point2& p : sample(truth, 7, 1.1)) EXPECT_NEAR(implicitValue(e, p), 0.0, 1e-8);
  }
}

TEST(EllipseFit, PartialArcStillRecoversTheEllipse) {
  // 120° of the arc, 30 points. Exact points still determine the conic exactly, but a short
  // arc conditions the fit worse (the far side is extrapolated): allow 1e-7 relative, which is
  // still rounding error amplified by the conditioning, not a fitting error.
  constexpr double kRelative = 1e-7;
  for (const Case& c : exactCases()) {
    for (const double t0 : {0.0, 1.0, 2.5}) {
      const std::vector<Point2> points = sample(c.truth, 30, t0, 2 * kPi / 3);
      const auto fit = fitEllipse(points);
      ASSERT_TRUE(fit.has_value()) << c.name << " from " << t0;
      expectSameEllipse(fit->ellipse, c.truth, kRelative, c.name);
    }
  }
}

TEST(EllipseFit, NoisyPointsWithinTheirPropagatedUncertainty) {
  // 100 points on a = 20, b = 12, each moved by isotropic normal noise of sigma = 0.05. The
  // fit's own sensitivities give each semi-axis' standard deviation, sigma * sqrt(sum of the
  // squared sensitivities) (~0.01 here): the errors must be within 5 of those (a 1-in-1.7e6
  // chance for a correct fit; the seed makes it deterministic anyway) and within an absolute
  // 0.05 (one sigma per point; ~5 standard deviations of sigma * sqrt(2 / 100)).
  constexpr double kSigma = 0.05;
  const Ellipse truth = makeEllipse(40.5, 33.25, 20, 12, radians(25));
  std::mt19937 rng(20240607);
  std::normal_distribution<double> noise(0.0, kSigma);
  std::vector<Point2> points = sample(truth, 100);
  for (Point2& p : points) p = {p.x + noise(rng), p.y + noise(rng)};
  const auto fit = fitEllipse(points);
  ASSERT_TRUE(fit.has_value());
  const Ellipse& e = fit->ellipse;
  double var_a = 0, var_b = 0;
  for (const auto& s : fit->axis_sensitivity) {
    var_a += kSigma * kSigma * (s[0] * s[0] + s[1] * s[1]);
    var_b += kSigma * kSigma * (s[2] * s[2] + s[3] * s[3]);
  }
  const double sigma_a = std::sqrt(var_a), sigma_b = std::sqrt(var_b);
  // A sanity range for the propagated uncertainties: between 0.2 and 5 times sigma * sqrt(2/N).
  const double rough = kSigma * std::sqrt(2.0 / 100);
  EXPECT_GT(sigma_a, 0.2 * rough);
  EXPECT_LT(sigma_a, 5 * rough);
  EXPECT_GT(sigma_b, 0.2 * rough);
  EXPECT_LT(sigma_b, 5 * rough);
  EXPECT_LT(std::abs(e.semi_major - 20), 5 * sigma_a);
  EXPECT_LT(std::abs(e.semi_minor - 12), 5 * sigma_b);
  EXPECT_LT(std::abs(e.semi_major - 20), kSigma);
  EXPECT_LT(std::abs(e.semi_minor - 12), kSigma);
  EXPECT_LT(std::abs(e.centre.x - 40.5), kSigma);
  EXPECT_LT(std::abs(e.centre.y - 33.25), kSigma);
  // The orientation: sigma / (a - b) rad per point, averaged over the points, ~1e-3 rad;
  // 0.01 rad is ten times that.
  EXPECT_LT(orientationDifference(e.angle_rad, radians(25)), 0.01);
  // The orthogonal residuals are the normal component of the noise: rms ~ sigma, less the
  // five fitted parameters' share (sqrt(95/100)); 20 % covers the sampling scatter of an rms
  // of 100 values (~7 %) three times over.
  EXPECT_NEAR(fit->rms_residual, kSigma * std::sqrt(0.95), 0.2 * kSigma);
  // Residuals are signed: positive outside the fitted ellipse.
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double r = fit->residuals[i];
    if (std::abs(r) < 1e-6) continue;
    EXPECT_EQ(r > 0, implicitValue(e, points[i]) > 0) << i;
  }
}

TEST(EllipseFit, NoisyFitsScatterAsTheSensitivitiesPredict) {
  // Monte Carlo: over 300 seeded noisy fits of the same ellipse, the standard deviation of each
  // fitted semi-axis matches the one propagated through axis_sensitivity. With 300 samples the
  // empirical standard deviation scatters by ~1/sqrt(600) ~ 4 %; allow 20 %.
  constexpr double kSigma = 0.05;
  constexpr int kTrials = 300;
  const Ellipse truth = makeEllipse(0, 0, 20, 12, radians(-40));
  const std::vector<Point2> exact = sample(truth, 60);
  const auto reference = fitEllipse(exact);
  ASSERT_TRUE(reference.has_value());
  double predicted_a = 0, predicted_b = 0;
  for (const auto& s : reference->axis_sensitivity) {
    predicted_a += kSigma * kSigma * (s[0] * s[0] + s[1] * s[1]);
    predicted_b += kSigma * kSigma * (s[2] * s[2] + s[3] * s[3]);
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, kSigma);
  double sum_a = 0, sum_b = 0, sum_a2 = 0, sum_b2 = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::vector<Point2> points = exact;
    for (Point2& p : points) p = {p.x + noise(rng), p.y + noise(rng)};
    const auto fit = fitEllipse(points);
    ASSERT_TRUE(fit.has_value());
    const double da = fit->ellipse.semi_major - 20, db = fit->ellipse.semi_minor - 12;
    sum_a += da;
    sum_b += db;
    sum_a2 += da * da;
    sum_b2 += db * db;
  }
  const double var_a = sum_a2 / kTrials - std::pow(sum_a / kTrials, 2);
  const double var_b = sum_b2 / kTrials - std::pow(sum_b / kTrials, 2);
  EXPECT_NEAR(std::sqrt(var_a / predicted_a), 1.0, 0.2);
  EXPECT_NEAR(std::sqrt(var_b / predicted_b), 1.0, 0.2);
}

TEST(EllipseFit, StartsFromAGivenEllipse) {
  // A start near the answer (as when refitting nearly the same points) converges to the same
  // fit as the direct start; exact points, so both are the truth to rounding: 1e-9 relative.
  const Ellipse truth = makeEllipse(-7, 4, 22, 13, 0.6);
  const std::vector<Point2> points = sample(truth, 30);
  const Ellipse start = makeEllipse(-6.5, 4.4, 21, 13.8, 0.5);
  const auto fit = fitEllipse(points, start);
  ASSERT_TRUE(fit.has_value());
  expectSameEllipse(fit->ellipse, truth, 1e-9, "from a given start");
  // The start does not stand in for missing points.
  EXPECT_FALSE(fitEllipse(sample(truth, 4), start).has_value());
}

TEST(EllipseFit, NothingForTooFewPoints) {
  const Ellipse truth = makeEllipse(1, 2, 9, 5, 0.4);
  const std::vector<Point2> four = sample(truth, 4);
  EXPECT_FALSE(fitEllipseDirect(four).has_value());
  EXPECT_FALSE(fitEllipse(four).has_value());
  EXPECT_FALSE(fitEllipse(std::vector<Point2>{}).has_value());
  // Five points on an ellipse determine it.
  const auto five = fitEllipse(sample(truth, 5));
  ASSERT_TRUE(five.has_value());
  expectSameEllipse(five->ellipse, truth, 1e-9, "five points");
}

TEST(EllipseFit, NothingForCollinearPoints) {
  std::vector<Point2> line;
  for (int i = 0; i < 12; ++i) line.push_back({1.5 + 2.0 * i, -3.0 + 0.75 * i});
  EXPECT_FALSE(fitEllipseDirect(line).has_value());
  EXPECT_FALSE(fitEllipse(line).has_value());
  std::vector<Point2> vertical;
  for (int i = 0; i < 8; ++i) vertical.push_back({4.0, 1.0 * i});
  EXPECT_FALSE(fitEllipse(vertical).has_value());
  const std::vector<Point2> same(10, Point2{3, 4});  // all at one point
  EXPECT_FALSE(fitEllipse(same).has_value());
}

// The direct fit is ellipse-specific (Fitzgibbon et al.): points on a hyperbola or a parabola
// still get their closest ellipse, and the residuals tell that the shape is wrong. Exact points
// on an ellipse leave an rms residual of ~1e-12 of the size; points on no ellipse leave a
// finite fraction of it: 1e-3 of the ~5-10 unit extents here separates the two by far.
void expectClosestEllipseWithLargeResiduals(const std::vector<Point2>& points, const char* what) {
  const auto direct = fitEllipseDirect(points);
  ASSERT_TRUE(direct.has_value()) << what;
  EXPECT_TRUE(std::isfinite(direct->semi_major) && std::isfinite(direct->semi_minor)) << what;
  EXPECT_GE(direct->semi_major, direct->semi_minor) << what;
  EXPECT_GT(direct->semi_minor, 0) << what;
  const auto fit = fitEllipse(points);
  ASSERT_TRUE(fit.has_value()) << what;
  EXPECT_GT(fit->rms_residual, 1e-3) << what;
}

TEST(EllipseFit, PointsOnAHyperbolaGetAnEllipseWithLargeResiduals) {
  // x²/4 - y²/9 = 1 about (10, -5), both branches, then one branch only.
  std::vector<Point2> both, one;
  for (int i = -5; i <= 5; ++i) {
    const double s = 0.3 * i;
    const Point2 right{2 * std::cosh(s) + 10, 3 * std::sinh(s) - 5};
    both.push_back(right);
    both.push_back({-2 * std::cosh(s) + 10, 3 * std::sinh(s) - 5});
    one.push_back(right);
  }
  expectClosestEllipseWithLargeResiduals(both, "both branches");
  expectClosestEllipseWithLargeResiduals(one, "one branch");
}

TEST(EllipseFit, PointsOnAParabolaGetADegenerateEllipse) {
  // A parabola is the limit of ever longer ellipses, so its closest ellipse fits it as closely
  // as the arithmetic allows (the residuals do not tell) but is absurdly long: the semi-major
  // axis is far beyond the points' extent (12 units; 1000 times that is no glare lobe).
  std::vector<Point2> parabola;
  for (int i = -6; i <= 6; ++i) parabola.push_back({1.0 * i, 0.25 * i * i});
  const auto direct = fitEllipseDirect(parabola);
  ASSERT_TRUE(direct.has_value());
  EXPECT_GT(direct->semi_major, 1000 * 12.0);
  const auto fit = fitEllipse(parabola);
  ASSERT_TRUE(fit.has_value());
  EXPECT_GT(fit->ellipse.semi_major, 1000 * 12.0);
  EXPECT_GE(fit->ellipse.semi_major, fit->ellipse.semi_minor);
}

TEST(EllipseFit, NormalsAreOutwardUnitVectors) {
  for (const Case& c : exactCases()) {
    const std::vector<Point2> points = sample(c.truth, 36);
    const auto fit = fitEllipse(points);
    ASSERT_TRUE(fit.has_value()) << c.name;
    const Ellipse& e = c.truth;
    const double cs = std::cos(e.angle_rad), sn = std::sin(e.angle_rad);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Point2 n = fit->normals[i];
      // Unit length and the analytic normal R (cos t / a, sin t / b) normalised: rounding only.
      EXPECT_NEAR(std::hypot(n.x, n.y), 1.0, 1e-12) << c.name;
      const double t = 0.3 + 2 * kPi * static_cast<double>(i) / 36;
      const double nu = std::cos(t) / e.semi_major, nv = std::sin(t) / e.semi_minor;
      const double norm = std::hypot(nu, nv);
      EXPECT_NEAR(n.x, (cs * nu - sn * nv) / norm, 1e-8) << c.name << " point " << i;
      EXPECT_NEAR(n.y, (sn * nu + cs * nv) / norm, 1e-8) << c.name << " point " << i;
      // Outward: away from the centre.
      EXPECT_GT(n.x * (points[i].x - e.centre.x) + n.y * (points[i].y - e.centre.y), 0);
    }
  }
}

TEST(EllipseFit, AxisSensitivityMatchesFiniteDifferences) {
  // Exact points, so the sensitivity (which drops terms proportional to the residuals) is the
  // exact derivative. Central differences with delta = 1e-4: O(delta²) truncation ~1e-8 and
  // the geometric fit converges to 1e-12 of the size (~3e-11), i.e. ~3e-7 in a derivative;
  // sensitivities are ~1 / N ~ 0.05: 1e-3 relative plus 1e-6 absolute covers both.
  constexpr double kDelta = 1e-4;
  for (const Case& c : exactCases()) {
    if (c.truth.semi_major == c.truth.semi_minor) continue;  // axes of a circle: not smooth
    const std::vector<Point2> points = sample(c.truth, 20);
    const auto fit = fitEllipse(points);
    ASSERT_TRUE(fit.has_value()) << c.name;
    double total = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      for (int axis = 0; axis < 2; ++axis) {
        std::vector<Point2> plus = points, minus = points;
        (axis == 0 ? plus[i].x : plus[i].y) += kDelta;
        (axis == 0 ? minus[i].x : minus[i].y) -= kDelta;
        const auto fp = fitEllipse(plus);
        const auto fm = fitEllipse(minus);
        ASSERT_TRUE(fp && fm) << c.name;
        const double da = (fp->ellipse.semi_major - fm->ellipse.semi_major) / (2 * kDelta);
        const double db = (fp->ellipse.semi_minor - fm->ellipse.semi_minor) / (2 * kDelta);
        const auto& s = fit->axis_sensitivity[i];
        const std::size_t k = static_cast<std::size_t>(axis);
        EXPECT_NEAR(s[k], da, 1e-3 * std::abs(da) + 1e-6)
            << c.name << " point " << i << (axis == 0 ? " x" : " y") << " semi-major";
        EXPECT_NEAR(s[2 + k], db, 1e-3 * std::abs(db) + 1e-6)
            << c.name << " point " << i << (axis == 0 ? " x" : " y") << " semi-minor";
        total += std::abs(s[k]) + std::abs(s[2 + k]);
      }
    }
    EXPECT_GT(total, 0.1) << c.name << ": sensitivities should not all vanish";
  }
}

TEST(EllipseFit, AxisSensitivityRespectsSimilarities) {
  // Exact invariances of the fit, to first order in the points' motions: translating every
  // point leaves the axes alone, rotating every point about the centre leaves them alone, and
  // scaling every point about the centre by (1 + e) scales them by (1 + e). Summed over all
  // points, the sensitivities must reproduce that; 1e-8 of the size is rounding in the
  // pseudo-inverse and the foot points.
  for (const Case& c : exactCases()) {
    const std::vector<Point2> points = sample(c.truth, 40);
    const auto fit = fitEllipse(points);
    ASSERT_TRUE(fit.has_value()) << c.name;
    const Point2 centre = fit->ellipse.centre;
    double shift_x[2] = {0, 0}, shift_y[2] = {0, 0}, rotate[2] = {0, 0}, scale[2] = {0, 0};
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto& s = fit->axis_sensitivity[i];
      const double dx = points[i].x - centre.x, dy = points[i].y - centre.y;
      for (std::size_t k = 0; k < 2; ++k) {
        shift_x[k] += s[2 * k];
        shift_y[k] += s[2 * k + 1];
        rotate[k] += s[2 * k] * -dy + s[2 * k + 1] * dx;
        scale[k] += s[2 * k] * dx + s[2 * k + 1] * dy;
      }
    }
    const double size = c.truth.semi_major;
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_NEAR(shift_x[k], 0.0, 1e-8) << c.name << " axis " << k;
      EXPECT_NEAR(shift_y[k], 0.0, 1e-8) << c.name << " axis " << k;
      EXPECT_NEAR(rotate[k], 0.0, 1e-8 * size) << c.name << " axis " << k;
    }
    EXPECT_NEAR(scale[0], fit->ellipse.semi_major, 1e-8 * size) << c.name;
    EXPECT_NEAR(scale[1], fit->ellipse.semi_minor, 1e-8 * size) << c.name;
  }
}

TEST(EllipseFit, AxisSensitivityOfACircleGrowsWithItsRadius) {
  // The orientation of a circle is undetermined, yet moving every point outward by delta is
  // a circle of radius r + delta: both axes' sensitivities summed along the normals are 1.
  // 1e-8: rounding in the pseudo-inverse.
  const auto fit = fitEllipse(sample(makeEllipse(2, 3, 9, 9, 0), 32));
  ASSERT_TRUE(fit.has_value());
  double da = 0, db = 0;
  for (std::size_t i = 0; i < fit->normals.size(); ++i) {
    const auto& s = fit->axis_sensitivity[i];
    const Point2 n = fit->normals[i];
    da += s[0] * n.x + s[1] * n.y;
    db += s[2] * n.x + s[3] * n.y;
  }
  EXPECT_NEAR(da, 1.0, 1e-8);
  EXPECT_NEAR(db, 1.0, 1e-8);
}

TEST(EllipseFit, PointAtFollowsTheConvention) {
  const Ellipse e = makeEllipse(1, 2, 4, 3, kPi / 2);
  // t = 0 is the end of the major axis, here along +y (angle toward +y).
  const Point2 p = e.pointAt(0);
  EXPECT_NEAR(p.x, 1, 1e-15);
  EXPECT_NEAR(p.y, 6, 1e-15);
  const Point2 q = e.pointAt(kPi / 2);  // end of the minor axis, along -x
  EXPECT_NEAR(q.x, -2, 1e-15);
  EXPECT_NEAR(q.y, 2, 1e-15);
}

}  // namespace
}  // namespace glarecam::pipeline
