// Which arrays a receptor point can see glare from, before any step is computed
// (../shared/docs/hazard.md; docs/hazard.md, "Screening a district"): the arrays within a
// distance of it (a Boost.Geometry R-tree over the arrays' boxes, then the exact distance to the
// polygon), and of those the ones whose front it sees. The calculation (hazard_calculation.h)
// steps through these pairs only, and rejects a pair for a whole day by a bound on where the
// day's sun can put its mirror image (dayMayReach below) before stepping through the day.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "hazard/scene.h"
#include "hazard/vec3.h"

namespace glarecam::hazard {

// No distance limit: every array is a candidate for every receptor point.
inline constexpr double kUnlimitedDistanceM = std::numeric_limits<double>::infinity();

// The shortest distance from a point to the array's polygon (its plane inside the outline, else
// its nearest edge).
double distanceToArrayM(const ArrayPolygon& array, Vec3 point_m);

// Per observer of the scene, the indices of the arrays whose polygon lies within max_distance_m
// (kUnlimitedDistanceM: all), in array order: O(observers · log arrays + pairs found).
std::vector<std::vector<std::size_t>> arraysWithin(const Scene& scene, double max_distance_m);

// Per observer of the scene, the indices of the arrays whose polygon lies within max_distance_m
// (kUnlimitedDistanceM: all) and whose front the observer sees (seesFront), in array order.
std::vector<std::vector<std::size_t>> candidateArrays(const Scene& scene, double max_distance_m);

// The counts behind candidateArrays, for the report.
struct CandidateCounts {
  std::size_t within_distance = 0;  // pairs whose polygon lies within the distance
  std::size_t behind = 0;           // of those, the pairs that see the array's back or edge
};
std::vector<std::vector<std::size_t>> candidateArrays(const Scene& scene, double max_distance_m,
                                                      CandidateCounts& counts);

// The day-level bound. A plane mirror is an isometry: the sun's mirror image c = R s (R the
// reflection in the array's plane) lies at the same angle θ from R p as the sun lies from the
// celestial pole p. Over a day the sun's θ stays within [θ_min, θ_max] (its declination and
// refraction), so the angle from c to the direction d toward the array's centre is at least
// the distance of φ = angle(R p, d) from that range. When that exceeds `reach_rad` (the largest
// half-axis any region of the profile can have plus the array's angular radius seen from the
// point) no step of the day can glare.
Vec3 celestialPole(double latitude_deg);  // unit, toward the north celestial pole (ENU)
double mirroredPoleAngleRad(const ArrayPolygon& array, Vec3 pole, Vec3 centre_direction);
struct PoleAngleRange {
  double min_rad = 0, max_rad = -1;  // empty (max < min) when the sun never rises
  bool empty() const { return max_rad < min_rad; }
};
bool dayMayReach(double mirrored_pole_angle_rad, double reach_rad, const PoleAngleRange& day);

}  // namespace glarecam::hazard
