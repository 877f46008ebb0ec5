#include "hazard/obstruction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace glarecam::hazard {
namespace {

// A point's level in the point's own slab is cut a millionth short (obstruction.h).
constexpr double kEyeLevelFraction = 1e-6;
// Parts of a face farther in front of the plane than this many metres per unit of cos α cast
// their shadow more than 4000 km away, beyond any scene (kMaxCoordinateM): left out, so that
// a grazing sun's projections stay inside Clipper's integer range.
constexpr double kShadowReachM = 4e6;
constexpr double kFar = std::numeric_limits<double>::max();

Obstruction withBounds(std::string name, std::vector<ArrayPolygon> faces,
                       std::vector<int> outward) {
  Obstruction obstruction;
  obstruction.name = std::move(name);
  obstruction.outward = std::move(outward);
  Vec3 low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
           std::numeric_limits<double>::max()};
  Vec3 high = -1 * low;
  for (const ArrayPolygon& face : faces) {
    for (const Vec3& v : face.vertices_m) {
      low = {std::min(low.x, v.x), std::min(low.y, v.y), std::min(low.z, v.z)};
      high = {std::max(high.x, v.x), std::max(high.y, v.y), std::max(high.z, v.z)};
    }
  }
  obstruction.centre_m = 0.5 * (low + high);
  obstruction.radius_m = norm(high - low) / 2;
  obstruction.faces = std::move(faces);
  return obstruction;
}

// The strip d_min ≤ d(u, w) ≤ d_max of a face's plane, d = d0 + gu·u + gw·w, as a rectangle
// holding the face's part of it (the face lies within `extent` of its centroid, the origin).
PlaneRing slabStrip(double d0, double gu, double gw, double d_min, double d_max, double extent) {
  const double g = std::hypot(gu, gw);
  const double nu = gu / g, nw = gw / g;
  // Along (nu, nw) the coordinate t = (d − d0)/g; across it, ±extent.
  const double t0 = std::max((d_min - d0) / g, -extent), t1 = std::min((d_max - d0) / g, extent);
  return {{t0 * nu + extent * nw, t0 * nw - extent * nu},
          {t1 * nu + extent * nw, t1 * nw - extent * nu},
          {t1 * nu - extent * nw, t1 * nw + extent * nu},
          {t0 * nu - extent * nw, t0 * nw + extent * nu}};
}

// A face's part with d_min ≤ d ≤ d_max, d = n·(X − P₀) the distance in front of the array's
// plane, each ring's vertices mapped by `project` onto that plane.
template <typename Project>
void projectFace(const ArrayPolygon& array, const ArrayPolygon& face, double d_min, double d_max,
                 const Project& project, std::vector<PlaneRing>& rings) {
  const double d_centre = dot(face.centroid_m - array.centroid_m, array.normal);
  if (d_centre + face.radius_m < d_min || d_centre - face.radius_m > d_max) return;
  const double gu = dot(array.normal, face.axis_u), gw = dot(array.normal, face.axis_w);
  bool inside = true, outside_low = true, outside_high = true;
  for (const PlanePoint& p : face.outline) {
    const double d = d_centre + gu * p[0] + gw * p[1];
    inside = inside && d >= d_min && d <= d_max;
    outside_low = outside_low && d < d_min;
    outside_high = outside_high && d > d_max;
  }
  if (outside_low || outside_high) return;
  PlaneRegion part = arrayRegion(face);
  if (!inside) {
    const double extent = face.radius_m * 1.01 + 1e-3;
    part = intersect(part, PlaneRegion{{slabStrip(d_centre, gu, gw, d_min, d_max, extent)}});
  }
  for (const PlaneRing& ring : part.rings) {
    PlaneRing projected;
    projected.reserve(ring.size());
    for (const PlanePoint& p : ring) {
      const Vec3 x = planeToScene(face, p);
      projected.push_back(sceneToPlane(array, project(x, dot(x - array.centroid_m, array.normal))));
    }
    rings.push_back(std::move(projected));
  }
}

}  // namespace

Result<Obstruction> makeExtrudedObstruction(std::string name,
                                            const std::vector<std::array<double, 2>>& footprint_m,
                                            double base_m, double height_m, const std::string& file,
                                            const std::string& field) {
  if (!(height_m - base_m >= kMinObstructionHeightM)) {
    return badInput(file + ": " + field + ": height_m " + std::to_string(height_m) +
                    " m is not at least 1 cm above base_m " + std::to_string(base_m) + " m");
  }
  std::vector<Vec3> bottom, top;
  for (const auto& [x, y] : footprint_m) {
    bottom.push_back({x, y, base_m});
    top.push_back({x, y, height_m});
  }
  std::vector<ArrayPolygon> faces;
  ArrayPolygon face;
  GLARECAM_ASSIGN(face, makeArrayPolygon(name, bottom, file, field + ".footprint_m"));
  // Counter-clockwise seen from above: the footprint's normal points up. Then the top's normal
  // points out, the bottom's in, and each wall's (bottom i, bottom j, top j) out; clockwise, the
  // other way round.
  const int turn = face.normal.z > 0 ? 1 : -1;
  std::vector<int> outward{-turn, turn};
  faces.push_back(std::move(face));
  GLARECAM_ASSIGN(face, makeArrayPolygon(name, top, file, field + ".footprint_m"));
  faces.push_back(std::move(face));
  for (std::size_t i = 0; i < bottom.size(); ++i) {
    const std::size_t j = (i + 1) % bottom.size();
    GLARECAM_ASSIGN(face, makeArrayPolygon(name, {bottom[i], bottom[j], top[j], top[i]}, file,
                                           field + ".footprint_m"));
    faces.push_back(std::move(face));
    outward.push_back(turn);
  }
  return withBounds(std::move(name), std::move(faces), std::move(outward));
}

Result<Obstruction> makePlanarObstruction(std::string name, std::vector<Vec3> vertices_m,
                                          const std::string& file, const std::string& field) {
  ArrayPolygon face;
  GLARECAM_ASSIGN(face, makeArrayPolygon(name, std::move(vertices_m), file, field));
  std::vector<ArrayPolygon> faces;
  faces.push_back(std::move(face));
  return withBounds(std::move(name), std::move(faces), {0});
}

namespace {
std::vector<const Obstruction*> pointersTo(const std::vector<Obstruction>& obstructions) {
  std::vector<const Obstruction*> pointers;
  pointers.reserve(obstructions.size());
  for (const Obstruction& obstruction : obstructions) pointers.push_back(&obstruction);
  return pointers;
}
}  // namespace

std::vector<PlaneRing> sunShadowRings(const ArrayPolygon& array,
                                      const std::vector<Obstruction>& obstructions, Vec3 sun) {
  return sunShadowRings(array, pointersTo(obstructions), sun);
}

std::vector<PlaneRing> hiddenRings(const ArrayPolygon& array,
                                   const std::vector<Obstruction>& obstructions, Vec3 point_m) {
  return hiddenRings(array, pointersTo(obstructions), point_m);
}

std::vector<PlaneRing> sunShadowRings(const ArrayPolygon& array,
                                      const std::vector<const Obstruction*>& obstructions,
                                      Vec3 sun) {
  std::vector<PlaneRing> rings;
  const double cos_alpha = dot(array.normal, sun);
  if (cos_alpha <= 0) return rings;
  const auto along_sun = [&](Vec3 x, double d) { return x - (d / cos_alpha) * sun; };
  std::array<double, 4> array_box{kFar, kFar, -kFar, -kFar};
  for (const PlanePoint& p : array.outline)
    array_box = {std::min(array_box[0], p[0]), std::min(array_box[1], p[1]),
                 std::max(array_box[2], p[0]), std::max(array_box[3], p[1])};
  for (const Obstruction* casting : obstructions) {
    const Obstruction& obstruction = *casting;
    const double d = dot(obstruction.centre_m - array.centroid_m, array.normal);
    if (d + obstruction.radius_m < kSlabMarginM) continue;
    // The projection along the sun is affine, so every clipped face's shadow lies within the
    // bounding box of the projected vertices: one that misses the array's box shades nothing.
    std::array<double, 4> box{kFar, kFar, -kFar, -kFar};  // u min, w min, u max, w max
    for (const ArrayPolygon& face : obstruction.faces) {
      for (const Vec3& vertex : face.vertices_m) {
        const PlanePoint p =
            sceneToPlane(array, along_sun(vertex, dot(vertex - array.centroid_m, array.normal)));
        box = {std::min(box[0], p[0]), std::min(box[1], p[1]), std::max(box[2], p[0]),
               std::max(box[3], p[1])};
      }
    }
    if (box[0] > array_box[2] || box[2] < array_box[0] || box[1] > array_box[3] ||
        box[3] < array_box[1])
      continue;
    for (std::size_t f = 0; f < obstruction.faces.size(); ++f) {
      const ArrayPolygon& face = obstruction.faces[f];
      const double toward_sun = dot(face.normal, sun);
      // Turned away from the sun, or seen edge-on (no area): not part of the shadow's outline.
      if (toward_sun == 0 || obstruction.outward[f] * toward_sun < 0) continue;
      projectFace(array, face, kSlabMarginM, kShadowReachM * cos_alpha, along_sun, rings);
    }
  }
  return rings;
}

std::vector<PlaneRing> hiddenRings(const ArrayPolygon& array,
                                   const std::vector<const Obstruction*>& obstructions,
                                   Vec3 point_m) {
  std::vector<PlaneRing> rings;
  const double d_point = dot(point_m - array.centroid_m, array.normal);
  if (d_point <= kSlabMarginM) return rings;
  const auto from_point = [&](Vec3 x, double d) {
    return point_m + (d_point / (d_point - d)) * (x - point_m);
  };
  for (const Obstruction* obstruction : obstructions) {
    for (const ArrayPolygon& face : obstruction->faces)
      projectFace(array, face, kSlabMarginM, d_point * (1 - kEyeLevelFraction), from_point, rings);
  }
  return rings;
}

bool mayMeetBox(const Obstruction& obstruction, Vec3 lo, Vec3 hi) {
  const Vec3& c = obstruction.centre_m;
  const double r = obstruction.radius_m;
  return c.x + r >= lo.x && c.x - r <= hi.x && c.y + r >= lo.y && c.y - r <= hi.y &&
         c.z + r >= lo.z && c.z - r <= hi.z;
}

double maxShadingElevationRad(const Obstruction& obstruction, const ArrayPolygon& array) {
  double lowest_m = kFar;
  for (const Vec3& vertex : array.vertices_m) lowest_m = std::min(lowest_m, vertex.z);
  double top_m = -kFar;
  for (const ArrayPolygon& face : obstruction.faces)
    for (const Vec3& vertex : face.vertices_m) top_m = std::max(top_m, vertex.z);
  const double rise_m = top_m - lowest_m;
  if (rise_m <= 0) return -1;  // a shadow ray rises from the array: it never meets this one
  const double gap_m = std::hypot(obstruction.centre_m.x - array.centroid_m.x,
                                  obstruction.centre_m.y - array.centroid_m.y) -
                       obstruction.radius_m - array.radius_m;
  if (gap_m <= 0) return std::numbers::pi / 2;
  return std::atan2(rise_m, gap_m);
}

}  // namespace glarecam::hazard
