#include "hazard/obstruction.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace glarecam::hazard {
namespace {

// A point's level in the point's own slab is cut a millionth short (obstruction.h).
constexpr double kEyeLevelFraction = 1e-6;
// Parts of a face farther in front of the plane than this many metres per unit of cos α cast
// their shadow more than 4000 km away, beyond any scene (kMaxCoordinateM): left out, so that
// a grazing sun's projections stay inside Clipper's integer range.
constexpr double kShadowReachM = 4e6;

Obstruction withBounds(std::string name, std::vector<ArrayPolygon> faces) {
  Obstruction obstruction;
  obstruction.name = std::move(name);
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

// A face's part with kSlabMarginM + d_min ≤ d ≤ d_max, d = n·(X − P₀) the distance in front of
// the array's plane, each ring's vertices mapped by `project` onto that plane.
void projectFace(const ArrayPolygon& array, const ArrayPolygon& face, double d_min, double d_max,
                 const std::function<Vec3(Vec3, double)>& project, std::vector<PlaneRing>& rings) {
  const double d_centre = dot(face.centroid_m - array.centroid_m, array.normal);
  if (d_centre + face.radius_m < d_min || d_centre - face.radius_m > d_max) return;
  const double gu = dot(array.normal, face.axis_u), gw = dot(array.normal, face.axis_w);
  bool inside = true;
  for (const PlanePoint& p : face.outline) {
    const double d = d_centre + gu * p[0] + gw * p[1];
    inside = inside && d >= d_min && d <= d_max;
  }
  PlaneRegion part = arrayRegion(face);
  if (!inside) {
    const double extent = face.radius_m * 1.01 + 1e-3;
    const PlaneRegion slab = intersect(halfPlane(gu, gw, d_centre - d_min, extent),
                                       halfPlane(-gu, -gw, d_max - d_centre, extent));
    part = intersect(part, slab);
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
  faces.push_back(std::move(face));
  GLARECAM_ASSIGN(face, makeArrayPolygon(name, top, file, field + ".footprint_m"));
  faces.push_back(std::move(face));
  for (std::size_t i = 0; i < bottom.size(); ++i) {
    const std::size_t j = (i + 1) % bottom.size();
    GLARECAM_ASSIGN(face, makeArrayPolygon(name, {bottom[i], bottom[j], top[j], top[i]}, file,
                                           field + ".footprint_m"));
    faces.push_back(std::move(face));
  }
  return withBounds(std::move(name), std::move(faces));
}

Result<Obstruction> makePlanarObstruction(std::string name, std::vector<Vec3> vertices_m,
                                          const std::string& file, const std::string& field) {
  ArrayPolygon face;
  GLARECAM_ASSIGN(face, makeArrayPolygon(name, std::move(vertices_m), file, field));
  std::vector<ArrayPolygon> faces;
  faces.push_back(std::move(face));
  return withBounds(std::move(name), std::move(faces));
}

std::vector<PlaneRing> sunShadowRings(const ArrayPolygon& array,
                                      const std::vector<Obstruction>& obstructions, Vec3 sun) {
  std::vector<PlaneRing> rings;
  const double cos_alpha = dot(array.normal, sun);
  if (cos_alpha <= 0) return rings;
  const auto along_sun = [&](Vec3 x, double d) { return x - (d / cos_alpha) * sun; };
  for (const Obstruction& obstruction : obstructions) {
    // The parallel projection moves a point by at most (1 + 1/cos α) of its offset from the
    // centre: an obstruction whose projected bound misses the array's circle shades nothing.
    const double d = dot(obstruction.centre_m - array.centroid_m, array.normal);
    if (d + obstruction.radius_m < kSlabMarginM) continue;
    const Vec3 centre = along_sun(obstruction.centre_m, d);
    if (norm(centre - array.centroid_m) >
        array.radius_m + obstruction.radius_m * (1 + 1 / cos_alpha))
      continue;
    for (const ArrayPolygon& face : obstruction.faces)
      projectFace(array, face, kSlabMarginM, kShadowReachM * cos_alpha, along_sun, rings);
  }
  return rings;
}

std::vector<PlaneRing> hiddenRings(const ArrayPolygon& array,
                                   const std::vector<Obstruction>& obstructions, Vec3 point_m) {
  std::vector<PlaneRing> rings;
  const double d_point = dot(point_m - array.centroid_m, array.normal);
  if (d_point <= kSlabMarginM) return rings;
  const auto from_point = [&](Vec3 x, double d) {
    return point_m + (d_point / (d_point - d)) * (x - point_m);
  };
  for (const Obstruction& obstruction : obstructions) {
    for (const ArrayPolygon& face : obstruction.faces)
      projectFace(array, face, kSlabMarginM, d_point * (1 - kEyeLevelFraction), from_point, rings);
  }
  return rings;
}

}  // namespace glarecam::hazard
