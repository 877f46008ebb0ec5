// A synthetic glare scene with known ground truth: an elliptical Gaussian lobe of luminance
// over a uniform background, defined on the sphere of viewing directions (azimuthal
// equidistant coordinates around the lobe centre), so that the angle between the rays through
// the two ends of an iso-contour axis is exactly that axis's length in degrees, whatever the
// lens distortion and wherever the lobe sits in the image.
//   L(theta) = B + (P - B) exp(-r²/2),  r² = (u / sigma_h)² + (v / sigma_v)²
// lobeWithAxesAt() picks sigma_h and sigma_v so that one iso-contour (the glare limit) has
// given full axes; the axes at any other level (the limit, half maximum) follow analytically.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "calibration/angular_plane.h"
#include "calibration/camera_model.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parallel.h"

namespace glarecam::capture {

struct GlareLobe {
  double peak_cd_m2 = 0;
  double background_cd_m2 = 0;
  double sigma_h_deg = 0;      // Gaussian width along the lobe's horizontal axis (angular)
  double sigma_v_deg = 0;      // ... and along its vertical axis
  double orientation_deg = 0;  // rotation of the horizontal axis from image horizontal
  std::array<double, 2> centre_direction_deg{0, 0};  // [horizontal, vertical] from the optical axis
};

// The lobe whose iso-contour at `level_cd_m2` has the given full axes (needs peak > level >
// background).
Result<GlareLobe> lobeWithAxesAt(double level_cd_m2, double peak_cd_m2, double background_cd_m2,
                                 double vertical_deg, double horizontal_deg);

struct EllipseAxes {
  double vertical_deg = 0, horizontal_deg = 0;
};

// A lobe's own full axes (along its vertical and horizontal) named as the measurement names them
// (pipeline/glare_ellipse.h): vertical is the axis closer to the image vertical, at exactly 45°
// the major one; the lobe's own horizontal axis lies at `orientation_deg` from the horizontal.
EllipseAxes measuredAxes(double own_vertical_deg, double own_horizontal_deg,
                         double orientation_deg);

struct SceneTruth {
  double peak_cd_m2 = 0;
  double limit_cd_m2 = 0;
  std::optional<EllipseAxes> limit_axes;  // none when the peak does not reach the limit
  std::optional<EllipseAxes> fwhm_axes;   // none when the peak is not above twice the background
};

// The image of a scene: `luminance(ray)` of each pixel's ray of the camera, rows in parallel.
template <typename Luminance>
FloatImage renderRays(const calibration::CameraModel& camera, int width, int height,
                      const Luminance& luminance) {
  FloatImage image(width, height);
  parallelRows(height, availableThreads(), [&](int begin, int end) {
    std::vector<calibration::PixelPoint> pixels(static_cast<std::size_t>(width));
    for (int y = begin; y < end; ++y) {
      for (int x = 0; x < width; ++x)
        pixels[static_cast<std::size_t>(x)] = {static_cast<double>(x), static_cast<double>(y)};
      const auto rays = camera.rays(pixels);
      auto row = image.row(y);
      for (int x = 0; x < width; ++x)
        row[static_cast<std::size_t>(x)] =
            static_cast<float>(luminance(rays[static_cast<std::size_t>(x)]));
    }
  });
  return image;
}

class GlareScene {
 public:
  static Result<GlareScene> create(const GlareLobe& lobe);

  double luminanceCdM2(const calibration::Ray& ray) const;
  // Full axes of the iso-contour at `level_cd_m2`, when the lobe reaches it, named vertical and
  // horizontal as the measurement names them (the axis closer to the vertical is vertical,
  // whatever the lobe's orientation), so that truth and result compare key by key.
  std::optional<EllipseAxes> axesAt(double level_cd_m2) const;
  SceneTruth truth(double limit_cd_m2) const;
  const GlareLobe& lobe() const { return lobe_; }
  calibration::Ray centreRay() const { return plane_.centre(); }

  // The true luminance seen by each pixel of a camera.
  FloatImage render(const calibration::CameraModel& camera, int width, int height) const;

 private:
  explicit GlareScene(const GlareLobe& lobe);

  GlareLobe lobe_;
  calibration::AngularPlane plane_;  // around the lobe centre
};

}  // namespace glarecam::capture
