// A synthetic glare scene drawn from a physical surface (surface/brdf_model.h) instead of the
// empirical curves: the luminance a module of that surface reflects toward each viewing direction
// under the sun at α, over a uniform background (the sky in its glass), in the same azimuthal
// equidistant plane around the specular direction as GlareScene (calibration/angular_plane.h):
//   L(p) = B + s · E_ref · ⟨f_r(i, o(p)) cos θ_i⟩_disc
// (s the scene's peak scale, the mean over the sun's disc). The lobe's own vertical is the plane
// of incidence (the specular frame's y, surface/specular_frame.h), rotated by the orientation.
//
// render() evaluates the point-source luminance on a square grid of the angular plane covering
// the frame, at most 0.05° and at most a pixel apart, convolves it with the disc (a shift in the
// plane: to first order what the incidence does) and samples each pixel's ray bicubically. The
// truth comes from surface/lobeContours() instead, which integrates over the incidence and never
// touches the grid: the difference between the two is the simulator's own error, which the
// truth tests measure with the rest.
#pragma once

#include <array>
#include <memory>

#include "calibration/angular_plane.h"
#include "calibration/camera_model.h"
#include "capture/sim/glare_scene.h"
#include "core/error.h"
#include "core/image.h"
#include "surface/brdf_model.h"
#include "surface/sun_disc.h"

namespace glarecam::capture {

struct SurfaceLobe {
  double alpha_deg = 0;
  double background_cd_m2 = 0;  // at the reference illuminance
  double peak_scale = 1;        // multiplies the surface's reflection (not the background)
  double orientation_deg = 0;   // of the lobe's horizontal axis from the image horizontal
  std::array<double, 2> centre_direction_deg{0, 0};       // the specular direction [h, v]
  double sun_half_angle_deg = surface::kSunHalfAngleDeg;  // 0: a point source
};

// The truth of a scene at the reference illuminance and as lit by a source `lit` times as bright.
struct SceneTruths {
  SceneTruth reference, as_lit;
  calibration::Ray peak_ray;  // where the peak is seen
};

class SurfaceScene {
 public:
  static Result<SurfaceScene> create(std::shared_ptr<const surface::BrdfModel> model,
                                     const SurfaceLobe& lobe);

  // The true luminance at the reference illuminance seen by each pixel of a camera.
  FloatImage render(const calibration::CameraModel& camera, int width, int height) const;
  // From the surface's own contours (surface/lobe_contours.h), independent of render().
  SceneTruths truth(double limit_cd_m2, double lit) const;
  calibration::Ray centreRay() const { return plane_.centre(); }
  const SurfaceLobe& lobe() const { return lobe_; }

 private:
  SurfaceScene(std::shared_ptr<const surface::BrdfModel> model, const SurfaceLobe& lobe);

  std::shared_ptr<const surface::BrdfModel> model_;
  SurfaceLobe lobe_;
  calibration::AngularPlane plane_;  // around the specular direction
};

}  // namespace glarecam::capture
