// The simulator's glare scene: contours with the requested axes on the sphere, the truth naming
// axes like the measurement, and an off-axis lobe keeping its angular size.
#include "capture/sim/glare_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/angles.h"

namespace glarecam::capture {
namespace {

// A point `angle_deg` away from `base` on the great circle towards `towards`.
calibration::Ray rotateTowards(const calibration::Ray& base, calibration::Ray towards,
                               double angle_deg) {
  const double d = towards.x * base.x + towards.y * base.y + towards.z * base.z;
  calibration::Ray t{towards.x - d * base.x, towards.y - d * base.y, towards.z - d * base.z};
  const double n = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  const double a = radians(angle_deg);
  return {std::cos(a) * base.x + std::sin(a) * t.x / n,
          std::cos(a) * base.y + std::sin(a) * t.y / n,
          std::cos(a) * base.z + std::sin(a) * t.z / n};
}

TEST(GlareScene, ContoursHaveTheRequestedAxesOnTheSphere) {
  auto lobe = lobeWithAxesAt(30000, 600000, 3000, 6.0, 4.0);
  ASSERT_TRUE(lobe);
  auto scene = GlareScene::create(*lobe);
  ASSERT_TRUE(scene);
  const calibration::Ray centre = scene->centreRay();
  // The limit contour passes 3° up and down and 2° left and right of the centre; the
  // tolerance is float-free double arithmetic, so 1e-6 cd/m² is generous.
  EXPECT_NEAR(scene->luminanceCdM2(rotateTowards(centre, {0, 1, 0}, 3.0)), 30000.0, 1e-6);
  EXPECT_NEAR(scene->luminanceCdM2(rotateTowards(centre, {0, -1, 0}, 3.0)), 30000.0, 1e-6);
  EXPECT_NEAR(scene->luminanceCdM2(rotateTowards(centre, {1, 0, 0}, 2.0)), 30000.0, 1e-6);
  EXPECT_NEAR(scene->luminanceCdM2(centre), 600000.0, 1e-6);
  const SceneTruth truth = scene->truth(30000);
  ASSERT_TRUE(truth.limit_axes && truth.fwhm_axes);
  EXPECT_NEAR(truth.limit_axes->vertical_deg, 6.0, 1e-12);
  EXPECT_NEAR(
      scene->luminanceCdM2(rotateTowards(centre, {0, 1, 0}, truth.fwhm_axes->vertical_deg / 2)),
      300000.0, 1e-6);
}

// Truth names the axes as the measurement does: the axis closer to the vertical is vertical,
// so a lobe turned by 90° swaps them, one turned by 30° does not, and at exactly 45° the major
// axis is the vertical one.
TEST(GlareScene, TruthNamesAxesLikeTheMeasurement) {
  const auto truthAt = [](double orientation_deg) {
    auto lobe = lobeWithAxesAt(30000, 600000, 3000, 6.0, 4.0);  // vertical 6, horizontal 4
    lobe->orientation_deg = orientation_deg;
    return *GlareScene::create(*lobe)->truth(30000).limit_axes;
  };
  for (const double orientation : {0.0, 30.0, -30.0, 180.0, 44.0}) {
    EXPECT_NEAR(truthAt(orientation).vertical_deg, 6.0, 1e-12) << orientation;
    EXPECT_NEAR(truthAt(orientation).horizontal_deg, 4.0, 1e-12) << orientation;
  }
  for (const double orientation : {90.0, -90.0, 60.0, 270.0}) {
    EXPECT_NEAR(truthAt(orientation).vertical_deg, 4.0, 1e-12) << orientation;
    EXPECT_NEAR(truthAt(orientation).horizontal_deg, 6.0, 1e-12) << orientation;
  }
  EXPECT_NEAR(truthAt(45.0).vertical_deg, 6.0, 1e-12);  // the major axis lies at 135° = -45°
}

TEST(GlareScene, OffAxisLobeKeepsItsAngularSize) {
  auto lobe = lobeWithAxesAt(30000, 600000, 3000, 5.0, 5.0);  // circular: any direction is an axis
  ASSERT_TRUE(lobe);
  lobe->centre_direction_deg = {14.0, -9.0};
  auto scene = GlareScene::create(*lobe);
  ASSERT_TRUE(scene);
  const calibration::Ray centre = scene->centreRay();
  for (const calibration::Ray& towards :
       {calibration::Ray{1, 0, 0}, calibration::Ray{0, 1, 0}, calibration::Ray{1, 1, 0}}) {
    EXPECT_NEAR(scene->luminanceCdM2(rotateTowards(centre, towards, 2.5)), 30000.0, 1e-6);
  }
}

}  // namespace
}  // namespace glarecam::capture
