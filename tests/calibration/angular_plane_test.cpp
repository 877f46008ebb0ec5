#include "calibration/angular_plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "calibration/camera_model.h"
#include "core/angles.h"

namespace glarecam::calibration {
namespace {

Ray unit(double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  return {x / n, y / n, z / n};
}

// Centres used throughout: on the optical axis, off axis in each quadrant, far off axis.
std::vector<Ray> centres() {
  return {unit(0, 0, 1),
          rayFromDirection({12.0, -7.5}),
          rayFromDirection({-25.0, 18.0}),
          rayFromDirection({3.0, 30.0}),
          rayFromDirection({-40.0, -35.0}),
          unit(0.6, 0.5, 0.62)};
}

// Rays around a centre: within `max_angle_deg` of it, in every direction.
std::vector<Ray> raysAround(const Ray& centre, double max_angle_deg, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> cosine(std::cos(radians(max_angle_deg)), 1.0);
  std::uniform_real_distribution<double> azimuth(-std::numbers::pi, std::numbers::pi);
  // A basis around the centre (any will do).
  const Ray helper = std::abs(centre.x) < 0.9 ? Ray{1, 0, 0} : Ray{0, 1, 0};
  const Ray u =
      unit(centre.y * helper.z - centre.z * helper.y, centre.z * helper.x - centre.x * helper.z,
           centre.x * helper.y - centre.y * helper.x);
  const Ray v = {centre.y * u.z - centre.z * u.y, centre.z * u.x - centre.x * u.z,
                 centre.x * u.y - centre.y * u.x};
  std::vector<Ray> rays;
  for (int i = 0; i < 200; ++i) {
    const double c = cosine(rng), s = std::sqrt(1 - c * c), phi = azimuth(rng);
    rays.push_back(unit(c * centre.x + s * (std::cos(phi) * u.x + std::sin(phi) * v.x),
                        c * centre.y + s * (std::cos(phi) * u.y + std::sin(phi) * v.y),
                        c * centre.z + s * (std::cos(phi) * u.z + std::sin(phi) * v.z)));
  }
  return rays;
}

TEST(AngularPlane, RoundTripsRays) {
  // Double rounding only: a few ulps of 1 per component; 1e-12 as required.
  constexpr double kTolerance = 1e-12;
  unsigned seed = 1;
  for (const Ray& centre : centres()) {
    const AngularPlane plane(centre);
    for (const Ray& ray : raysAround(centre, 120.0, seed++)) {
      const Ray back = plane.toRay(plane.toPlane(ray));
      EXPECT_NEAR(back.x, ray.x, kTolerance);
      EXPECT_NEAR(back.y, ray.y, kTolerance);
      EXPECT_NEAR(back.z, ray.z, kTolerance);
    }
  }
}

TEST(AngularPlane, DistanceFromTheOriginIsTheAngleFromTheCentre) {
  // Both are atan2 of double-precision sines and cosines: ~1e-15 rad, i.e. ~1e-13 deg; 1e-10
  // deg allows for the different formulas and is far below any use (a pixel is ~1e-2 deg).
  constexpr double kToleranceDeg = 1e-10;
  unsigned seed = 100;
  for (const Ray& centre : centres()) {
    const AngularPlane plane(centre);
    for (const Ray& ray : raysAround(centre, 150.0, seed++)) {
      const PlanePointDeg p = plane.toPlane(ray);
      EXPECT_NEAR(std::hypot(p.x_deg, p.y_deg), angleBetweenDeg(ray, plane.centre()),
                  kToleranceDeg);
    }
    // Small angles too (no loss of precision near the centre): 1e-6 deg off the centre.
    const Ray near = rayFromDirection(
        {directionFromAxis(centre).horizontal_deg + 1e-6, directionFromAxis(centre).vertical_deg});
    const PlanePointDeg p = plane.toPlane(near);
    EXPECT_NEAR(std::hypot(p.x_deg, p.y_deg) / angleBetweenDeg(near, plane.centre()), 1.0, 1e-6);
  }
}

TEST(AngularPlane, CentreMapsToTheOrigin) {
  // Rounding only: the centre's components along the tangent basis are ~1e-16.
  for (const Ray& centre : centres()) {
    const AngularPlane plane(centre);
    const PlanePointDeg p = plane.toPlane(centre);
    EXPECT_NEAR(p.x_deg, 0.0, 1e-12);
    EXPECT_NEAR(p.y_deg, 0.0, 1e-12);
    const Ray back = plane.toRay({0, 0});
    EXPECT_NEAR(back.x, plane.centre().x, 1e-15);
    EXPECT_NEAR(back.y, plane.centre().y, 1e-15);
    EXPECT_NEAR(back.z, plane.centre().z, 1e-15);
  }
}

TEST(AngularPlane, CentreIsNormalised) {
  const AngularPlane plane(Ray{0.3, -0.2, 2.0});  // not a unit vector
  const Ray& c = plane.centre();
  EXPECT_NEAR(std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z), 1.0, 1e-15);
  EXPECT_NEAR(c.x / c.z, 0.15, 1e-15);
  EXPECT_NEAR(c.y / c.z, -0.1, 1e-15);
  // The same plane as from the unit centre.
  const AngularPlane unit_plane(unit(0.3, -0.2, 2.0));
  const Ray ray = unit(0.1, 0.05, 1.0);
  EXPECT_NEAR(plane.toPlane(ray).x_deg, unit_plane.toPlane(ray).x_deg, 1e-12);
  EXPECT_NEAR(plane.toPlane(ray).y_deg, unit_plane.toPlane(ray).y_deg, 1e-12);
}

TEST(AngularPlane, OnAxisCentreMapsImageXAndYToPlaneXAndY) {
  // Rounding only (~1e-14 deg).
  constexpr double kToleranceDeg = 1e-12;
  const AngularPlane plane(Ray{0, 0, 1});
  for (const double angle_deg : {0.5, 10.0, 45.0, 89.0, 120.0}) {
    const double s = std::sin(radians(angle_deg)), c = std::cos(radians(angle_deg));
    const PlanePointDeg right = plane.toPlane({s, 0, c});
    EXPECT_NEAR(right.x_deg, angle_deg, kToleranceDeg);
    EXPECT_NEAR(right.y_deg, 0.0, kToleranceDeg);
    const PlanePointDeg down = plane.toPlane({0, s, c});  // +y is down in the image
    EXPECT_NEAR(down.x_deg, 0.0, kToleranceDeg);
    EXPECT_NEAR(down.y_deg, angle_deg, kToleranceDeg);
    const PlanePointDeg left = plane.toPlane({-s, 0, c});
    EXPECT_NEAR(left.x_deg, -angle_deg, kToleranceDeg);
    const PlanePointDeg up = plane.toPlane({0, -s, c});
    EXPECT_NEAR(up.y_deg, -angle_deg, kToleranceDeg);
    // Diagonal: the direction psi is kept, the distance is the angle.
    const PlanePointDeg diagonal = plane.toPlane({s * std::sqrt(0.5), s * std::sqrt(0.5), c});
    EXPECT_NEAR(diagonal.x_deg, angle_deg * std::sqrt(0.5), kToleranceDeg);
    EXPECT_NEAR(diagonal.y_deg, angle_deg * std::sqrt(0.5), kToleranceDeg);
  }
}

TEST(AngularPlane, OffAxisCentreKeepsTheImageHorizontalAtTheCentre) {
  // A small step from the centre to the right in the image (larger x/z, same y/z) goes along
  // plane +x exactly: the plane's horizontal is the image horizontal made perpendicular to the
  // centre. Rounding only: 1e-9 of the step.
  constexpr double kStep = radians(1e-4);
  for (const Ray& centre : centres()) {
    const AngularPlane plane(centre);
    const double x = centre.x / centre.z, y = centre.y / centre.z;
    const PlanePointDeg right = plane.toPlane(unit(x + kStep, y, 1));
    EXPECT_GT(right.x_deg, 0);
    EXPECT_LT(std::abs(right.y_deg), 1e-9 * right.x_deg);
    // A step down in the image goes toward plane +y, but off axis the pinhole projection is not
    // conformal: image x and y are not perpendicular on the sky (their tangents at c make
    // cos = -cx cy / ...), so the step leans by the shear between them. Its direction is that
    // of the image-y tangent e_y - c cy in the plane's basis (h = e_x - c cx normalised,
    // v = c x h); first order in the step: 1e-4 deg steps leave ~1e-6 relative, allow 1e-4.
    const PlanePointDeg down = plane.toPlane(unit(x, y + kStep, 1));
    EXPECT_GT(down.y_deg, 0);
    const Ray& c = plane.centre();
    const Ray h = unit(1 - c.x * c.x, -c.x * c.y, -c.x * c.z);
    const Ray v = {c.y * h.z - c.z * h.y, c.z * h.x - c.x * h.z, c.x * h.y - c.y * h.x};
    const double ty_x = -c.y * c.x, ty_y = 1 - c.y * c.y, ty_z = -c.y * c.z;  // e_y - c cy
    const double along_h = ty_x * h.x + ty_y * h.y + ty_z * h.z;
    const double along_v = ty_x * v.x + ty_y * v.y + ty_z * v.z;
    EXPECT_NEAR(down.x_deg / down.y_deg, along_h / along_v, 1e-4);
    // On the optical axis (or on either image axis through it) there is no shear.
    if (c.x == 0 || c.y == 0) {
      EXPECT_NEAR(down.x_deg, 0.0, 1e-9 * down.y_deg);
    }
  }
}

TEST(AngularPlane, OppositePointsSpanTheSumOfTheirDistances) {
  // Lines through the origin are great circles through the centre: two points on opposite
  // sides are rho1 + rho2 apart on the sky, wherever the centre. Rounding only: 1e-10 deg.
  constexpr double kToleranceDeg = 1e-10;
  for (const Ray& centre : centres()) {
    const AngularPlane plane(centre);
    for (const double psi_deg : {0.0, 17.0, 90.0, 133.0, -70.0}) {
      const double cx = std::cos(radians(psi_deg)), cy = std::sin(radians(psi_deg));
      for (const auto& [rho1, rho2] :
           {std::pair{1.0, 1.0}, std::pair{2.5, 7.25}, std::pair{20.0, 35.0}, std::pair{0.01, 0.02},
            std::pair{60.0, 80.0}}) {
        const Ray a = plane.toRay({rho1 * cx, rho1 * cy});
        const Ray b = plane.toRay({-rho2 * cx, -rho2 * cy});
        EXPECT_NEAR(angleBetweenDeg(a, b), rho1 + rho2, kToleranceDeg)
            << "psi " << psi_deg << ", rho " << rho1 << " + " << rho2;
        // And each is its distance from the centre.
        EXPECT_NEAR(angleBetweenDeg(a, plane.centre()), rho1, kToleranceDeg);
        EXPECT_NEAR(angleBetweenDeg(b, plane.centre()), rho2, kToleranceDeg);
      }
    }
  }
}

TEST(AngularPlane, PointsOffTheLineAreNotAdditive) {
  // Contrast: distances add only along lines through the origin. Two points at 10° either side
  // of the origin but not opposite (90° apart in psi) are ~14.1°, not 20°, apart.
  const AngularPlane plane(rayFromDirection({15.0, -10.0}));
  const Ray a = plane.toRay({10, 0}), b = plane.toRay({0, 10});
  const double expected = degrees(std::acos(std::cos(radians(10.0)) * std::cos(radians(10.0))));
  EXPECT_NEAR(angleBetweenDeg(a, b), expected, 1e-10);  // spherical law of cosines
}

TEST(AngularPlane, DirectionFromAxisRoundTrips) {
  // Rounding only: 1e-12 in degrees and in ray components.
  constexpr double kTolerance = 1e-12;
  for (const double h : {-80.0, -30.0, -0.5, 0.0, 12.0, 45.0, 79.0}) {
    for (const double v : {-75.0, -10.0, 0.0, 3.3, 60.0}) {
      const DirectionDeg back = directionFromAxis(rayFromDirection({h, v}));
      EXPECT_NEAR(back.horizontal_deg, h, kTolerance) << h << ", " << v;
      EXPECT_NEAR(back.vertical_deg, v, kTolerance) << h << ", " << v;
    }
  }
  unsigned seed = 9;
  for (const Ray& ray : raysAround(Ray{0, 0, 1}, 80.0, seed)) {
    const Ray back = rayFromDirection(directionFromAxis(ray));
    EXPECT_NEAR(back.x, ray.x, kTolerance);
    EXPECT_NEAR(back.y, ray.y, kTolerance);
    EXPECT_NEAR(back.z, ray.z, kTolerance);
  }
}

TEST(AngularPlane, DirectionFromAxisConventions) {
  // Positive right and down; the axis is (0, 0); atan(x/z), atan(y/z) per axis.
  const DirectionDeg axis = directionFromAxis({0, 0, 1});
  EXPECT_EQ(axis.horizontal_deg, 0.0);
  EXPECT_EQ(axis.vertical_deg, 0.0);
  const DirectionDeg d = directionFromAxis(unit(1, -1, 1));
  EXPECT_NEAR(d.horizontal_deg, 45.0, 1e-12);
  EXPECT_NEAR(d.vertical_deg, -45.0, 1e-12);
  const Ray r = rayFromDirection({30.0, 0.0});
  EXPECT_NEAR(r.x, std::sin(radians(30)), 1e-15);
  EXPECT_NEAR(r.y, 0.0, 1e-15);
  EXPECT_NEAR(r.z, std::cos(radians(30)), 1e-15);
  // A unit vector.
  const Ray s = rayFromDirection({-20.0, 35.0});
  EXPECT_NEAR(s.x * s.x + s.y * s.y + s.z * s.z, 1.0, 1e-15);
  EXPECT_LT(s.x, 0);
  EXPECT_GT(s.y, 0);
}

}  // namespace
}  // namespace glarecam::calibration
