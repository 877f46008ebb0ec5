// The azimuthal equidistant plane around a viewing direction: a ray at angle rho from the
// centre, in direction psi, maps to rho (cos psi, sin psi), in degrees. psi is measured in the
// basis of the image horizontal (toward +x) and image vertical (toward +y, down) at the centre.
// Distances from the origin along any line through it are exact angles on the sky, so the full
// axis of an ellipse centred at the origin is the angle between the rays through its end
// points, wherever the ellipse sits in the image and whatever the lens distortion. Glare lobes
// are defined (capture/sim/glare_scene.h) and measured (pipeline/glare_ellipse.h) in it.
#pragma once

#include "calibration/camera_model.h"

namespace glarecam::calibration {

struct PlanePointDeg {
  double x_deg = 0, y_deg = 0;
};

class AngularPlane {
 public:
  explicit AngularPlane(const Ray& centre);

  PlanePointDeg toPlane(const Ray& ray) const;
  Ray toRay(const PlanePointDeg& point) const;
  const Ray& centre() const { return centre_; }

 private:
  Ray centre_, horizontal_, vertical_;  // centre and its tangent basis
};

// A ray's direction from the optical axis as [horizontal, vertical] angles: atan(x/z),
// atan(y/z) in degrees (positive right and down).
struct DirectionDeg {
  double horizontal_deg = 0, vertical_deg = 0;
};
DirectionDeg directionFromAxis(const Ray& ray);
Ray rayFromDirection(const DirectionDeg& direction);

}  // namespace glarecam::calibration
