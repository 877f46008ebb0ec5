#include "hazard/candidate_pairs.h"

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <numbers>
#include <numeric>
#include <utility>

#include "core/angles.h"

namespace glarecam::hazard {
namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using RtreePoint = bg::model::point<double, 3, bg::cs::cartesian>;
using RtreeBox = bg::model::box<RtreePoint>;
using RtreeEntry = std::pair<RtreeBox, std::size_t>;
// R*-tree nodes of 16 entries: Boost's suggested default for bulk-loaded static data.
constexpr std::size_t kRtreeNodeEntries = 16;
// Rounding of the bound's angles: far below a step's motion of the sun (0.25°/min).
constexpr double kBoundSlackRad = 1e-9;

double pointSegmentDistanceM(Vec3 p, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  const double length2 = dot(ab, ab);
  const double t = length2 > 0 ? std::clamp(dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * ab));
}

RtreeBox arrayBox(const ArrayPolygon& array) {
  RtreePoint lo(array.vertices_m[0].x, array.vertices_m[0].y, array.vertices_m[0].z), hi = lo;
  for (const Vec3& v : array.vertices_m) {
    lo = RtreePoint(std::min(lo.get<0>(), v.x), std::min(lo.get<1>(), v.y),
                    std::min(lo.get<2>(), v.z));
    hi = RtreePoint(std::max(hi.get<0>(), v.x), std::max(hi.get<1>(), v.y),
                    std::max(hi.get<2>(), v.z));
  }
  return {lo, hi};
}

}  // namespace

double distanceToArrayM(const ArrayPolygon& array, Vec3 point_m) {
  const double height_m = dot(point_m - array.centroid_m, array.normal);
  if (containsPlanePoint(array, point_m - height_m * array.normal)) return std::abs(height_m);
  double nearest_m = std::numeric_limits<double>::infinity();
  const std::size_t n = array.vertices_m.size();
  for (std::size_t i = 0; i < n; ++i)
    nearest_m = std::min(nearest_m, pointSegmentDistanceM(point_m, array.vertices_m[i],
                                                          array.vertices_m[(i + 1) % n]));
  return nearest_m;
}

std::vector<std::vector<std::size_t>> arraysWithin(const Scene& scene, double max_distance_m) {
  std::vector<std::vector<std::size_t>> within(scene.observers.size());
  if (!std::isfinite(max_distance_m)) {
    for (std::vector<std::size_t>& row : within) {
      row.resize(scene.arrays.size());
      std::iota(row.begin(), row.end(), std::size_t{0});
    }
    return within;
  }
  std::vector<RtreeEntry> entries;
  entries.reserve(scene.arrays.size());
  for (std::size_t a = 0; a < scene.arrays.size(); ++a)
    entries.emplace_back(arrayBox(scene.arrays[a]), a);
  // Bulk loading (the packing constructor) builds a better tree than inserting one by one.
  const bgi::rtree<RtreeEntry, bgi::rstar<kRtreeNodeEntries>> tree(entries.begin(), entries.end());
  std::vector<RtreeEntry> found;
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const Vec3 p = scene.observers[o].position_m;
    found.clear();
    const RtreeBox query(
        RtreePoint(p.x - max_distance_m, p.y - max_distance_m, p.z - max_distance_m),
        RtreePoint(p.x + max_distance_m, p.y + max_distance_m, p.z + max_distance_m));
    tree.query(bgi::intersects(query), std::back_inserter(found));
    for (const RtreeEntry& entry : found) {
      if (distanceToArrayM(scene.arrays[entry.second], p) <= max_distance_m)
        within[o].push_back(entry.second);
    }
    std::sort(within[o].begin(), within[o].end());
  }
  return within;
}

std::vector<std::vector<std::size_t>> candidateArrays(const Scene& scene, double max_distance_m,
                                                      CandidateCounts& counts) {
  std::vector<std::vector<std::size_t>> candidates = arraysWithin(scene, max_distance_m);
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const Vec3 p = scene.observers[o].position_m;
    std::vector<std::size_t>& row = candidates[o];
    counts.within_distance += row.size();
    const auto behind = std::remove_if(
        row.begin(), row.end(), [&](std::size_t a) { return !seesFront(scene.arrays[a], p); });
    counts.behind += static_cast<std::size_t>(row.end() - behind);
    row.erase(behind, row.end());
  }
  return candidates;
}

std::vector<std::vector<std::size_t>> candidateArrays(const Scene& scene, double max_distance_m) {
  CandidateCounts counts;
  return candidateArrays(scene, max_distance_m, counts);
}

Vec3 celestialPole(double latitude_deg) {
  const double latitude = radians(latitude_deg);
  return {0, std::cos(latitude), std::sin(latitude)};
}

double mirroredPoleAngleRad(const ArrayPolygon& array, Vec3 pole, Vec3 centre_direction) {
  const Vec3 mirrored = pole - 2 * dot(array.normal, pole) * array.normal;
  return angleBetweenRad(mirrored, centre_direction);
}

bool dayMayReach(double mirrored_pole_angle_rad, double reach_rad, const PoleAngleRange& day) {
  if (day.empty()) return false;
  if (reach_rad >= std::numbers::pi) return true;
  const double gap_rad =
      std::max(mirrored_pole_angle_rad - day.max_rad, day.min_rad - mirrored_pole_angle_rad);
  return gap_rad <= reach_rad + kBoundSlackRad;
}

}  // namespace glarecam::hazard
