// A region of an array's plane: what is left of the array for glare once obstructions, the
// sun's shadows and an observer's field of view have taken their part (../shared/docs/hazard.md,
// scene version 2). Points are in the array's in-plane frame (ArrayPolygon::axis_u, axis_w,
// metres about its centroid), the frame of ArrayPolygon::outline.
//
// The polygon operations are Clipper's (Angus Johnson's Clipper 6, Debian's libpolyclipping),
// on integer coordinates of kPlaneUnitsPerM to the metre: every vertex a clipped region has is
// exact to half a micrometre, a thousandth of a second of arc seen from 100 m, so the glare test's
// own bound (glare_region.h) holds for a clipped region as for the whole array.
//
// A region is a set of rings read with the even–odd rule (outer rings and their holes, as
// Clipper returns them): a point is inside when a ray from it crosses its rings an odd number of
// times. Rings never cross each other.
#pragma once

#include <array>
#include <vector>

#include "hazard/scene.h"

namespace glarecam::hazard {

// Micrometres: coordinates up to kMaxCoordinateM (1000 km) stay far inside Clipper's 62-bit
// range even for a projection that stretches a shadow a million-fold.
inline constexpr double kPlaneUnitsPerM = 1e6;

using PlanePoint = std::array<double, 2>;
using PlaneRing = std::vector<PlanePoint>;

struct PlaneRegion {
  std::vector<PlaneRing> rings;
  bool empty() const { return rings.empty(); }
};

// The whole array.
PlaneRegion arrayRegion(const ArrayPolygon& array);

// `region` less the union of `cuts` (rings of either orientation, each a simple polygon; they may
// overlap each other).
PlaneRegion subtract(const PlaneRegion& region, const std::vector<PlaneRing>& cuts);
// The part of `region` inside `other`.
PlaneRegion intersect(const PlaneRegion& region, const PlaneRegion& other);
// The union of simple rings of either orientation.
PlaneRegion unite(const std::vector<PlaneRing>& rings);

// Even–odd containment; the boundary counts as inside within rounding.
bool contains(const PlaneRegion& region, PlanePoint point);
double areaM2(const PlaneRegion& region);

// The half-plane a·u + b·w + c ≥ 0 within `extent_m` of the origin, as a region (empty when it
// misses that square; the whole square when a and b are both zero and c ≥ 0).
PlaneRegion halfPlane(double a, double b, double c, double extent_m);

// A point of the array's plane in the scene's frame, and back (the plane's own coordinates of
// the point's foot on it).
Vec3 planeToScene(const ArrayPolygon& array, PlanePoint point);
PlanePoint sceneToPlane(const ArrayPolygon& array, Vec3 point_m);

}  // namespace glarecam::hazard
