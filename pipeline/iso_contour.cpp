#include "pipeline/iso_contour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "core/neighbourhood.h"
#include "core/parallel.h"

namespace glarecam::pipeline {
namespace {

bool reaches(float value, double level) { return std::isfinite(value) && value >= level; }

struct RegionBox {
  int x0, y0, x1, y1;  // inclusive
};

// The 8-connected pixels at or above `level` around `seed`, flagged 1 in `mask`.
RegionBox floodRegion(const FloatImage& image, double level, PixelIndex seed, ByteImage& mask,
                      std::size_t& count) {
  RegionBox box{seed.x, seed.y, seed.x, seed.y};
  count = floodFill8(
      mask, seed.x, seed.y, [&](int x, int y) { return reaches(image.at(x, y), level); },
      [&](int x, int y) {
        box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x), std::max(box.y1, y)};
      });
  return box;
}

// The region's box padded by one pixel on every side (possibly beyond the image), with each
// cell inside (region or hole) or outside (4-connected to the padding through non-region cells).
class RegionGrid {
 public:
  RegionGrid(const ByteImage& mask, const RegionBox& box)
      : x0_(box.x0 - 1),
        y0_(box.y0 - 1),
        width_(box.x1 - box.x0 + 3),
        height_(box.y1 - box.y0 + 3),
        inside_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 1) {
    std::vector<std::uint8_t> region(inside_.size(), 0);
    for (int j = 1; j + 1 < height_; ++j)
      for (int i = 1; i + 1 < width_; ++i) region[index(i, j)] = mask.at(x0_ + i, y0_ + j);
    // Everything 4-connected to the padding through non-region cells is outside; the rest of
    // the non-region cells are holes and count as inside.
    std::vector<std::pair<int, int>> stack{{0, 0}};
    inside_[0] = 0;
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      constexpr std::array<std::pair<int, int>, 4> kSteps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
      for (const auto& [di, dj] : kSteps) {
        const int ni = i + di, nj = j + dj;
        if (ni < 0 || nj < 0 || ni >= width_ || nj >= height_) continue;
        const std::size_t n = index(ni, nj);
        if (!inside_[n] || region[n]) continue;
        inside_[n] = 0;
        stack.emplace_back(ni, nj);
      }
    }
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int imageX(int i) const { return x0_ + i; }
  int imageY(int j) const { return y0_ + j; }
  bool inside(int i, int j) const { return inside_[index(i, j)] != 0; }
  std::size_t count() const {
    return static_cast<std::size_t>(std::count(inside_.begin(), inside_.end(), 1));
  }

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(i);
  }
  int x0_, y0_, width_, height_;
  std::vector<std::uint8_t> inside_;
};

// Grid edges by id: 2 * corner index for the edge to the right of a corner, + 1 for the edge
// below it.
using EdgeId = std::size_t;

class EdgeGraph {
 public:
  void link(EdgeId a, EdgeId b) {
    add(a, b);
    add(b, a);
  }
  bool empty() const { return neighbours_.empty(); }

  // The longest closed loop of edges (a simply connected region has exactly one).
  std::vector<EdgeId> longestLoop() const {
    std::vector<EdgeId> best;
    std::unordered_map<EdgeId, bool> visited;
    for (const auto& [start, ignored] : neighbours_) {
      if (visited[start]) continue;
      std::vector<EdgeId> loop;
      EdgeId previous = start, current = start;
      do {
        visited[current] = true;
        loop.push_back(current);
        const auto& next = neighbours_.at(current);
        const EdgeId following = next[0] != previous ? next[0] : next[1];
        previous = current;
        current = following;
      } while (current != start && loop.size() <= neighbours_.size());
      if (loop.size() > best.size()) best = std::move(loop);
    }
    return best;
  }

 private:
  static constexpr EdgeId kNone = static_cast<EdgeId>(-1);
  void add(EdgeId from, EdgeId to) {
    auto [it, inserted] = neighbours_.try_emplace(from, std::array<EdgeId, 2>{kNone, kNone});
    (it->second[0] == kNone ? it->second[0] : it->second[1]) = to;
  }
  std::unordered_map<EdgeId, std::array<EdgeId, 2>> neighbours_;
};

// Marching squares over the grid's cells. Saddle cells (diagonal corners inside) join their
// inside corners, as 8-connectivity of the region demands.
EdgeGraph linkBoundaryEdges(const RegionGrid& grid) {
  EdgeGraph graph;
  const auto corner = [&](int i, int j) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(grid.width()) +
           static_cast<std::size_t>(i);
  };
  for (int j = 0; j + 1 < grid.height(); ++j) {
    for (int i = 0; i + 1 < grid.width(); ++i) {
      const bool tl = grid.inside(i, j), tr = grid.inside(i + 1, j);
      const bool br = grid.inside(i + 1, j + 1), bl = grid.inside(i, j + 1);
      const EdgeId top = 2 * corner(i, j), bottom = 2 * corner(i, j + 1);
      const EdgeId left = 2 * corner(i, j) + 1, right = 2 * corner(i + 1, j) + 1;
      if (tl && br && !tr && !bl) {
        graph.link(top, right);
        graph.link(bottom, left);
        continue;
      }
      if (tr && bl && !tl && !br) {
        graph.link(top, left);
        graph.link(bottom, right);
        continue;
      }
      std::array<EdgeId, 4> crossing{};
      int n = 0;
      if (tl != tr) crossing[static_cast<std::size_t>(n++)] = top;
      if (tr != br) crossing[static_cast<std::size_t>(n++)] = right;
      if (br != bl) crossing[static_cast<std::size_t>(n++)] = bottom;
      if (bl != tl) crossing[static_cast<std::size_t>(n++)] = left;
      if (n == 2) graph.link(crossing[0], crossing[1]);
    }
  }
  return graph;
}

// Slots of ContourPoint::pixels along the step.
enum Slot { kBehind, kInside, kOutside, kBeyond };

// The crossing as a fraction t of the step from the inside pixel, with its derivatives.
void linearCrossing(double a, double b, double level, ContourPoint& point, double& t) {
  if (b > 0) {  // in ln L
    const double la = std::log(a), lb = std::log(b), ll = std::log(level);
    const double span = lb - la;
    t = (ll - la) / span;
    point.dt_dvalue[kInside] = (ll - lb) / (span * span) / a;
    point.dt_dvalue[kOutside] = -(ll - la) / (span * span) / b;
    point.dt_dlevel = 1.0 / (span * level);
  } else {  // in L
    const double span = a - b;
    t = (a - level) / span;
    point.dt_dvalue[kInside] = (level - b) / (span * span);
    point.dt_dvalue[kOutside] = (a - level) / (span * span);
    point.dt_dlevel = -1.0 / span;
  }
}

// Lagrange cubic through ln L at steps -1, 0, 1, 2: basis values and derivatives at t.
struct CubicBasis {
  std::array<double, 4> value, slope;
  explicit CubicBasis(double t)
      : value{-t * (t - 1) * (t - 2) / 6, (t + 1) * (t - 1) * (t - 2) / 2,
              -(t + 1) * t * (t - 2) / 2, (t + 1) * t * (t - 1) / 6},
        slope{-(3 * t * t - 6 * t + 2) / 6, (3 * t * t - 4 * t - 1) / 2,
              -(3 * t * t - 2 * t - 2) / 2, (3 * t * t - 1) / 6} {}
};

// The cubic's crossing of ln level in [0, 1] (safeguarded Newton from the linear estimate);
// false when the cubic is not clearly decreasing there.
bool cubicCrossing(const std::array<double, 4>& values, double level, ContourPoint& point,
                   double& t) {
  std::array<double, 4> f;
  for (std::size_t k = 0; k < 4; ++k) f[k] = std::log(values[k]);
  const double ll = std::log(level);
  const auto eval = [&](double s, double& slope) {
    const CubicBasis basis(s);
    double value = -ll;
    slope = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      value += basis.value[k] * f[k];
      slope += basis.slope[k] * f[k];
    }
    return value;
  };
  // Converged when the value vanishes, the bracket closes, or a Newton step no longer moves t
  // (tested before bisecting: a step below rounding lands on the bracket's end).
  constexpr double kTolerance = 1e-13;
  double lo = 0, hi = 1, slope = 0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double value = eval(t, slope);
    if (value == 0) break;
    (value > 0 ? lo : hi) = t;
    const double newton = slope < 0 ? t - value / slope : lo - 1;
    if (std::abs(newton - t) <= kTolerance) {
      t = std::clamp(newton, lo, hi);
      break;
    }
    t = newton > lo && newton < hi ? newton : (lo + hi) / 2;
    if (hi - lo <= kTolerance) break;
  }
  eval(t, slope);
  // A crossing where the cubic is much flatter than the chord is noise (or a contour grazing
  // the pixel line), not a lobe's flank: the linear crossing is safer there.
  constexpr double kMinSlopeFractionOfChord = 0.5;
  if (!(slope < kMinSlopeFractionOfChord * (f[kOutside] - f[kInside]))) return false;
  const CubicBasis basis(t);
  for (std::size_t k = 0; k < 4; ++k) point.dt_dvalue[k] = -basis.value[k] / slope / values[k];
  point.dt_dlevel = 1.0 / (slope * level);
  return true;
}

void interpolateCrossing(const std::array<double, 4>& values, double level, ContourPoint& point) {
  const double a = values[kInside], b = values[kOutside];
  double t = 0.5;
  if (std::isfinite(b)) {
    linearCrossing(a, b, level, point, t);
    const bool cubic_possible = b > 0 && values[kBehind] > 0 && values[kBeyond] > 0 &&
                                std::isfinite(values[kBehind]) && std::isfinite(values[kBeyond]);
    if (cubic_possible) {
      const ContourPoint linear = point;
      const double t_linear = t;
      if (!cubicCrossing(values, level, point, t)) {
        point = linear;
        t = t_linear;
      }
    }
  }
  point.x_px += t * point.step_x;
  point.y_px += t * point.step_y;
}

ContourPoint crossingPoint(const FloatImage& image, const RegionGrid& grid, EdgeId edge,
                           double level) {
  const auto corner = edge / 2;
  const int i = static_cast<int>(corner % static_cast<std::size_t>(grid.width()));
  const int j = static_cast<int>(corner / static_cast<std::size_t>(grid.width()));
  const int i2 = edge % 2 == 0 ? i + 1 : i, j2 = edge % 2 == 0 ? j : j + 1;
  const bool first_inside = grid.inside(i, j);
  const int in_x = grid.imageX(first_inside ? i : i2), in_y = grid.imageY(first_inside ? j : j2);
  ContourPoint point;
  point.x_px = in_x;
  point.y_px = in_y;
  point.step_x = grid.imageX(first_inside ? i2 : i) - in_x;
  point.step_y = grid.imageY(first_inside ? j2 : j) - in_y;
  // Values along the step at -1, 0, 1, 2; NaN outside the image.
  const auto in_image = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < image.width() && y < image.height();
  };
  std::array<double, 4> values;
  for (std::size_t k = 0; k < 4; ++k) {
    const int x = in_x + (static_cast<int>(k) - 1) * point.step_x;
    const int y = in_y + (static_cast<int>(k) - 1) * point.step_y;
    values[k] = in_image(x, y) ? image.at(x, y) : std::nan("");
    point.pixels[k] =
        in_image(x, y) ? static_cast<std::size_t>(y) * image.width() + static_cast<std::size_t>(x)
                       : 0;
  }
  point.on_border = !in_image(in_x + point.step_x, in_y + point.step_y);
  interpolateCrossing(values, level, point);
  return point;
}

}  // namespace

std::optional<RegionContour> traceRegionContour(const FloatImage& luminance, double level,
                                                PixelIndex seed, ByteImage* region_mask) {
  if (!(level > 0) || seed.x < 0 || seed.y < 0 || seed.x >= luminance.width() ||
      seed.y >= luminance.height() || !reaches(luminance.at(seed.x, seed.y), level)) {
    return std::nullopt;
  }
  ByteImage own_mask;
  if (region_mask) {
    *region_mask = ByteImage(luminance.width(), luminance.height());
  } else {
    own_mask = ByteImage(luminance.width(), luminance.height());
  }
  ByteImage& mask = region_mask ? *region_mask : own_mask;
  RegionContour contour;
  const RegionBox box = floodRegion(luminance, level, seed, mask, contour.connected_pixels);
  const RegionGrid grid(mask, box);
  contour.region_pixels = grid.count();
  contour.touches_all_borders = box.x0 == 0 && box.y0 == 0 && box.x1 == luminance.width() - 1 &&
                                box.y1 == luminance.height() - 1;
  for (const EdgeId edge : linkBoundaryEdges(grid).longestLoop()) {
    contour.points.push_back(crossingPoint(luminance, grid, edge, level));
    contour.touches_border = contour.touches_border || contour.points.back().on_border;
  }
  return contour;
}

std::vector<RegionExtent> findRegions(const FloatImage& luminance, double level,
                                      std::size_t min_pixels, ByteImage* seen) {
  // Rows holding any pixel at or above the level, found on all cores: on a glare image they
  // are few, and only they are labelled.
  std::vector<std::uint8_t> bright_row(static_cast<std::size_t>(luminance.height()), 0);
  parallelRows(luminance.height(), availableThreads(), [&](int begin, int end) {
    for (int y = begin; y < end; ++y) {
      const auto row = luminance.row(y);
      bright_row[static_cast<std::size_t>(y)] =
          std::any_of(row.begin(), row.end(), [&](float v) { return reaches(v, level); });
    }
  });
  ByteImage own_mask;
  if (!seen) own_mask = ByteImage(luminance.width(), luminance.height());
  ByteImage& mask = seen ? *seen : own_mask;
  std::vector<RegionExtent> regions;
  for (int y = 0; y < luminance.height(); ++y) {
    if (!bright_row[static_cast<std::size_t>(y)]) continue;
    const auto row = luminance.row(y);
    for (int x = 0; x < luminance.width(); ++x) {
      if (!reaches(row[static_cast<std::size_t>(x)], level) || mask.at(x, y)) continue;
      std::size_t count = 0;
      const RegionBox box = floodRegion(luminance, level, {x, y}, mask, count);
      if (count >= min_pixels) regions.push_back({box.x0, box.y0, box.x1, box.y1, count});
    }
  }
  return regions;
}

int countRegions(const FloatImage& luminance, double level, std::size_t min_pixels) {
  return static_cast<int>(findRegions(luminance, level, min_pixels).size());
}

}  // namespace glarecam::pipeline
