#include "calibration/camera_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <vector>

#include "core/angles.h"

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
              degrees(std::atan(1.0 / 2400)), 1e-9);
}

// The forward model against OpenCV's own (cv::projectPoints): every angle glarecam measures
// rests on CameraModel agreeing with the model the intrinsics were calibrated in, and the
// simulator renders through the same CameraModel, so this is the independent check.
TEST(CameraModel, ProjectAgreesWithOpenCv) {
  const Intrinsics k{1200, 1180, 640, 480, {-0.25, 0.08, 0.001, -0.0005, 0.01}};
  const CameraModel camera(k);
  std::vector<cv::Point3d> points;
  std::vector<Ray> rays;
  for (double hx : {-0.5, -0.2, 0.0, 0.3, 0.55}) {
    for (double hy : {-0.4, 0.0, 0.1, 0.45}) {
      const double n = std::sqrt(hx * hx + hy * hy + 1);
      rays.push_back({hx / n, hy / n, 1 / n});
      points.emplace_back(hx, hy, 1.0);
    }
  }
  const cv::Matx33d matrix(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  const cv::Matx<double, 1, 5> distortion(k.distortion[0], k.distortion[1], k.distortion[2],
                                          k.distortion[3], k.distortion[4]);
  std::vector<cv::Point2d> expected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), matrix, distortion, expected);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const PixelPoint p = camera.project(rays[i]);
    // Same polynomial, evaluated in another order: agreement to rounding (1e-9 px).
    EXPECT_NEAR(p.x, expected[i].x, 1e-9) << i;
    EXPECT_NEAR(p.y, expected[i].y, 1e-9) << i;
  }
}

}  // namespace
}  // namespace glarecam::calibration
