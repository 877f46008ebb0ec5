#include "capture/sim/surface_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "core/angles.h"
#include "core/parallel.h"
#include "core/source_illuminance.h"
#include "surface/lobe_contours.h"
#include "surface/specular_frame.h"

namespace glarecam::capture {
namespace {

using calibration::PlanePointDeg;
using calibration::Ray;

// The grid's spacing at most: a tenth of the narrowest disc-convolved lobe the catalogue holds
// (≈ 0.5° across at small α), where bicubic sampling is exact to far below the sensor's noise.
constexpr double kMaxGridStepDeg = 0.05;
// Its side at most (a frame 100° wide at 0.05°, 16 M doubles): a wider frame gets a coarser grid.
constexpr int kMaxGridSide = 4096;
constexpr int kCubicMargin = 2;      // the bicubic's reach beyond a grid point
constexpr double kMaxAlphaDeg = 89;  // the specular direction stays above the glass

// A square grid of the angular plane: values[j * nx + i] at (x0 + i·step, y0 + j·step).
struct PlaneGrid {
  double x0 = 0, y0 = 0, step = 1;
  int nx = 0, ny = 0;
  std::vector<double> values;

  double value(int i, int j) const {
    i = std::clamp(i, 0, nx - 1);
    j = std::clamp(j, 0, ny - 1);
    return values[static_cast<std::size_t>(j) * nx + i];
  }
  // Catmull–Rom bicubic sampling (Keys 1981, a = −0.5), clamped at the edges and at 0.
  double sample(const PlanePointDeg& p) const {
    const double gx = (p.x_deg - x0) / step, gy = (p.y_deg - y0) / step;
    const double fx = std::floor(gx), fy = std::floor(gy);
    const double tx = gx - fx, ty = gy - fy;
    const auto weights = [](double t, double w[4]) {
      w[0] = ((-t + 2) * t - 1) * t / 2;
      w[1] = ((3 * t - 5) * t * t + 2) / 2;
      w[2] = ((-3 * t + 4) * t + 1) * t / 2;
      w[3] = (t - 1) * t * t / 2;
    };
    double wx[4], wy[4];
    weights(tx, wx);
    weights(ty, wy);
    const int i0 = static_cast<int>(fx) - 1, j0 = static_cast<int>(fy) - 1;
    double sum = 0;
    for (int b = 0; b < 4; ++b) {
      double row = 0;
      for (int a = 0; a < 4; ++a) row += wx[a] * value(i0 + a, j0 + b);
      sum += wy[b] * row;
    }
    return std::max(0.0, sum);
  }
};

// The frame's extent in the angular plane: every border pixel's ray, and the angle one pixel
// spans at the principal point.
struct FrameExtent {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0, pixel_deg = 0;
};

FrameExtent frameExtent(const calibration::CameraModel& camera,
                        const calibration::AngularPlane& plane, int width, int height) {
  std::vector<calibration::PixelPoint> border;
  for (int x = 0; x < width; ++x) {
    border.push_back({static_cast<double>(x), 0.0});
    border.push_back({static_cast<double>(x), height - 1.0});
  }
  for (int y = 0; y < height; ++y) {
    border.push_back({0.0, static_cast<double>(y)});
    border.push_back({width - 1.0, static_cast<double>(y)});
  }
  FrameExtent extent{.x_min = 1e9, .x_max = -1e9, .y_min = 1e9, .y_max = -1e9};
  for (const Ray& ray : camera.rays(border)) {
    const PlanePointDeg p = plane.toPlane(ray);
    extent.x_min = std::min(extent.x_min, p.x_deg);
    extent.x_max = std::max(extent.x_max, p.x_deg);
    extent.y_min = std::min(extent.y_min, p.y_deg);
    extent.y_max = std::max(extent.y_max, p.y_deg);
  }
  const double cx = (width - 1) / 2.0, cy = (height - 1) / 2.0;
  const Ray a = camera.ray({cx, cy}), b = camera.ray({cx + 1, cy});
  const double dot =
      (a.x * b.x + a.y * b.y + a.z * b.z) /
      std::sqrt((a.x * a.x + a.y * a.y + a.z * a.z) * (b.x * b.x + b.y * b.y + b.z * b.z));
  extent.pixel_deg = degrees(std::acos(std::clamp(dot, -1.0, 1.0)));
  return extent;
}

}  // namespace

Result<SurfaceScene> SurfaceScene::create(std::shared_ptr<const surface::BrdfModel> model,
                                          const SurfaceLobe& lobe) {
  if (!model) return fail(ErrorCode::kInternal, "surface scene: no surface model");
  if (!(lobe.alpha_deg >= 0 && lobe.alpha_deg <= kMaxAlphaDeg))
    return badInput(fmt::format("surface scene: α must be in [0, {:g}]°", kMaxAlphaDeg));
  if (!(lobe.background_cd_m2 >= 0 && std::isfinite(lobe.background_cd_m2)) ||
      !(lobe.peak_scale > 0 && std::isfinite(lobe.peak_scale)) ||
      !std::isfinite(lobe.orientation_deg) ||
      !(lobe.sun_half_angle_deg >= 0 && lobe.sun_half_angle_deg < 5))
    return badInput("surface scene: non-finite or out-of-range parameters");
  return SurfaceScene(std::move(model), lobe);
}

SurfaceScene::SurfaceScene(std::shared_ptr<const surface::BrdfModel> model, const SurfaceLobe& lobe)
    : model_(std::move(model)),
      lobe_(lobe),
      plane_(calibration::rayFromDirection(
          {lobe.centre_direction_deg[0], lobe.centre_direction_deg[1]})) {}

FloatImage SurfaceScene::render(const calibration::CameraModel& camera, int width,
                                int height) const {
  const FrameExtent extent = frameExtent(camera, plane_, width, height);
  const double span = std::max(extent.x_max - extent.x_min, extent.y_max - extent.y_min);
  double step = std::min(kMaxGridStepDeg, extent.pixel_deg);
  step = std::max(step, span / (kMaxGridSide - 64));
  int side = 1;
  std::vector<double> kernel = surface::discKernel(lobe_.sun_half_angle_deg, step, side);
  const int margin = side / 2 + kCubicMargin;
  PlaneGrid grid;
  grid.step = step;
  grid.x0 = extent.x_min - margin * step;
  grid.y0 = extent.y_min - margin * step;
  grid.nx = static_cast<int>(std::ceil((extent.x_max - extent.x_min) / step)) + 1 + 2 * margin;
  grid.ny = static_cast<int>(std::ceil((extent.y_max - extent.y_min) / step)) + 1 + 2 * margin;
  grid.values.assign(static_cast<std::size_t>(grid.nx) * grid.ny, 0.0);

  // The point source's luminance E_ref · f_r(sun, o) · cos θ_i, in the lobe's own axes.
  const surface::SpecularFrame frame(lobe_.alpha_deg, 0);
  const Ray sun = surface::sampleDirection(lobe_.alpha_deg, 0);
  const double c = std::cos(radians(lobe_.orientation_deg)),
               s = std::sin(radians(lobe_.orientation_deg));
  parallelRows(grid.ny, availableThreads(), [&](int begin, int end) {
    for (int j = begin; j < end; ++j) {
      const double y = grid.y0 + j * step;
      for (int i = 0; i < grid.nx; ++i) {
        const double x = grid.x0 + i * step;
        const Ray outgoing = frame.sampleRayAt({c * x + s * y, -s * x + c * y});
        grid.values[static_cast<std::size_t>(j) * grid.nx + i] =
            kDefaultReferenceIlluminanceLx * model_->brdfSr(sun, outgoing) * sun.z;
      }
    }
  });
  if (side > 1) {
    cv::Mat values(grid.ny, grid.nx, CV_64F, grid.values.data());
    const cv::Mat weights(side, side, CV_64F, kernel.data());
    cv::Mat convolved;
    cv::filter2D(values, convolved, CV_64F, weights, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
    convolved.copyTo(values);  // into grid.values
  }
  return renderRays(camera, width, height, [&](const Ray& ray) {
    return lobe_.background_cd_m2 + lobe_.peak_scale * grid.sample(plane_.toPlane(ray));
  });
}

SceneTruths SurfaceScene::truth(double limit_cd_m2, double lit) const {
  // The surface's own luminance levels whose scene contours are asked for: at the reference,
  // B + s·L = level; as lit, lit · (B + s·L) = level.
  const auto surface_level = [&](double scene_level) {
    return (scene_level - lobe_.background_cd_m2) / lobe_.peak_scale;
  };
  surface::LobeOptions options;
  options.illuminance_lx = kDefaultReferenceIlluminanceLx;
  options.sun_half_angle_deg = lobe_.sun_half_angle_deg;
  const surface::LobeContours peak = surface::lobePeak(*model_, lobe_.alpha_deg, options);
  const double reference_peak = lobe_.background_cd_m2 + lobe_.peak_scale * peak.peak_cd_m2;
  const double levels[] = {surface_level(limit_cd_m2), surface_level(reference_peak / 2),
                           surface_level(limit_cd_m2 / lit)};
  const auto axes = [&](int k) -> std::optional<EllipseAxes> {
    if (!(levels[k] > 0)) return std::nullopt;  // the background alone reaches the level
    const surface::ContourAxes found = surface::contourAxes(*model_, peak, levels[k], options);
    if (!found.vertical_deg || !found.horizontal_deg) return std::nullopt;
    return measuredAxes(*found.vertical_deg, *found.horizontal_deg, lobe_.orientation_deg);
  };
  SceneTruths truths;
  truths.reference = {.peak_cd_m2 = reference_peak,
                      .limit_cd_m2 = limit_cd_m2,
                      .limit_axes = axes(0),
                      .fwhm_axes = axes(1)};
  truths.as_lit = {.peak_cd_m2 = lit * reference_peak,
                   .limit_cd_m2 = limit_cd_m2,
                   .limit_axes = axes(2),
                   .fwhm_axes = truths.reference.fwhm_axes};
  // The peak in the lobe's own axes (0, y), back into the image's plane.
  const double c = std::cos(radians(lobe_.orientation_deg)),
               s = std::sin(radians(lobe_.orientation_deg));
  const double y = peak.peak.y_deg;
  truths.peak_ray = plane_.toRay({-s * y, c * y});
  return truths;
}

}  // namespace glarecam::capture
