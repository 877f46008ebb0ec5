// The hazard scene, glarecam.hazard-scene/1 (docs/hazard.md, ../shared/docs/hazard.md): the
// site, the arrays (planar polygons in local east–north–up metres, each optionally with its own
// glare profile) and the observers (a point and the local hours in which glare counts there).
// Reading validates everything the calculation relies on and refuses the first problem with one
// line naming the file and the field: a key the format does not define, at any level (with the
// closest known one); an array with fewer than 3 vertices, a repeated vertex, all on one line,
// not planar within kPlanarityToleranceM (naming the vertex farthest from the plane of the
// others), crossing itself (naming two edges that cross) or of zero area. What is valid but
// surely unmeant is warned about (Scene::warnings): an array facing downward, an observer that
// never sees an array's front.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "hazard/vec3.h"
#include "sun/solar_position.h"

namespace glarecam::hazard {

inline constexpr const char* kSceneSchema = "glarecam.hazard-scene/1";

// hazard.md: "refuse one that is not planar within 1 cm".
inline constexpr double kPlanarityToleranceM = 0.01;
// Smallest array area accepted: below a square centimetre a polygon is a typing error.
inline constexpr double kMinArrayAreaM2 = 1e-4;
// Coordinates are local: a scene larger than a thousand kilometres is a typing error (and would
// overflow the geometry's squares long before doubles do).
inline constexpr double kMaxCoordinateM = 1e6;
// Local standard time is UTC + utc_offset_h; the offsets in use run from −12 h to +14 h.
inline constexpr double kMinUtcOffsetH = -12, kMaxUtcOffsetH = 14;

struct HazardSite {
  sun::SiteLocation location;  // latitude, longitude, elevation (altitude_m), refraction inputs
  double utc_offset_h = 0;     // local standard time = UTC + this (no daylight saving time)
};

// A planar array and what the per-step geometry needs of it, derived once when it is read.
struct ArrayPolygon {
  std::string name;
  std::vector<Vec3> vertices_m;
  std::optional<std::filesystem::path> profile;  // its own glare profile (overrides --profile)

  Vec3 normal;      // unit Newell normal: the front, from which the vertices run counter-clockwise
  Vec3 centroid_m;  // of the vertices
  double radius_m = 0;  // of the sphere around centroid_m holding every vertex
  double area_m2 = 0;
  Vec3 up_slope;  // unit, in the plane, uphill (north for a level array): hazard.md step 4 at α = 0
  Vec3 axis_u, axis_w;  // in-plane orthonormal basis with axis_u × axis_w = normal
  std::vector<std::array<double, 2>> outline;  // vertices in (axis_u, axis_w) about centroid_m
};

struct Observer {
  std::string name;
  Vec3 position_m;
  double from_h = 0, to_h = 24;  // local standard hours [from, to) in which glare counts
};

struct Scene {
  std::filesystem::path path;
  HazardSite site;
  std::vector<ArrayPolygon> arrays;
  std::vector<Observer> observers;
  // e.g. an array facing downward, an observer that never sees an array's front
  std::vector<std::string> warnings;
};

// Reads and validates a scene file. An array's relative `profile` path is taken relative to the
// scene file's directory.
Result<Scene> readScene(const std::filesystem::path& path);
// The same from a parsed document; `file` names it in messages, `base` resolves profile paths.
Result<Scene> parseScene(const nlohmann::json& document, const std::string& file,
                         const std::filesystem::path& base);

// An array from its vertices: validated (see above) and its geometry derived. `file` and `field`
// name it in messages ("scene.json", "arrays[0].vertices_m").
Result<ArrayPolygon> makeArrayPolygon(std::string name, std::vector<Vec3> vertices_m,
                                      const std::string& file, const std::string& field);

// Whether a point sees the array's front: more than kPlanarityToleranceM in front of its plane
// (hazard.md step 2; behind it, or within the tolerance, where it sees the array edge-on, the
// array never glares there).
bool seesFront(const ArrayPolygon& array, Vec3 point_m);

// The compass direction the array's front faces: the azimuth of its normal's horizontal part,
// clockwise from north, [0, 360); nullopt for a level array.
std::optional<double> facingAzimuthDeg(const ArrayPolygon& array);
// The normal's angle from straight up: 0 level facing up, 90 vertical, 180 facing straight down.
double tiltDeg(const ArrayPolygon& array);

// Whether a point of the array's plane lies inside its polygon (even–odd rule; the boundary
// counts as inside within rounding).
bool containsPlanePoint(const ArrayPolygon& array, Vec3 point_m);

}  // namespace glarecam::hazard
