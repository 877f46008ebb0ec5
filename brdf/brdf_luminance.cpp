#include "brdf/brdf_luminance.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

#include "core/angles.h"
#include "core/parallel.h"

namespace glarecam::brdf {

using calibration::PlanePointDeg;

Status LuminanceImageOptions::validate() const {
  GLARECAM_CHECK(checkReferenceIlluminance(reference_illuminance_lx, "--reference-illuminance"));
  constexpr double kMaxSunHalfAngleDeg = 5;  // a source wider than this is no sun or lamp
  if (!(sun_half_angle_deg >= 0 && sun_half_angle_deg <= kMaxSunHalfAngleDeg))
    return badInput(fmt::format("--source-radius: must be in [0, {:g}]°", kMaxSunHalfAngleDeg));
  if (!(max_half_width_deg >= 1 && max_half_width_deg <= 60))
    return badInput("--half-width: must be in [1, 60]°");
  if (max_size_px < 65 || max_size_px > 4001 || max_size_px % 2 == 0)
    return badInput("--pixels: must be an odd number of pixels in [65, 4001]");
  if (!(min_pixel_deg > 0 && min_pixel_deg <= 1))
    return badInput("the finest pixel must be in (0, 1]°");
  return {};
}

namespace {

struct PlaneSamples {
  std::vector<cv::Point2f> points;
  std::vector<double> ln_brdf;  // one per point (duplicates averaged)
};

// The samples in the angular plane, ln f_r, with zeros (below the detector's floor) at a
// thousandth of the smallest positive value.
PlaneSamples planeSamples(const BrdfMeasurement& m) {
  const SpecularFrame frame(m.incident_theta_deg, m.incident_phi_deg);
  double smallest = std::numeric_limits<double>::infinity();
  for (const BrdfSample& s : m.samples)
    if (s.brdf_sr > 0) smallest = std::min(smallest, s.brdf_sr);
  // Zeros are below the detector's floor: a thousandth of the smallest measured value, so that a
  // contour between a measured sample and a zero lies near the last measured one (the caller
  // warns that contours there are not measured).
  constexpr double kZeroFloorFraction = 1e-3;
  const double floor = kZeroFloorFraction * smallest;
  // In the file's order (a scan's neighbours follow each other): the triangulation walks from
  // each point to the next, so that order keeps it short (sorted by x it is ten times slower).
  std::map<std::pair<float, float>, std::size_t> index;
  PlaneSamples out;
  std::vector<int> counts;
  for (const BrdfSample& s : m.samples) {
    const PlanePointDeg p = frame.toPlane(s.theta_deg, s.phi_deg);
    const std::pair key{static_cast<float>(p.x_deg), static_cast<float>(p.y_deg)};
    const auto [it, added] = index.try_emplace(key, out.points.size());
    const double ln = std::log(std::max(s.brdf_sr, floor));
    if (added) {
      out.points.emplace_back(key.first, key.second);
      out.ln_brdf.push_back(ln);
      counts.push_back(1);
    } else {
      out.ln_brdf[it->second] += ln;
      ++counts[it->second];
    }
  }
  for (std::size_t i = 0; i < counts.size(); ++i) out.ln_brdf[i] /= counts[i];
  return out;
}

// ln f_r linearly interpolated over the Delaunay triangles onto the grid (side n, spacing
// `pixel`, centre index c); NaN where no triangle covers a node.
cv::Mat interpolateOnGrid(const PlaneSamples& samples, int n, double pixel) {
  cv::Mat grid(n, n, CV_64F, cv::Scalar(std::numeric_limits<double>::quiet_NaN()));
  float min_x = samples.points.front().x, max_x = min_x;
  float min_y = samples.points.front().y, max_y = min_y;
  for (const cv::Point2f& p : samples.points) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y);
    max_y = std::max(max_y, p.y);
  }
  const cv::Rect2f bounds(min_x, min_y, max_x - min_x, max_y - min_y);
  constexpr float kMarginDeg = 1;
  const cv::Rect rect(static_cast<int>(std::floor(bounds.x - kMarginDeg)),
                      static_cast<int>(std::floor(bounds.y - kMarginDeg)),
                      static_cast<int>(std::ceil(bounds.width + 2 * kMarginDeg)) + 1,
                      static_cast<int>(std::ceil(bounds.height + 2 * kMarginDeg)) + 1);
  cv::Subdiv2D subdiv(rect);
  std::map<std::pair<float, float>, double> value_at;
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    subdiv.insert(samples.points[i]);
    value_at[{samples.points[i].x, samples.points[i].y}] = samples.ln_brdf[i];
  }
  std::vector<cv::Vec6f> triangles;
  subdiv.getTriangleList(triangles);
  const double c = (n - 1) / 2.0;
  for (const cv::Vec6f& t : triangles) {
    double x[3], y[3], v[3];
    bool real = true;
    for (int k = 0; k < 3 && real; ++k) {
      const auto it = value_at.find({t[2 * k], t[2 * k + 1]});
      real = it != value_at.end();  // not one of the subdivision's outer vertices
      if (!real) break;
      x[k] = t[2 * k] / pixel + c;
      y[k] = t[2 * k + 1] / pixel + c;
      v[k] = it->second;
    }
    if (!real) continue;
    const double det = (y[1] - y[2]) * (x[0] - x[2]) + (x[2] - x[1]) * (y[0] - y[2]);
    if (std::abs(det) < 1e-12) continue;  // degenerate
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({x[0], x[1], x[2]}))));
    const int x1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({x[0], x[1], x[2]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({y[0], y[1], y[2]}))));
    const int y1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({y[0], y[1], y[2]}))));
    constexpr double kEdge = -1e-9;  // a node on a shared edge belongs to both triangles
    for (int gy = y0; gy <= y1; ++gy) {
      double* row = grid.ptr<double>(gy);
      for (int gx = x0; gx <= x1; ++gx) {
        const double a = ((y[1] - y[2]) * (gx - x[2]) + (x[2] - x[1]) * (gy - y[2])) / det;
        const double b = ((y[2] - y[0]) * (gx - x[2]) + (x[0] - x[2]) * (gy - y[2])) / det;
        const double g = 1 - a - b;
        if (a < kEdge || b < kEdge || g < kEdge) continue;
        row[gx] = a * v[0] + b * v[1] + g * v[2];
      }
    }
  }
  return grid;
}

// How far from the specular direction the samples reach in every direction: the distance from
// it to their convex hull's nearest edge (negative when it lies outside).
double coverageDeg(const std::vector<cv::Point2f>& points) {
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull);
  if (hull.size() < 3) return -1;
  return cv::pointPolygonTest(hull, cv::Point2f(0, 0), true);
}

double bilinear(const cv::Mat& grid, double gx, double gy) {
  const int n = grid.cols;
  gx = std::clamp(gx, 0.0, n - 1.0);
  gy = std::clamp(gy, 0.0, n - 1.0);
  const int x0 = std::min(static_cast<int>(gx), n - 2), y0 = std::min(static_cast<int>(gy), n - 2);
  const double fx = gx - x0, fy = gy - y0;
  const double* r0 = grid.ptr<double>(y0);
  const double* r1 = grid.ptr<double>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
         fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

}  // namespace

Result<BrdfLuminance> luminanceUnderSun(const BrdfMeasurement& m, const SamplingCheck& sampling,
                                        const LuminanceImageOptions& options) {
  GLARECAM_CHECK(options.validate());
  BrdfLuminance out;
  const auto zeros =
      std::ranges::count_if(m.samples, [](const BrdfSample& s) { return s.brdf_sr <= 0; });
  if (zeros > 0)
    spdlog::warn(
        "{}: {} of {} samples at θ_i {:g}° are 0 (below the detector's floor?): taken as a "
        "thousandth of the smallest measured value; a contour among them is not measured",
        m.file, zeros, m.samples.size(), m.incident_theta_deg);
  const PlaneSamples samples = planeSamples(m);
  out.covered_deg = coverageDeg(samples.points);
  // The grid must hold the lobe's core: at least a few FWHM of the Gaussian approximation.
  const double fwhm_deg = 2.3548200450309493 * std::max(sampling.lobe.sigma_vertical_deg,
                                                        sampling.lobe.sigma_horizontal_deg);
  constexpr double kMinFwhmCovered = 1.0;
  if (!(out.covered_deg >= kMinFwhmCovered * fwhm_deg))
    return badInput(fmt::format(
        "{}: the samples at θ_i {:g}° reach only {:.3g}° around the specular direction, less "
        "than the lobe's FWHM of {:.3g}°: the glare spot is not in the data",
        m.file, m.incident_theta_deg, std::max(out.covered_deg, 0.0), fwhm_deg));
  // The square grid inside the covered circle (its corners too).
  const double half_width = std::min(options.max_half_width_deg, out.covered_deg / std::sqrt(2.0));
  double pixel = std::max(options.min_pixel_deg, 2 * half_width / (options.max_size_px - 1));
  const int half = std::max(1, static_cast<int>(std::floor(half_width / pixel)));
  const int n = 2 * half + 1;
  out.pixel_deg = pixel;
  out.half_width_deg = half * pixel;

  cv::Mat ln_grid = interpolateOnGrid(samples, n, pixel);
  const double floor_ln = samples.ln_brdf.empty() ? 0 : *std::ranges::min_element(samples.ln_brdf);
  cv::Mat brdf_grid(n, n, CV_64F);
  std::size_t uncovered = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      double v = ln_grid.at<double>(y, x);
      if (!std::isfinite(v)) {
        ++uncovered;
        v = floor_ln;
      }
      brdf_grid.at<double>(y, x) = std::exp(v);
    }
  if (uncovered > 0)
    spdlog::debug("{}: {} grid nodes outside every triangle, at the data's floor", m.file,
                  uncovered);
  if (options.sun_half_angle_deg > 0) {
    int side = 0;
    std::vector<double> weights = discKernel(options.sun_half_angle_deg, pixel, side);
    const cv::Mat kernel(side, side, CV_64F, weights.data());
    cv::Mat convolved;
    cv::filter2D(brdf_grid, convolved, CV_64F, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
    brdf_grid = convolved;
  }
  const double scale = options.reference_illuminance_lx * std::cos(radians(m.incident_theta_deg));

  if (m.relative_noise) {
    out.relative_noise = *m.relative_noise;
    out.noise_origin = "stated";
  } else if (const std::optional<double> estimate = estimateRelativeNoise(m)) {
    out.relative_noise = *estimate;
    out.noise_origin = "estimated";
  } else {
    out.relative_noise = kAssumedRelativeNoise;
    out.noise_origin = "assumed";
  }

  const double sigma_min =
      std::min(sampling.lobe.sigma_vertical_deg, sampling.lobe.sigma_horizontal_deg);
  const auto under_read = [&](double spacing_deg) {
    return spacing_deg * spacing_deg / (8 * sigma_min * sigma_min);
  };
  out.grid_relative_uncertainty = under_read(sampling.spacing_deg);
  out.contour_grid_relative_uncertainty = under_read(sampling.coarsest_spacing_deg);
  // Each pixel's noise is its samples', shared by every pixel within a sample spacing: the
  // analysis, which averages pixels as independent (the peak's fit, the contours), must see the
  // noise of one independent value per spacing², so each pixel carries it times spacing / pixel.
  // The grid's under-read is no pixel noise at all: it is alike over the lobe's top (the route
  // states it as the picture's scale uncertainty, brdf_route.h).
  out.noise_correlation = std::max(1.0, sampling.spacing_deg / pixel);
  const double pixel_u = out.relative_noise * out.noise_correlation;

  // The pinhole camera along the specular direction: a pixel at the centre spans `pixel`.
  const double focal_px = 1 / std::tan(radians(pixel));
  out.intrinsics = {.fx = focal_px, .fy = focal_px, .cx = double(half), .cy = double(half)};
  out.intrinsics.width = n;
  out.intrinsics.height = n;
  calibration::MergedImage& image = out.image;
  image.luminance_cd_m2 = FloatImage(n, n);
  image.relative_uncertainty = FloatImage(n, n, static_cast<float>(pixel_u));
  image.valid_frames = ByteImage(n, n, 1);
  image.bound = ByteImage(n, n, static_cast<std::uint8_t>(calibration::PixelBound::kMeasured));
  const calibration::AngularPlane plane(calibration::Ray{0, 0, 1});
  parallelRows(n, 0, [&](int first, int end) {
    for (int v = first; v < end; ++v)
      for (int u = 0; u < n; ++u) {
        const calibration::Ray ray{(u - half) / focal_px, (v - half) / focal_px, 1};
        const PlanePointDeg p = plane.toPlane(ray);
        image.luminance_cd_m2.at(u, v) = static_cast<float>(
            scale * bilinear(brdf_grid, p.x_deg / pixel + half, p.y_deg / pixel + half));
      }
  });
  return out;
}

}  // namespace glarecam::brdf
