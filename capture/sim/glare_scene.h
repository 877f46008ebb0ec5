// A synthetic glare scene with known ground truth: an elliptical Gaussian lobe of luminance
// over a uniform background, defined on the sphere of viewing directions (azimuthal
// equidistant coordinates around the lobe centre), so that the angle between the rays through
// the two ends of an iso-contour axis is exactly that axis's length in degrees, whatever the
// lens distortion and wherever the lobe sits in the image.
//   L(theta) = B + (P - B) exp(-r²/2),  r² = (u / sigma_h)² + (v / sigma_v)²
// sigma_h and sigma_v are chosen so that the iso-contour at `limit_cd_m2` has the requested
// full axes; the FWHM axes follow analytically.
#pragma once

#include <array>

#include "calibration/camera_model.h"
#include "core/error.h"
#include "core/image.h"

namespace glarecam::capture {

struct GlareLobe {
  double peak_cd_m2 = 0;
  double background_cd_m2 = 0;
  double limit_cd_m2 = 0;      // iso-contour at which the axes below hold
  double vertical_deg = 0;     // full axis at the limit, along the image vertical when orientation is 0
  double horizontal_deg = 0;   // full axis at the limit, along the image horizontal
  double orientation_deg = 0;  // rotation of the horizontal axis from image horizontal
  std::array<double, 2> centre_direction_deg{0, 0};  // [horizontal, vertical] from the optical axis
};

struct SceneTruth {
  double peak_cd_m2 = 0;
  double limit_cd_m2 = 0;
  double limit_vertical_deg = 0, limit_horizontal_deg = 0;
  double fwhm_vertical_deg = 0, fwhm_horizontal_deg = 0;
};

class GlareScene {
 public:
  // Refuses lobes without a contour at the limit (needs peak > limit > background) or
  // without a half-maximum contour (needs peak > 2 background).
  static Result<GlareScene> create(const GlareLobe& lobe);

  double luminanceCdM2(const calibration::Ray& ray) const;
  SceneTruth truth() const;
  const GlareLobe& lobe() const { return lobe_; }
  calibration::Ray centreRay() const { return centre_; }

  // The true luminance seen by each pixel of a camera.
  FloatImage render(const calibration::CameraModel& camera, int width, int height) const;

 private:
  explicit GlareScene(const GlareLobe& lobe);
  double fullAxisDeg(double level_cd_m2, double sigma_rad) const;

  GlareLobe lobe_;
  calibration::Ray centre_, axis_h_, axis_v_;  // lobe centre and its tangent-plane basis
  double sigma_h_rad_ = 0, sigma_v_rad_ = 0;
};

}  // namespace glarecam::capture
