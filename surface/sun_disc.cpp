#include "surface/sun_disc.h"

#include <cmath>
#include <cstddef>

namespace glarecam::surface {

std::vector<double> discKernel(double radius_deg, double pixel_deg, int& side) {
  if (radius_deg <= 0) {
    side = 1;
    return {1.0};
  }
  const int half = static_cast<int>(std::ceil(radius_deg / pixel_deg + 0.5));
  side = 2 * half + 1;
  std::vector<double> weights(static_cast<std::size_t>(side) * side, 0.0);
  constexpr int kSub = 16;  // points a pixel side: the disc's edge to 1/16 pixel
  double total = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      int inside = 0;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          const double dx = (x - half + (sx + 0.5) / kSub - 0.5) * pixel_deg;
          const double dy = (y - half + (sy + 0.5) / kSub - 0.5) * pixel_deg;
          inside += dx * dx + dy * dy <= radius_deg * radius_deg;
        }
      weights[static_cast<std::size_t>(y) * side + x] = inside;
      total += inside;
    }
  for (double& w : weights) w /= total;
  return weights;
}

}  // namespace glarecam::surface
