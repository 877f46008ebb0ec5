#include "surface/specular_frame.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/test_support.h"

namespace glarecam::surface {
namespace {

using glarecam::testing::kExactDeg;

TEST(SpecularFrame, TheSpecularDirectionIsTheOrigin) {
  for (double phi : {0.0, 90.0, 217.0}) {
    const SpecularFrame frame(35, phi);
    const auto p = frame.toPlane(35, std::fmod(phi + 180, 360));
    EXPECT_NEAR(p.x_deg, 0, kExactDeg);
    EXPECT_NEAR(p.y_deg, 0, kExactDeg);
  }
}

TEST(SpecularFrame, TheVerticalIsThePlaneOfIncidenceTowardGrazing) {
  const SpecularFrame frame(35, 0);
  // 5° further from the normal in the plane of incidence: +5 on y, nothing across.
  const auto p = frame.toPlane(40, 180);
  EXPECT_NEAR(p.x_deg, 0, kExactDeg);
  EXPECT_NEAR(p.y_deg, 5, kExactDeg);
}

TEST(SpecularFrame, PlaneAndAnglesRoundTrip) {
  const SpecularFrame frame(60, 30);
  for (double x : {-10.0, 0.5, 7.0})
    for (double y : {-8.0, 0.0, 3.0}) {
      const auto [theta, phi] = frame.fromPlane({x, y});
      const auto back = frame.toPlane(theta, phi);
      EXPECT_NEAR(back.x_deg, x, 1e-9);
      EXPECT_NEAR(back.y_deg, y, 1e-9);
    }
}

}  // namespace
}  // namespace glarecam::surface
