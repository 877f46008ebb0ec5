#include "brdf/brdf_measurement.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/angles.h"

namespace glarecam::brdf {

namespace {

using calibration::PlanePointDeg;
using calibration::Ray;

// 2√(2 ln 2): a Gaussian's FWHM in units of its σ.
constexpr double kFwhmPerSigma = 2.3548200450309493;

double distanceDeg(const PlanePointDeg& a, const PlanePointDeg& b) {
  return std::hypot(a.x_deg - b.x_deg, a.y_deg - b.y_deg);
}

}  // namespace

const char* toString(BrdfFileFormat format) {
  return format == BrdfFileFormat::kPabOpto ? "pabopto" : "zemax";
}

double GaussianLobe::verticalAxisDeg(double fraction) const {
  return 2 * sigma_vertical_deg * std::sqrt(2 * std::log(1 / fraction));
}

double GaussianLobe::horizontalAxisDeg(double fraction) const {
  return 2 * sigma_horizontal_deg * std::sqrt(2 * std::log(1 / fraction));
}

namespace {

// The samples of at least `fraction` of the peak, in the angular plane.
struct LobePoints {
  std::vector<PlanePointDeg> points;
  std::vector<double> ln_brdf;
};

LobePoints lobePoints(const BrdfMeasurement& m, const SpecularFrame& frame, double peak,
                      double fraction) {
  LobePoints lobe;
  for (const BrdfSample& s : m.samples) {
    if (!(s.brdf_sr >= fraction * peak) || s.brdf_sr <= 0) continue;
    lobe.points.push_back(frame.toPlane(s.theta_deg, s.phi_deg));
    lobe.ln_brdf.push_back(std::log(s.brdf_sr));
  }
  return lobe;
}

// ln f = a0 + a1 x + a2 y + a3 x² + a4 xy + a5 y², least squares; none when it is not a lobe
// (too few points, or a quadratic that is not a maximum).
std::optional<GaussianLobe> fitGaussian(const LobePoints& lobe) {
  constexpr std::size_t kTerms = 6;
  const std::size_t n = lobe.points.size();
  if (n < 2 * kTerms) return std::nullopt;  // twice the unknowns: a fit, not an interpolation
  Eigen::MatrixXd a(n, kTerms);
  Eigen::VectorXd b(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = lobe.points[i].x_deg, y = lobe.points[i].y_deg;
    a.row(static_cast<Eigen::Index>(i)) << 1, x, y, x * x, x * y, y * y;
    b(static_cast<Eigen::Index>(i)) = lobe.ln_brdf[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  Eigen::Matrix2d hessian;
  hessian << 2 * c(3), c(4), c(4), 2 * c(5);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> curvature(-hessian);
  if (curvature.info() != Eigen::Success || !(curvature.eigenvalues().minCoeff() > 0))
    return std::nullopt;
  const Eigen::Vector2d centre = hessian.fullPivLu().solve(-Eigen::Vector2d(c(1), c(2)));
  GaussianLobe g;
  g.centre = {centre(0), centre(1)};
  const double x = centre(0), y = centre(1);
  g.peak_brdf_sr =
      std::exp(c(0) + c(1) * x + c(2) * y + c(3) * x * x + c(4) * x * y + c(5) * y * y);
  // σ² along each principal axis is the inverse of the curvature there.
  const Eigen::Vector2d e0 = curvature.eigenvectors().col(0), e1 = curvature.eigenvectors().col(1);
  const double s0 = 1 / std::sqrt(curvature.eigenvalues()(0));
  const double s1 = 1 / std::sqrt(curvature.eigenvalues()(1));
  // The axis nearer the y axis (the plane of incidence) is the vertical one.
  const bool first_vertical = std::abs(e0.y()) >= std::abs(e1.y());
  g.sigma_vertical_deg = first_vertical ? s0 : s1;
  g.sigma_horizontal_deg = first_vertical ? s1 : s0;
  const Eigen::Vector2d horizontal = first_vertical ? e1 : e0;
  double orientation = degrees(std::atan2(horizontal.y(), horizontal.x()));
  if (orientation > 90) orientation -= 180;
  if (orientation <= -90) orientation += 180;
  g.orientation_deg = orientation;
  g.samples = n;
  return g;
}

double medianOf(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

Result<SamplingCheck> checkSampling(const BrdfMeasurement& m) {
  if (m.samples.empty()) return badInput(m.file + ": no BRDF samples");
  SamplingCheck check;
  const auto peak = std::ranges::max_element(m.samples, {}, &BrdfSample::brdf_sr);
  check.peak_index = static_cast<std::size_t>(peak - m.samples.begin());
  const std::string where = peak->line > 0 ? fmt::format("{}:{}", m.file, peak->line) : m.file;
  if (!(peak->brdf_sr > 0)) return badInput(m.file + ": every BRDF sample is zero");
  const SpecularFrame frame(m.incident_theta_deg, m.incident_phi_deg);
  const PlanePointDeg peak_point = frame.toPlane(peak->theta_deg, peak->phi_deg);
  check.peak_offset_deg = std::hypot(peak_point.x_deg, peak_point.y_deg);

  const LobePoints lobe = lobePoints(m, frame, peak->brdf_sr, kLobeFitFraction);
  // Nearest-neighbour distances among the lobe's samples: the grid's step where it matters.
  std::vector<double> nearest;
  for (std::size_t i = 0; i < lobe.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < lobe.points.size(); ++j) {
      const double d = distanceDeg(lobe.points[i], lobe.points[j]);
      if (j != i && d > 0) best = std::min(best, d);
    }
    if (std::isfinite(best)) nearest.push_back(best);
  }
  const std::optional<GaussianLobe> gaussian = fitGaussian(lobe);
  // Many samples near the peak value that do not make a peak: no lobe at all (flat or noisy
  // data, or a file cut before the specular direction), not a coarse grid.
  constexpr std::size_t kManyLobeSamples = 50;
  if (!gaussian && lobe.points.size() >= kManyLobeSamples)
    return badInput(fmt::format(
        "{}: no glare lobe at θ_i {:g}°: the {} samples of at least {:g} of the peak do not rise "
        "to a maximum (flat or noisy data, or the specular direction not measured)",
        where, m.incident_theta_deg, lobe.points.size(), kLobeFitFraction));
  const std::string coarse = fmt::format(
      "{}: the grid is too coarse for the lobe at θ_i {:g}°: {} samples of at least {:g} of the "
      "peak{}; at least {:g} samples across the FWHM are needed to draw a glare spot a few "
      "degrees wide (docs/brdf.md)",
      where, m.incident_theta_deg, lobe.points.size(), kLobeFitFraction,
      nearest.empty() ? std::string() : fmt::format(", {:.3g}° apart", medianOf(nearest)),
      kMinSamplesAcrossFwhm);
  if (!gaussian || nearest.empty()) return badInput(coarse);
  check.lobe = *gaussian;
  check.spacing_deg = medianOf(nearest);
  check.coarsest_spacing_deg = *std::ranges::max_element(nearest);
  check.samples_across_fwhm =
      kFwhmPerSigma * std::min(gaussian->sigma_vertical_deg, gaussian->sigma_horizontal_deg) /
      check.spacing_deg;
  if (check.samples_across_fwhm < kMinSamplesAcrossFwhm)
    return badInput(fmt::format(
        "{}: the grid is too coarse for the lobe at θ_i {:g}°: {:.1f} samples across its FWHM "
        "of {:.3g}° (samples {:.3g}° apart), at least {:g} are needed to draw a glare spot a few "
        "degrees wide (docs/brdf.md)",
        where, m.incident_theta_deg, check.samples_across_fwhm,
        kFwhmPerSigma * std::min(gaussian->sigma_vertical_deg, gaussian->sigma_horizontal_deg),
        check.spacing_deg, kMinSamplesAcrossFwhm));
  // A real lobe's peak may sit off the specular direction (Fresnel and the 1/cos θ_o of grazing
  // reflection move it toward grazing), by a fraction of its width: only more is suspect.
  const double half_fwhm =
      0.5 * kFwhmPerSigma * std::min(gaussian->sigma_vertical_deg, gaussian->sigma_horizontal_deg);
  if (check.peak_offset_deg > std::max({kPeakOffsetWarningDeg, 2 * check.spacing_deg, half_fwhm})) {
    const auto [theta, phi] = frame.fromPlane({0, 0});
    check.warnings.push_back(fmt::format(
        "{}: the peak lies {:.2f}° from the specular direction (θ {:g}°, φ {:g}°), at θ {:g}°, "
        "φ {:g}°: is the incident direction (θ_i, φ_i) the one toward the source (docs/brdf.md)?",
        where, check.peak_offset_deg, theta, phi, peak->theta_deg, peak->phi_deg));
  }
  return check;
}

std::optional<double> estimateRelativeNoise(const BrdfMeasurement& m) {
  if (m.samples.size() < 4) return std::nullopt;
  const auto peak = std::ranges::max_element(m.samples, {}, &BrdfSample::brdf_sr);
  if (!(peak->brdf_sr > 0)) return std::nullopt;
  // On the lobe (within two decades of the peak) the values are well above any noise floor.
  constexpr double kLobeDecades = 0.01;
  // Evenly spaced: the steps of a run agree to 10 %.
  constexpr double kEvenStep = 0.1;
  const SpecularFrame frame(m.incident_theta_deg, m.incident_phi_deg);
  std::vector<double> third;
  for (std::size_t i = 0; i + 3 < m.samples.size(); ++i) {
    double ln[4];
    PlanePointDeg p[4];
    bool ok = true;
    for (int k = 0; k < 4 && ok; ++k) {
      const BrdfSample& s = m.samples[i + k];
      ok = s.brdf_sr >= kLobeDecades * peak->brdf_sr;
      if (!ok) break;
      ln[k] = std::log(s.brdf_sr);
      p[k] = frame.toPlane(s.theta_deg, s.phi_deg);
    }
    if (!ok) continue;
    const double d0 = distanceDeg(p[0], p[1]), d1 = distanceDeg(p[1], p[2]),
                 d2 = distanceDeg(p[2], p[3]);
    const double d03 = distanceDeg(p[0], p[3]);
    if (!(d0 > 0) || std::abs(d1 - d0) > kEvenStep * d0 || std::abs(d2 - d0) > kEvenStep * d0 ||
        std::abs(d03 - 3 * d0) > kEvenStep * d0)  // in a line, not round a corner
      continue;
    third.push_back(std::abs(ln[0] - 3 * ln[1] + 3 * ln[2] - ln[3]));
  }
  if (third.size() < kMinNoiseRuns) return std::nullopt;
  // A third difference of independent noise σ has variance (1 + 9 + 9 + 1) σ²; the median of
  // |N(0, s)| is s / 1.4826.
  constexpr double kMadToSigma = 1.4826;
  return kMadToSigma * medianOf(third) / std::sqrt(20.0);
}

}  // namespace glarecam::brdf
