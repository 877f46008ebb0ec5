// The hazard scene, glarecam.hazard-scene/1 and /2 (docs/hazard.md, ../shared/docs/hazard.md):
// the site, the arrays (planar polygons in local east–north–up metres, each optionally with its
// own glare profile) and the receptors: observers (a point, the local hours in which glare
// counts there and, since /2, the direction a window looks out to), and since /2 routes (a
// polyline sampled every spacing_m, glare counting within a field of view around the direction
// of travel) and areas (a polygon sampled on a grid at eye height); since /2 also obstructions
// (obstruction.h). Every receptor is expanded into points (Scene::observers), each knowing its
// receptor, so that the calculation sees points only; a /1 scene reads as it always did.
// Reading validates everything the calculation relies on and refuses the first problem with one
// line naming the file and the field: a key the format does not define, at any level (with the
// closest known one); an array with fewer than 3 vertices, a repeated vertex, all on one line,
// not planar within kPlanarityToleranceM (naming the vertex farthest from the plane of the
// others), crossing itself (naming two edges that cross) or of zero area. What is valid but
// surely unmeant is warned about (Scene::warnings): an array facing downward, and a receptor
// that never sees the front of an array within kDefaultMaxDistanceM (100 m, LAI) of it (behind or
// on its plane; a route or area when none of its points there does). Up to ten such pairs are a
// small scene's drawing mistake and get a warning each; more are a district, where most windows
// face away from most roofs: then one line counts them (receptors, pairs, arrays, three
// examples), and one names the arrays that every receptor within the distance sees from behind
// (listed the wrong way round?). Farther pairs are never computed by default and not warned
// about. The check goes through an R-tree (candidate_pairs.h): O(points · log arrays + pairs
// within the distance), never observers × arrays.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "hazard/geo_frame.h"
#include "hazard/vec3.h"
#include "sun/solar_position.h"

namespace glarecam::hazard {

inline constexpr const char* kSceneSchema = "glarecam.hazard-scene/2";
inline constexpr const char* kSceneSchemaV1 = "glarecam.hazard-scene/1";

// hazard.md: "refuse one that is not planar within 1 cm".
inline constexpr double kPlanarityToleranceM = 0.01;
// Smallest array area accepted: below a square centimetre a polygon is a typing error.
inline constexpr double kMinArrayAreaM2 = 1e-4;
// Coordinates are local: a scene larger than a thousand kilometres is a typing error (and would
// overflow the geometry's squares long before doubles do).
inline constexpr double kMaxCoordinateM = 1e6;
// A route or area sampled more finely than this many points is a typing error in spacing_m.
inline constexpr std::size_t kMaxReceptorPoints = 20000;
// hazard.md: a driver's field of view, half-angle, and a window's (the half-space in front).
inline constexpr double kDriverFieldOfViewDeg = 50, kWindowFieldOfViewDeg = 90;
// An area's receptors stand this high above it unless eye_height_m says otherwise (a standing
// adult's eye, DIN 33402), and are this far apart unless spacing_m does.
inline constexpr double kDefaultEyeHeightM = 1.6, kDefaultAreaSpacingM = 2,
                        kDefaultRouteSpacingM = 10;
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

enum class ReceptorKind { kObserver, kRoute, kArea };
const char* receptorKindName(ReceptorKind kind);  // "observer", "route", "area"

// One receptor of the scene as written: its points are Scene::observers[first, first + count).
struct Receptor {
  ReceptorKind kind = ReceptorKind::kObserver;
  std::string name;
  std::size_t first = 0, count = 0;
};

// A point at which glare is counted: an observer, or one sample of a route or an area.
struct Observer {
  std::string name;  // "window-3"; a route's "road-b@30m", an area's "terrace[4]"
  Vec3 position_m;
  double from_h = 0, to_h = 24;  // local standard hours [from, to) in which glare counts
  // The horizontal directions glare counts around (azimuths clockwise from north: a window's
  // facing, a route's direction(s) of travel there), each within field_of_view_deg (half-angle,
  // measured horizontally); empty: from every direction.
  std::vector<double> view_azimuths_deg{};
  double field_of_view_deg = 180;
  std::size_t receptor = 0;  // index into Scene::receptors
};

struct Obstruction;

struct Scene {
  std::filesystem::path path;
  HazardSite site;
  std::vector<ArrayPolygon> arrays;
  std::vector<Observer> observers;  // every receptor's points, receptor by receptor
  std::vector<Receptor> receptors;
  std::vector<Obstruction> obstructions;
  int version = 2;  // of the scene's schema
  // A geographic scene's frame (geo_scene.h): where the local metres lie on the Earth.
  std::optional<GeoFrame> geo;
  // e.g. an array facing downward, an observer that never sees an array's front
  std::vector<std::string> warnings;

  Scene();
  ~Scene();
  Scene(const Scene&);
  Scene(Scene&&) noexcept;
  Scene& operator=(const Scene&);
  Scene& operator=(Scene&&) noexcept;
};

// Reads and validates a scene file. An array's relative `profile` path is taken relative to the
// scene file's directory. A `.kml` file, or a JSON document that is a GeoJSON FeatureCollection,
// is a geographic scene (geo_scene.h).
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
