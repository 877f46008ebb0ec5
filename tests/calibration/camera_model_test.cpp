#include "calibration/camera_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glarecam::calibration {
namespace {

TEST(CameraModel, PrincipalPointLooksAlongTheOpticalAxis) {
  const CameraModel camera({1000, 1000, 320, 240, {}});
  const Ray ray = camera.ray({320, 240});
  EXPECT_NEAR(ray.z, 1.0, 1e-12);
  // A pixel f px to the right of the principal point is 45° off axis.
  EXPECT_NEAR(angleBetweenDeg(ray, camera.ray({1320, 240})), 45.0, 1e-9);
}

TEST(CameraModel, ProjectInvertsRaysWithDistortion) {
  const CameraModel camera({1200, 1180, 640, 480, {-0.25, 0.08, 0.001, -0.0005, 0.01}});
  for (double x : {0.0, 200.0, 640.0, 1100.0, 1279.0}) {
    for (double y : {0.0, 300.0, 959.0}) {
      const PixelPoint back = camera.project(camera.ray({x, y}));
      // undistortPoints iterates to 1e-12 in normalised units; 1e-3 px is far below any use.
      EXPECT_NEAR(back.x, x, 1e-3) << x << "," << y;
      EXPECT_NEAR(back.y, y, 1e-3) << x << "," << y;
    }
  }
}

TEST(CameraModel, SmallAnglesAreAccurate) {
  const CameraModel camera({2400, 2400, 1223.5, 1023.5, {}});
  // One pixel at the centre subtends atan(1/2400).
  EXPECT_NEAR(angleBetweenDeg(camera.ray({1223.5, 1023.5}), camera.ray({1224.5, 1023.5})),
              std::atan(1.0 / 2400) * 180 / M_PI, 1e-9);
}

}  // namespace
}  // namespace glarecam::calibration
