#include "surface/sun_disc.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace glarecam::surface {
namespace {

TEST(DiscKernel, HoldsTheDiscsAreaAndSumsToOne) {
  int side = 0;
  const std::vector<double> w = discKernel(kSunHalfAngleDeg, 0.05, side);
  EXPECT_EQ(side % 2, 1);
  EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-12);
  // Its second moment is the disc's: R²/4 per axis, to the 1/16-pixel sampling of the edge.
  double m2 = 0;
  const int half = side / 2;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) m2 += w[y * side + x] * std::pow((x - half) * 0.05, 2);
  EXPECT_NEAR(m2, kSunHalfAngleDeg * kSunHalfAngleDeg / 4,
              0.02 * kSunHalfAngleDeg * kSunHalfAngleDeg / 4);
  int one = 0;
  EXPECT_EQ(discKernel(0, 0.05, one), std::vector<double>{1.0});
  EXPECT_EQ(one, 1);
}

}  // namespace
}  // namespace glarecam::surface
