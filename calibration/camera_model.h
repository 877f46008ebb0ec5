// The camera's geometric model: OpenCV's pinhole + distortion (k1, k2, p1, p2, k3), pixel
// centres at integer coordinates, x right, y down, z along the optical axis. Converts pixels
// to unit viewing rays (undistorting) and rays back to pixels (distorting), so that sizes
// measured in the image become angles independent of lens distortion and of where the spot is.
#pragma once

#include <span>
#include <vector>

#include "core/stack_manifest.h"

namespace glarecam::calibration {

struct PixelPoint {
  double x = 0, y = 0;
};

struct Ray {  // unit vector
  double x = 0, y = 0, z = 1;
};

double angleBetweenDeg(const Ray& a, const Ray& b);

class CameraModel {
 public:
  explicit CameraModel(const Intrinsics& intrinsics) : intrinsics_(intrinsics) {}

  const Intrinsics& intrinsics() const { return intrinsics_; }
  bool hasDistortion() const;

  // Viewing rays through many pixels at once (OpenCV undistortPoints, iterated to 1e-10 px).
  std::vector<Ray> rays(std::span<const PixelPoint> pixels) const;
  Ray ray(const PixelPoint& pixel) const;
  // Pixel where a ray in front of the camera (z > 0) lands.
  PixelPoint project(const Ray& ray) const;

 private:
  Intrinsics intrinsics_;
};

}  // namespace glarecam::calibration
