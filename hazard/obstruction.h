// Obstructions of a hazard scene (../shared/docs/hazard.md, scene version 2): a building, a wall
// or a hedge as an extruded footprint (a polygon in x, y from base_m to height_m above z = 0), or
// one planar polygon. Each is kept as its planar faces, and what it takes from an array is found
// by projecting those faces onto the array's plane:
//   - the sun's shadow: a face's part in front of the plane (where the sun is) projected along
//     the sun's direction onto it; the array is lit where no face's projection falls;
//   - what a point does not see: a face's part between the point and the plane (0 < d < d_O, d
//     the distance in front of the plane) projected from the point onto it (a central
//     projection, defined on that slab, that keeps a simple polygon simple).
// A solid's projection is the union of its faces' projections, so both are exact polygons, up
// to Clipper's half-micrometre grid (plane_region.h). Parts within kSlabMarginM of the plane, or
// within a millionth of d_O of the point's own level, are left out: what they would hide lies
// under them or beyond a million times their distance, never on an array in between.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"
#include "hazard/plane_region.h"
#include "hazard/scene.h"
#include "hazard/vec3.h"

namespace glarecam::hazard {

// A micrometre: a face resting on the array's plane shades nothing of it.
inline constexpr double kSlabMarginM = 1e-6;
// An extrusion's height in metres: at least a centimetre, at most a kilometre.
inline constexpr double kMinObstructionHeightM = 0.01, kMaxObstructionHeightM = 1000;

struct Obstruction {
  std::string name;
  std::vector<ArrayPolygon> faces;  // planar, validated as arrays are
  // Per face: +1 or −1 when its normal times this points out of the solid (an extrusion's
  // faces), 0 for a face seen from both sides (a lone polygon).
  std::vector<int> outward;
  Vec3 centre_m;
  double radius_m = 0;  // every face lies within this of centre_m
};

// An extruded footprint: `footprint_m` (x, y; a simple polygon, as arrays are checked) from
// `base_m` to `height_m` above z = 0. kBadInput naming `file` and `field` for a bad footprint or
// heights out of order.
Result<Obstruction> makeExtrudedObstruction(std::string name,
                                            const std::vector<std::array<double, 2>>& footprint_m,
                                            double base_m, double height_m, const std::string& file,
                                            const std::string& field);
// One planar polygon (a wall, a screen).
Result<Obstruction> makePlanarObstruction(std::string name, std::vector<Vec3> vertices_m,
                                          const std::string& file, const std::string& field);

// Where the obstructions shade the array's plane from a sun in direction `sun` (unit, in front:
// n·s > 0), as rings in the array's plane frame, only those that can meet the array. Of a solid
// only the faces turned to the sun are projected: every ray through it enters through one of
// them (or through its cut at the plane, which faces away from the sun), so their shadows are
// its shadow.
std::vector<PlaneRing> sunShadowRings(const ArrayPolygon& array,
                                      const std::vector<Obstruction>& obstructions, Vec3 sun);
// Where the obstructions hide the array's plane from `point_m` (in front of it): every face, so
// that a point inside a solid is hidden too.
std::vector<PlaneRing> hiddenRings(const ArrayPolygon& array,
                                   const std::vector<Obstruction>& obstructions, Vec3 point_m);
// The same over some of a scene's obstructions (those that can matter, hazard_calculation.h).
std::vector<PlaneRing> sunShadowRings(const ArrayPolygon& array,
                                      const std::vector<const Obstruction*>& obstructions,
                                      Vec3 sun);
std::vector<PlaneRing> hiddenRings(const ArrayPolygon& array,
                                   const std::vector<const Obstruction*>& obstructions,
                                   Vec3 point_m);

// Whether the obstruction's bounding sphere can meet the axis-aligned box [lo, hi].
bool mayMeetBox(const Obstruction& obstruction, Vec3 lo, Vec3 hi);
// The highest apparent sun elevation (radians, up to π/2) at which the obstruction can shade
// some point of the array: its highest vertex above the array's lowest point over the horizontal
// gap between their bounding spheres; below zero when it is lower than every point of the array.
double maxShadingElevationRad(const Obstruction& obstruction, const ArrayPolygon& array);

}  // namespace glarecam::hazard
