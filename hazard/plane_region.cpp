#include "hazard/plane_region.h"

#include <cmath>
#include <polyclipping/clipper.hpp>

namespace glarecam::hazard {
namespace {

ClipperLib::Path toPath(const PlaneRing& ring) {
  ClipperLib::Path path;
  path.reserve(ring.size());
  for (const PlanePoint& point : ring) {
    path.emplace_back(static_cast<ClipperLib::cInt>(std::llround(point[0] * kPlaneUnitsPerM)),
                      static_cast<ClipperLib::cInt>(std::llround(point[1] * kPlaneUnitsPerM)));
  }
  return path;
}

ClipperLib::Paths toPaths(const std::vector<PlaneRing>& rings) {
  ClipperLib::Paths paths;
  paths.reserve(rings.size());
  for (const PlaneRing& ring : rings) {
    if (ring.size() >= 3) paths.push_back(toPath(ring));
  }
  return paths;
}

PlaneRegion fromPaths(const ClipperLib::Paths& paths) {
  PlaneRegion region;
  for (const ClipperLib::Path& path : paths) {
    if (path.size() < 3) continue;
    PlaneRing ring;
    ring.reserve(path.size());
    for (const ClipperLib::IntPoint& point : path)
      ring.push_back({static_cast<double>(point.X) / kPlaneUnitsPerM,
                      static_cast<double>(point.Y) / kPlaneUnitsPerM});
    region.rings.push_back(std::move(ring));
  }
  return region;
}

// Every ring counter-clockwise: overlapping cuts of opposite orientation must not cancel under
// the non-zero rule.
ClipperLib::Paths positive(ClipperLib::Paths paths) {
  for (ClipperLib::Path& path : paths) {
    if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
  }
  return paths;
}

ClipperLib::Paths execute(ClipperLib::ClipType type, const ClipperLib::Paths& subject,
                          ClipperLib::PolyFillType subject_fill, const ClipperLib::Paths& clip,
                          ClipperLib::PolyFillType clip_fill) {
  ClipperLib::Clipper clipper;
  clipper.AddPaths(subject, ClipperLib::ptSubject, true);
  if (!clip.empty()) clipper.AddPaths(clip, ClipperLib::ptClip, true);
  ClipperLib::Paths solution;
  clipper.Execute(type, solution, subject_fill, clip_fill);
  return solution;
}

}  // namespace

bool containsPlanePoint(const ArrayPolygon& array, Vec3 point_m) {
  return contains(arrayRegion(array), sceneToPlane(array, point_m));
}

PlaneRegion arrayRegion(const ArrayPolygon& array) {
  PlaneRegion region;
  region.rings.push_back(array.outline);
  return region;
}

PlaneRegion subtract(const PlaneRegion& region, const std::vector<PlaneRing>& cuts) {
  if (cuts.empty() || region.empty()) return region;
  return fromPaths(execute(ClipperLib::ctDifference, toPaths(region.rings), ClipperLib::pftEvenOdd,
                           positive(toPaths(cuts)), ClipperLib::pftNonZero));
}

PlaneRegion intersect(const PlaneRegion& region, const PlaneRegion& other) {
  if (region.empty() || other.empty()) return {};
  return fromPaths(execute(ClipperLib::ctIntersection, toPaths(region.rings),
                           ClipperLib::pftEvenOdd, toPaths(other.rings), ClipperLib::pftEvenOdd));
}

PlaneRegion unite(const std::vector<PlaneRing>& rings) {
  if (rings.empty()) return {};
  return fromPaths(execute(ClipperLib::ctUnion, positive(toPaths(rings)), ClipperLib::pftNonZero,
                           {}, ClipperLib::pftNonZero));
}

bool contains(const PlaneRegion& region, PlanePoint point) {
  const double u = point[0], w = point[1];
  bool inside = false;
  for (const PlaneRing& ring : region.rings) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const double ui = ring[i][0], wi = ring[i][1];
      const double uj = ring[j][0], wj = ring[j][1];
      if ((wi > w) != (wj > w) && u < (uj - ui) * (w - wi) / (wj - wi) + ui) inside = !inside;
    }
  }
  return inside;
}

double areaM2(const PlaneRegion& region) {
  double twice = 0;
  for (const PlaneRing& ring : region.rings) {
    double ring_twice = 0;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
      ring_twice += ring[j][0] * ring[i][1] - ring[i][0] * ring[j][1];
    twice += ring_twice;  // Clipper's holes run the other way round: they subtract
  }
  return std::abs(twice) / 2;
}

PlaneRegion halfPlane(double a, double b, double c, double extent_m) {
  const double length = std::hypot(a, b);
  const PlaneRing square = {
      {-extent_m, -extent_m}, {extent_m, -extent_m}, {extent_m, extent_m}, {-extent_m, extent_m}};
  if (length == 0) return c >= 0 ? PlaneRegion{{square}} : PlaneRegion{};
  // The boundary line's nearest point to the origin, p0 = −c n̂ / |n|, and its direction t. A
  // line farther than the square's half-diagonal (√2·extent) leaves it whole or empty; a nearer
  // one has p0 within √2·extent of the origin, so every point of the square lies within
  // 2·√2·extent < 3·extent of p0: a rectangle reaching 3·extent along t and 3·extent along n̂
  // holds the half-plane's part of it.
  const double nu = a / length, nw = b / length, offset = -c / length;
  if (std::abs(offset) > std::sqrt(2.0) * extent_m)
    return c >= 0 ? PlaneRegion{{square}} : PlaneRegion{};
  const double reach = 3 * extent_m;
  const PlanePoint p0{offset * nu, offset * nw};
  const PlanePoint t{-nw, nu};
  const PlaneRing rectangle = {
      {p0[0] - reach * t[0], p0[1] - reach * t[1]},
      {p0[0] + reach * t[0], p0[1] + reach * t[1]},
      {p0[0] + reach * t[0] + reach * nu, p0[1] + reach * t[1] + reach * nw},
      {p0[0] - reach * t[0] + reach * nu, p0[1] - reach * t[1] + reach * nw}};
  return intersect(PlaneRegion{{square}}, PlaneRegion{{rectangle}});
}

Vec3 planeToScene(const ArrayPolygon& array, PlanePoint point) {
  return array.centroid_m + point[0] * array.axis_u + point[1] * array.axis_w;
}

PlanePoint sceneToPlane(const ArrayPolygon& array, Vec3 point_m) {
  const Vec3 d = point_m - array.centroid_m;
  return {dot(d, array.axis_u), dot(d, array.axis_w)};
}

}  // namespace glarecam::hazard
