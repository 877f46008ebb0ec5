// Pixel neighbourhoods shared by the image algorithms: the 3x3 neighbourhood of a pixel clipped
// to the image, and 8-connected flood fill (regions of a glare spot, a saturated plateau).
// Pixel coordinates as in core/image.h: x right, y down.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/image.h"

namespace glarecam {

// Calls visit(x, y) for each pixel of the 3x3 neighbourhood of (x, y), itself included, that
// lies inside a width x height image, row by row.
template <typename Visit>
void forEach3x3(int width, int height, int x, int y, Visit&& visit) {
  for (int yy = std::max(0, y - 1); yy <= std::min(height - 1, y + 1); ++yy)
    for (int xx = std::max(0, x - 1); xx <= std::min(width - 1, x + 1); ++xx) visit(xx, yy);
}

// Fills from (x, y) over the 8-connected pixels inside(x, y) accepts, calling visit(x, y) once
// for each (the seed included, whatever inside() says of it). `seen` has the image's size; the
// pixels reached are set to 1 in it, and pixels already set are neither entered nor visited.
// Returns how many pixels were visited.
template <typename Inside, typename Visit>
std::size_t floodFill8(ByteImage& seen, int x, int y, Inside&& inside, Visit&& visit) {
  if (seen.at(x, y)) return 0;
  std::vector<std::pair<int, int>> stack{{x, y}};
  seen.at(x, y) = 1;
  std::size_t count = 0;
  while (!stack.empty()) {
    const auto [px, py] = stack.back();
    stack.pop_back();
    ++count;
    visit(px, py);
    forEach3x3(seen.width(), seen.height(), px, py, [&](int nx, int ny) {
      if (seen.at(nx, ny) || !inside(nx, ny)) return;
      seen.at(nx, ny) = 1;
      stack.emplace_back(nx, ny);
    });
  }
  return count;
}

}  // namespace glarecam
