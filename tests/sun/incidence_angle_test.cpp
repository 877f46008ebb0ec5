// The angle of incidence α between the sun (or a lamp) and the module's normal, on geometries
// whose answer is known by construction and against the textbook formula.
#include "sun/incidence_angle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/angles.h"
#include "support/test_support.h"

namespace glarecam::sun {
namespace {

using testing::kExactDeg;

// α on geometries whose answer is known by construction. The bound is 0.05°; these are
// exact in doubles.
TEST(IncidenceAngle, ConstructedGeometries) {
  EXPECT_NEAR(sun::incidenceAngleDeg({0, 180}, {35, 123}), 55, kExactDeg);  // flat: 90° − elevation
  EXPECT_NEAR(sun::incidenceAngleDeg({30, 180}, {60, 180}), 0,
              1e-6);                                                // sun on the normal (acos at 1)
  EXPECT_NEAR(sun::incidenceAngleDeg({90, 90}, {0, 90}), 0, 1e-6);  // vertical east wall, sunrise
  EXPECT_NEAR(sun::incidenceAngleDeg({90, 90}, {0, 180}), 90, kExactDeg);
  EXPECT_NEAR(sun::incidenceAngleDeg({90, 90}, {0, 270}), 180, 1e-6);  // behind
  EXPECT_NEAR(sun::incidenceAngleDeg({30, 180}, {30, 180}), 30, kExactDeg);
  EXPECT_NEAR(sun::incidenceAngleDeg({30, 180}, {30, 180 + 360}), 30, kExactDeg);
}

// Against the textbook formula (Duffie & Beckman, Solar Engineering of Thermal Processes, eq.
// 1.6.5 with the zenith angle): cos α = cos θz cos β + sin θz sin β cos(γs − γ).
TEST(IncidenceAngle, AgreesWithTheTextbookFormula) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> tilt(0, 90), azimuth(0, 360), elevation(0, 90);
  for (int i = 0; i < 1000; ++i) {
    const sun::ModuleOrientation module{tilt(random), azimuth(random)};
    const sun::SkyDirection sun{elevation(random), azimuth(random)};
    const double zenith = radians(90 - sun.elevation_deg);
    const double cosine = std::cos(zenith) * std::cos(radians(module.tilt_deg)) +
                          std::sin(zenith) * std::sin(radians(module.tilt_deg)) *
                              std::cos(radians(sun.azimuth_deg - module.azimuth_deg));
    // acos near 0° amplifies rounding (1e-16 in the cosine → 1e-6°): 1e-6° is rounding.
    EXPECT_NEAR(sun::incidenceAngleDeg(module, sun),
                degrees(std::acos(std::clamp(cosine, -1.0, 1.0))), 1e-6);
  }
}

}  // namespace
}  // namespace glarecam::sun
