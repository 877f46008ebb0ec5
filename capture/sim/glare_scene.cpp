#include "capture/sim/glare_scene.h"

#include <cmath>
#include <numbers>
#include <string>

#include "core/angles.h"

namespace glarecam::capture {
namespace {

// Radius (in units of sigma) of the contour at `level` of B + (P - B) exp(-r²/2).
double contourRadius(double peak, double background, double level) {
  return std::sqrt(2.0 * std::log((peak - background) / (level - background)));
}

}  // namespace

EllipseAxes measuredAxes(double own_vertical_deg, double own_horizontal_deg,
                         double orientation_deg) {
  // The lobe's major axis lies at its orientation, 90° further when the vertical one is longer.
  const double major_deg = orientation_deg + (own_vertical_deg > own_horizontal_deg ? 90.0 : 0.0);
  const double wrapped = std::abs(std::remainder(major_deg, 180.0));  // [0, 90]
  const bool major_is_vertical = wrapped >= 45.0;
  const double major = std::max(own_vertical_deg, own_horizontal_deg);
  const double minor = std::min(own_vertical_deg, own_horizontal_deg);
  return major_is_vertical ? EllipseAxes{major, minor} : EllipseAxes{minor, major};
}

Result<GlareLobe> lobeWithAxesAt(double level_cd_m2, double peak_cd_m2, double background_cd_m2,
                                 double vertical_deg, double horizontal_deg) {
  if (!(peak_cd_m2 > level_cd_m2 && level_cd_m2 > background_cd_m2 && background_cd_m2 >= 0)) {
    return badInput("glare scene: needs peak > level > background (peak " +
                    std::to_string(peak_cd_m2) + ", level " + std::to_string(level_cd_m2) +
                    ", background " + std::to_string(background_cd_m2) + " cd/m²)");
  }
  const double radius = contourRadius(peak_cd_m2, background_cd_m2, level_cd_m2);
  GlareLobe lobe;
  lobe.peak_cd_m2 = peak_cd_m2;
  lobe.background_cd_m2 = background_cd_m2;
  lobe.sigma_h_deg = horizontal_deg / 2.0 / radius;
  lobe.sigma_v_deg = vertical_deg / 2.0 / radius;
  return lobe;
}

Result<GlareScene> GlareScene::create(const GlareLobe& lobe) {
  const bool finite = std::isfinite(lobe.peak_cd_m2) && std::isfinite(lobe.background_cd_m2) &&
                      std::isfinite(lobe.sigma_h_deg) && std::isfinite(lobe.sigma_v_deg) &&
                      std::isfinite(lobe.orientation_deg);
  if (!finite || lobe.background_cd_m2 < 0 || !(lobe.peak_cd_m2 > 0)) {
    return badInput("glare scene: non-finite or non-positive parameters");
  }
  if (!(lobe.sigma_h_deg > 0 && lobe.sigma_v_deg > 0 && lobe.sigma_h_deg < 45 &&
        lobe.sigma_v_deg < 45)) {
    return badInput("glare scene: lobe widths must be between 0 and 45 degrees");
  }
  return GlareScene(lobe);
}

GlareScene::GlareScene(const GlareLobe& lobe)
    : lobe_(lobe),
      plane_(calibration::rayFromDirection(
          {lobe.centre_direction_deg[0], lobe.centre_direction_deg[1]})) {}

double GlareScene::luminanceCdM2(const calibration::Ray& ray) const {
  const calibration::PlanePointDeg point = plane_.toPlane(ray);
  // Into the lobe's own axes, rotated by its orientation from the image horizontal.
  const double c = std::cos(radians(lobe_.orientation_deg)),
               s = std::sin(radians(lobe_.orientation_deg));
  const double u = (c * point.x_deg + s * point.y_deg) / lobe_.sigma_h_deg;
  const double w = (-s * point.x_deg + c * point.y_deg) / lobe_.sigma_v_deg;
  return lobe_.background_cd_m2 +
         (lobe_.peak_cd_m2 - lobe_.background_cd_m2) * std::exp(-0.5 * (u * u + w * w));
}

std::optional<EllipseAxes> GlareScene::axesAt(double level_cd_m2) const {
  if (!(lobe_.peak_cd_m2 > level_cd_m2 && level_cd_m2 > lobe_.background_cd_m2))
    return std::nullopt;
  const double radius = contourRadius(lobe_.peak_cd_m2, lobe_.background_cd_m2, level_cd_m2);
  const double own_vertical = 2.0 * lobe_.sigma_v_deg * radius;
  const double own_horizontal = 2.0 * lobe_.sigma_h_deg * radius;
  return measuredAxes(own_vertical, own_horizontal, lobe_.orientation_deg);
}

SceneTruth GlareScene::truth(double limit_cd_m2) const {
  return {.peak_cd_m2 = lobe_.peak_cd_m2,
          .limit_cd_m2 = limit_cd_m2,
          .limit_axes = axesAt(limit_cd_m2),
          .fwhm_axes = axesAt(lobe_.peak_cd_m2 / 2.0)};
}

FloatImage GlareScene::render(const calibration::CameraModel& camera, int width, int height) const {
  return renderRays(camera, width, height,
                    [this](const calibration::Ray& ray) { return luminanceCdM2(ray); });
}

}  // namespace glarecam::capture
