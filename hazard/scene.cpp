#include "hazard/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "core/angles.h"
#include "core/json.h"
#include "hazard/candidate_pairs.h"
#include "hazard/geo_scene.h"
#include "hazard/hazard_calculation.h"
#include "hazard/obstruction.h"

namespace glarecam::hazard {
namespace {

// Vertices closer than this are one vertex repeated (a micrometre: far below survey precision).
constexpr double kSameVertexM = 1e-6;
// Level within this: the up-slope direction falls back to north (hazard.md step 4).
constexpr double kLevelTolerance = 1e-9;
// An array "faces downward" (listed the wrong way round) when its normal points more than 1°
// below the horizontal: a facade drawn vertical on a map leans by the Earth's curvature in the
// site's frame (0.45° at 50 km, geo_frame.h) and by rounding, and is not warned about.
const double kFacesDownwardNormalZ = -std::sin(radians(1.0));
// A route's end within this of its last sample adds no receptor, an area this much larger than
// whole cells no row or column: coordinates converted from a map (geo_scene.h) or rounded in a
// file are exact to about a millimetre, and must not change the receptors.
constexpr double kReceptorSnapM = 1e-3;
// An area within this of level lays its receptor grid north–south (readAreas).
constexpr double kLevelAreaTiltDeg = 1;

using Point2 = std::array<double, 2>;

double cross2(Point2 o, Point2 a, Point2 b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

bool onSegment(Point2 p, Point2 a, Point2 b) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

// Whether closed segments ab and cd share a point (touching counts), with a tolerance scaled
// to the polygon's size for the collinear cases.
bool segmentsMeet(Point2 a, Point2 b, Point2 c, Point2 d, double epsilon) {
  const double d1 = cross2(c, d, a), d2 = cross2(c, d, b);
  const double d3 = cross2(a, b, c), d4 = cross2(a, b, d);
  if (((d1 > epsilon && d2 < -epsilon) || (d1 < -epsilon && d2 > epsilon)) &&
      ((d3 > epsilon && d4 < -epsilon) || (d3 < -epsilon && d4 > epsilon)))
    return true;
  if (std::abs(d1) <= epsilon && onSegment(a, c, d)) return true;
  if (std::abs(d2) <= epsilon && onSegment(b, c, d)) return true;
  if (std::abs(d3) <= epsilon && onSegment(c, a, b)) return true;
  if (std::abs(d4) <= epsilon && onSegment(d, a, b)) return true;
  return false;
}

constexpr std::size_t kAllVertices = static_cast<std::size_t>(-1);

// Newell's vector of the polygon of the vertices but `skip`: normal to their plane, oriented by
// the right-hand rule, twice the area it encloses in length.
Vec3 newellVector(const std::vector<Vec3>& vertices, std::size_t skip) {
  std::vector<Vec3> kept;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (i != skip) kept.push_back(vertices[i]);
  Vec3 newell;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Vec3 a = kept[i], b = kept[(i + 1) % kept.size()];
    newell = newell +
             Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return newell;
}

struct VertexPlane {
  Vec3 point_m;  // the centroid of the vertices
  Vec3 normal;   // unit; zero when the vertices lie on one line
};

// The plane of the vertices but `skip`, through their centroid: Newell's normal when they enclose
// area as a polygon; else (lobes that cancel, a symmetric bow-tie) the largest cross product of
// two of them about the centroid, which any two vertices off a common line give.
VertexPlane fitPlane(const std::vector<Vec3>& vertices, std::size_t skip) {
  VertexPlane plane;
  double kept = 0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (i == skip) continue;
    plane.point_m = plane.point_m + vertices[i];
    kept += 1;
  }
  plane.point_m = (1.0 / kept) * plane.point_m;
  const Vec3 newell = newellVector(vertices, skip);
  if (norm(newell) / 2 >= kMinArrayAreaM2) {
    plane.normal = normalised(newell);
    return plane;
  }
  Vec3 largest;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (std::size_t j = i + 1; j < vertices.size(); ++j) {
      if (i == skip || j == skip) continue;
      const Vec3 spanned = cross(vertices[i] - plane.point_m, vertices[j] - plane.point_m);
      if (norm(spanned) > norm(largest)) largest = spanned;
    }
  }
  if (norm(largest) / 2 >= kMinArrayAreaM2) plane.normal = normalised(largest);
  return plane;
}

struct OffPlaneVertex {
  std::size_t index = 0;
  double distance_m = 0;
};

// The vertex farthest from the plane through the others: the one a typing error moved.
OffPlaneVertex farthestOffPlane(const std::vector<Vec3>& vertices) {
  OffPlaneVertex farthest;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const VertexPlane others = fitPlane(vertices, i);
    if (others.normal == Vec3{}) continue;  // the others on one line: any plane holds them
    const double distance_m = std::abs(dot(vertices[i] - others.point_m, others.normal));
    if (distance_m > farthest.distance_m) farthest = {i, distance_m};
  }
  return farthest;
}

Result<Vec3> readPoint(const JsonReader& value) {
  GLARECAM_CHECK(value.array());
  if (value.size() != 3) return value.fail("is not [x, y, z] (3 numbers in metres)");
  std::array<double, 3> xyz{};
  for (std::size_t i = 0; i < 3; ++i)
    GLARECAM_ASSIGN(xyz[i], value.element(i).numberIn(-kMaxCoordinateM, kMaxCoordinateM, " m"));
  return Vec3{xyz[0], xyz[1], xyz[2]};
}

// Every element of a list as [x, y, z].
Result<std::vector<Vec3>> readPoints(const JsonReader& list) {
  std::vector<Vec3> points;
  for (std::size_t v = 0; v < list.size(); ++v) {
    Vec3 point;
    GLARECAM_ASSIGN(point, readPoint(list.element(v)));
    points.push_back(point);
  }
  return points;
}

Status readSite(const JsonReader& document, HazardSite& site) {
  JsonReader json;
  GLARECAM_ASSIGN(json, document.objectMember("site"));
  GLARECAM_CHECK(json.onlyKeys({"latitude_deg", "longitude_deg", "elevation_m", "utc_offset_h",
                                "pressure_hpa", "temperature_c"}));
  sun::SiteLocation& location = site.location;
  GLARECAM_ASSIGN(location.latitude_deg, json.numberIn("latitude_deg", -90, 90, "°"));
  GLARECAM_ASSIGN(location.longitude_deg, json.numberIn("longitude_deg", -180, 180, "°"));
  GLARECAM_ASSIGN(site.utc_offset_h,
                  json.numberIn("utc_offset_h", kMinUtcOffsetH, kMaxUtcOffsetH, " h"));
  std::optional<double> elevation_m, pressure_hpa, temperature_c;
  GLARECAM_ASSIGN(elevation_m, json.optionalNumberIn("elevation_m", -1000, 10000, " m"));
  GLARECAM_ASSIGN(pressure_hpa, json.optionalNumberIn("pressure_hpa", 0, 5000, " hPa"));
  GLARECAM_ASSIGN(temperature_c, json.optionalNumberIn("temperature_c", -90, 60, " °C"));
  if (elevation_m) location.altitude_m = *elevation_m;
  location.pressure_hpa = pressure_hpa.value_or(sun::standardPressureHpa(location.altitude_m));
  if (temperature_c) location.temperature_c = *temperature_c;
  return {};
}

Result<std::string> readName(const JsonReader& json, std::set<std::string>& seen,
                             const char* kind) {
  std::string name;
  GLARECAM_ASSIGN(name, json.text("name"));
  if (name.empty()) return json.fail("name", "is empty");
  if (!seen.insert(name).second)
    return json.fail("name", "repeats the " + std::string(kind) + " name \"" + name + "\"");
  return name;
}

// A non-empty array member of the document (`what`: why it may not be empty).
Result<JsonReader> nonEmptyArray(const JsonReader& document, const char* key, const char* what) {
  JsonReader list;
  GLARECAM_ASSIGN(list, document.arrayMember(key));
  if (list.size() == 0) return list.fail(std::string("is empty (the scene needs ") + what + ")");
  return list;
}

Status readArrays(const JsonReader& document, const std::filesystem::path& base, Scene& scene) {
  JsonReader list;
  GLARECAM_ASSIGN(list, nonEmptyArray(document, "arrays", "an array"));
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader json = list.element(i);
    GLARECAM_CHECK(json.onlyKeys({"name", "vertices_m", "profile"}));
    std::string name;
    GLARECAM_ASSIGN(name, readName(json, names, "array"));
    JsonReader vertices_json;
    GLARECAM_ASSIGN(vertices_json, json.arrayMember("vertices_m"));
    std::vector<Vec3> vertices;
    GLARECAM_ASSIGN(vertices, readPoints(vertices_json));
    ArrayPolygon array;
    GLARECAM_ASSIGN(array, makeArrayPolygon(std::move(name), std::move(vertices), json.file(),
                                            vertices_json.path()));
    std::optional<std::string> profile;
    GLARECAM_ASSIGN(profile, json.optionalText("profile"));
    if (profile) {
      if (profile->empty()) return json.fail("profile", "is empty");
      const std::filesystem::path path(*profile);
      array.profile = path.is_absolute() ? path : base / path;
    }
    if (array.normal.z < kFacesDownwardNormalZ) {
      scene.warnings.push_back(json.file() + ": array \"" + array.name +
                               "\" faces downward (its vertices may run clockwise seen from "
                               "its front)");
    }
    scene.arrays.push_back(std::move(array));
  }
  return {};
}

// In a version-1 scene, a key of version 2: named with the schema that has it.
Status refuseNewerKeys(const JsonReader& json, std::initializer_list<const char*> keys) {
  for (const char* key : keys) {
    if (json.has(key))
      return json.fail(key, std::string("is a key of ") + kSceneSchema + " (give \"schema\": \"" +
                                kSceneSchema + "\")");
  }
  return {};
}

// An optional [from, to] window of local standard hours.
Status readHours(const JsonReader& json, double& from_h, double& to_h) {
  std::optional<JsonReader> hours;
  GLARECAM_ASSIGN(hours, json.optionalArray("hours"));
  if (!hours) return {};
  if (hours->size() != 2) return hours->fail("is not [from, to] in hours");
  GLARECAM_ASSIGN(from_h, hours->element(0).numberIn(0, 24, " h"));
  GLARECAM_ASSIGN(to_h, hours->element(1).numberIn(0, 24, " h"));
  if (from_h >= to_h) return hours->fail("is an empty window (from must be before to)");
  return {};
}

Result<double> readFieldOfView(const JsonReader& json, double default_deg) {
  std::optional<double> field_of_view_deg;
  GLARECAM_ASSIGN(field_of_view_deg, json.optionalNumberIn("field_of_view_deg", 0, 180, "°"));
  if (field_of_view_deg && *field_of_view_deg <= 0)
    return json.fail("field_of_view_deg", "is 0° (no direction would count)");
  return field_of_view_deg.value_or(default_deg);
}

// A receptor's points are the scene's observers from `first` on.
void addReceptor(Scene& scene, ReceptorKind kind, std::string name, std::size_t first) {
  for (std::size_t i = first; i < scene.observers.size(); ++i)
    scene.observers[i].receptor = scene.receptors.size();
  scene.receptors.push_back({.kind = kind,
                             .name = std::move(name),
                             .first = first,
                             .count = scene.observers.size() - first});
}

Status checkPointCount(const JsonReader& json, std::size_t count) {
  if (count > kMaxReceptorPoints) {
    return json.fail("spacing_m", "samples " + std::to_string(count) + " points, more than " +
                                      std::to_string(kMaxReceptorPoints) + " (is it too fine?)");
  }
  return {};
}

Status readObservers(const JsonReader& document, Scene& scene, std::set<std::string>& names) {
  std::optional<JsonReader> list;
  if (scene.version == 1) {
    JsonReader required;
    GLARECAM_ASSIGN(required, nonEmptyArray(document, "observers", "an observer"));
    list = required;
  } else {
    GLARECAM_ASSIGN(list, document.optionalArray("observers"));
  }
  if (!list) return {};
  for (std::size_t i = 0; i < list->size(); ++i) {
    const JsonReader json = list->element(i);
    if (scene.version == 1) {
      GLARECAM_CHECK(refuseNewerKeys(json, {"facing_azimuth_deg", "field_of_view_deg"}));
      GLARECAM_CHECK(json.onlyKeys({"name", "position_m", "hours"}));
    } else {
      GLARECAM_CHECK(json.onlyKeys(
          {"name", "position_m", "hours", "facing_azimuth_deg", "field_of_view_deg"}));
    }
    Observer observer;
    GLARECAM_ASSIGN(observer.name, readName(json, names, "observer"));
    JsonReader position;
    GLARECAM_ASSIGN(position, json.member("position_m"));
    GLARECAM_ASSIGN(observer.position_m, readPoint(position));
    GLARECAM_CHECK(readHours(json, observer.from_h, observer.to_h));
    std::optional<double> facing_deg;
    GLARECAM_ASSIGN(facing_deg, json.optionalNumberIn("facing_azimuth_deg", 0, 360, "°"));
    if (facing_deg) {
      observer.view_azimuths_deg = {*facing_deg};
      GLARECAM_ASSIGN(observer.field_of_view_deg, readFieldOfView(json, kWindowFieldOfViewDeg));
    } else if (json.has("field_of_view_deg")) {
      return json.fail("field_of_view_deg", "needs facing_azimuth_deg (the direction it is about)");
    }
    const std::size_t first = scene.observers.size();
    std::string name = observer.name;
    scene.observers.push_back(std::move(observer));
    addReceptor(scene, ReceptorKind::kObserver, std::move(name), first);
  }
  return {};
}

// The compass azimuth of a horizontal direction, [0, 360).
double azimuthDeg(double east, double north) {
  const double azimuth_deg = degrees(std::atan2(east, north));
  return azimuth_deg < 0 ? azimuth_deg + 360 : azimuth_deg;
}

std::string metresText(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", std::round(metres * 100) / 100);
  return text;
}

Status readRoutes(const JsonReader& document, Scene& scene, std::set<std::string>& names) {
  std::optional<JsonReader> list;
  GLARECAM_ASSIGN(list, document.optionalArray("routes"));
  if (!list) return {};
  for (std::size_t i = 0; i < list->size(); ++i) {
    const JsonReader json = list->element(i);
    GLARECAM_CHECK(json.onlyKeys(
        {"name", "points_m", "spacing_m", "direction", "field_of_view_deg", "hours"}));
    std::string name;
    GLARECAM_ASSIGN(name, readName(json, names, "receptor"));
    JsonReader points_json;
    GLARECAM_ASSIGN(points_json, json.arrayMember("points_m"));
    if (points_json.size() < 2)
      return points_json.fail("has fewer than 2 points (a route is a line)");
    std::vector<Vec3> points;
    for (std::size_t p = 0; p < points_json.size(); ++p) {
      Vec3 point;
      GLARECAM_ASSIGN(point, readPoint(points_json.element(p)));
      if (!points.empty() && norm(point - points.back()) < kSameVertexM)
        return points_json.element(p).fail("repeats the point before it");
      if (!points.empty() &&
          std::hypot(point.x - points.back().x, point.y - points.back().y) < kSameVertexM) {
        return points_json.element(p).fail(
            "is straight above or below the point before it (a route runs along the ground)");
      }
      points.push_back(point);
    }
    std::optional<double> spacing_m;
    GLARECAM_ASSIGN(spacing_m, json.optionalPositive("spacing_m"));
    const double spacing = spacing_m.value_or(kDefaultRouteSpacingM);
    std::optional<std::string> direction;
    GLARECAM_ASSIGN(direction, json.optionalWord("direction", {"forward", "backward", "both"}));
    const std::string travel = direction.value_or("both");
    double field_of_view_deg = 0;
    GLARECAM_ASSIGN(field_of_view_deg, readFieldOfView(json, kDriverFieldOfViewDeg));
    double from_h = 0, to_h = 24;
    GLARECAM_CHECK(readHours(json, from_h, to_h));

    double length_m = 0;
    for (std::size_t p = 1; p < points.size(); ++p) length_m += norm(points[p] - points[p - 1]);
    // Samples at 0, spacing, 2·spacing, … along the line, and its end.
    const double whole = std::floor(length_m / spacing);
    const bool end_apart = length_m - whole * spacing > kReceptorSnapM;
    GLARECAM_CHECK(checkPointCount(
        json, static_cast<std::size_t>(std::min(whole, 1e12)) + 1 + (end_apart ? 1 : 0)));
    const auto count = static_cast<std::size_t>(whole) + 1;
    std::vector<double> stations;
    for (std::size_t k = 0; k < count; ++k) stations.push_back(static_cast<double>(k) * spacing);
    if (end_apart) stations.push_back(length_m);
    const std::size_t first = scene.observers.size();
    std::size_t segment = 0;
    double segment_start_m = 0;
    for (const double station : stations) {
      while (segment + 2 < points.size() &&
             station >= segment_start_m + norm(points[segment + 1] - points[segment])) {
        segment_start_m += norm(points[segment + 1] - points[segment]);
        ++segment;
      }
      const Vec3 a = points[segment], b = points[segment + 1];
      const double t = std::clamp((station - segment_start_m) / norm(b - a), 0.0, 1.0);
      Observer observer;
      observer.name = name + "@" + metresText(station) + "m";
      observer.position_m = a + t * (b - a);
      observer.from_h = from_h, observer.to_h = to_h;
      const double forward_deg = azimuthDeg(b.x - a.x, b.y - a.y);
      const double backward_deg = std::fmod(forward_deg + 180, 360);
      if (travel != "backward") observer.view_azimuths_deg.push_back(forward_deg);
      if (travel != "forward") observer.view_azimuths_deg.push_back(backward_deg);
      observer.field_of_view_deg = field_of_view_deg;
      scene.observers.push_back(std::move(observer));
    }
    addReceptor(scene, ReceptorKind::kRoute, std::move(name), first);
  }
  return {};
}

Status readAreas(const JsonReader& document, Scene& scene, std::set<std::string>& names) {
  std::optional<JsonReader> list;
  GLARECAM_ASSIGN(list, document.optionalArray("areas"));
  if (!list) return {};
  for (std::size_t i = 0; i < list->size(); ++i) {
    const JsonReader json = list->element(i);
    GLARECAM_CHECK(json.onlyKeys({"name", "vertices_m", "eye_height_m", "spacing_m", "hours"}));
    std::string name;
    GLARECAM_ASSIGN(name, readName(json, names, "receptor"));
    JsonReader vertices_json;
    GLARECAM_ASSIGN(vertices_json, json.arrayMember("vertices_m"));
    std::vector<Vec3> vertices;
    GLARECAM_ASSIGN(vertices, readPoints(vertices_json));
    ArrayPolygon polygon;
    GLARECAM_ASSIGN(polygon,
                    makeArrayPolygon(name, std::move(vertices), json.file(), vertices_json.path()));
    std::optional<double> eye_height_m, spacing_m;
    GLARECAM_ASSIGN(eye_height_m, json.optionalNumberIn("eye_height_m", 0, 1000, " m"));
    GLARECAM_ASSIGN(spacing_m, json.optionalPositive("spacing_m"));
    const double spacing = spacing_m.value_or(kDefaultAreaSpacingM);
    double from_h = 0, to_h = 24;
    GLARECAM_CHECK(readHours(json, from_h, to_h));
    // Cell centres of a grid in the polygon's own plane, aligned with its bounding box there;
    // a polygon smaller than one cell gets its centroid. The grid's rows run up its slope, or
    // north on a polygon within kLevelAreaTiltDeg of level: a terrace drawn on a map is level
    // but for rounding and the Earth's curvature, whose micro-tilt must not turn its grid.
    Vec3 axis_u = polygon.axis_u, axis_w = polygon.axis_w;
    if (std::abs(polygon.normal.z) >= std::cos(radians(kLevelAreaTiltDeg))) {
      const Vec3 north{0, 1, 0};
      axis_w = normalised(north - dot(north, polygon.normal) * polygon.normal);
      axis_u = normalised(cross(axis_w, polygon.normal));
    }
    double u_min = 0, u_max = 0, w_min = 0, w_max = 0;
    for (const Vec3& vertex : polygon.vertices_m) {
      const double u = dot(vertex - polygon.centroid_m, axis_u);
      const double w = dot(vertex - polygon.centroid_m, axis_w);
      u_min = std::min(u_min, u), u_max = std::max(u_max, u);
      w_min = std::min(w_min, w), w_max = std::max(w_max, w);
    }
    const double columns =
        std::max(1.0, std::ceil((u_max - u_min - kReceptorSnapM) / spacing - 1e-9));
    const double rows = std::max(1.0, std::ceil((w_max - w_min - kReceptorSnapM) / spacing - 1e-9));
    GLARECAM_CHECK(checkPointCount(json, static_cast<std::size_t>(std::min(columns * rows, 1e12))));
    const double u0 = (u_min + u_max) / 2 - (columns - 1) * spacing / 2;
    const double w0 = (w_min + w_max) / 2 - (rows - 1) * spacing / 2;
    const Vec3 eye{0, 0, eye_height_m.value_or(kDefaultEyeHeightM)};
    const std::size_t first = scene.observers.size();
    auto add = [&](Vec3 ground) {
      Observer observer;
      observer.name = name + "[" + std::to_string(scene.observers.size() - first) + "]";
      observer.position_m = ground + eye;
      observer.from_h = from_h, observer.to_h = to_h;
      scene.observers.push_back(std::move(observer));
    };
    for (int r = 0; r < static_cast<int>(rows); ++r) {
      for (int c = 0; c < static_cast<int>(columns); ++c) {
        const Vec3 ground =
            polygon.centroid_m + (u0 + c * spacing) * axis_u + (w0 + r * spacing) * axis_w;
        if (containsPlanePoint(polygon, ground)) add(ground);
      }
    }
    if (scene.observers.size() == first) add(polygon.centroid_m);
    addReceptor(scene, ReceptorKind::kArea, std::move(name), first);
  }
  return {};
}

Status readObstructions(const JsonReader& document, Scene& scene) {
  std::optional<JsonReader> list;
  GLARECAM_ASSIGN(list, document.optionalArray("obstructions"));
  if (!list) return {};
  std::set<std::string> names;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const JsonReader json = list->element(i);
    GLARECAM_CHECK(json.onlyKeys({"name", "footprint_m", "base_m", "height_m", "vertices_m"}));
    std::string name;
    GLARECAM_ASSIGN(name, readName(json, names, "obstruction"));
    const bool footprint = json.has("footprint_m"), planar = json.has("vertices_m");
    if (footprint == planar)
      return json.fail(
          std::string(footprint ? "has both footprint_m and" : "has neither footprint_m nor") +
          " vertices_m (give one: an extruded footprint or a polygon)");
    Obstruction obstruction;
    if (planar) {
      if (json.has("base_m") || json.has("height_m"))
        return json.fail("base_m and height_m belong to a footprint_m, not to vertices_m");
      JsonReader vertices_json;
      GLARECAM_ASSIGN(vertices_json, json.arrayMember("vertices_m"));
      std::vector<Vec3> vertices;
      GLARECAM_ASSIGN(vertices, readPoints(vertices_json));
      GLARECAM_ASSIGN(obstruction, makePlanarObstruction(std::move(name), std::move(vertices),
                                                         json.file(), vertices_json.path()));
    } else {
      JsonReader footprint_json;
      GLARECAM_ASSIGN(footprint_json, json.arrayMember("footprint_m"));
      std::vector<std::array<double, 2>> footprint_m;
      for (std::size_t v = 0; v < footprint_json.size(); ++v) {
        const JsonReader point = footprint_json.element(v);
        GLARECAM_CHECK(point.array());
        if (point.size() != 2) return point.fail("is not [x, y] (2 numbers in metres)");
        std::array<double, 2> xy{};
        for (std::size_t k = 0; k < 2; ++k)
          GLARECAM_ASSIGN(xy[k],
                          point.element(k).numberIn(-kMaxCoordinateM, kMaxCoordinateM, " m"));
        footprint_m.push_back(xy);
      }
      std::optional<double> base_m;
      GLARECAM_ASSIGN(base_m,
                      json.optionalNumberIn("base_m", -kMaxCoordinateM, kMaxCoordinateM, " m"));
      double height_m = 0;
      GLARECAM_ASSIGN(height_m, json.numberIn("height_m", -kMaxCoordinateM, kMaxCoordinateM, " m"));
      GLARECAM_ASSIGN(obstruction,
                      makeExtrudedObstruction(std::move(name), footprint_m, base_m.value_or(0),
                                              height_m, json.file(), json.path()));
    }
    scene.obstructions.push_back(std::move(obstruction));
  }
  return {};
}

// A receptor behind an array's plane, or on it, never sees its front: the array can add no
// minute there. Inside the building, on the roof, or a facade listed the wrong way round; in a
// district also the ordinary case of a window facing away from a roof. Only the pairs within
// kHiddenFrontDistanceM count (found through an R-tree: never observers × arrays), and a
// route's or area's pair only when none of its points there sees the front. A handful of pairs
// is a small scene's drawing mistake: a warning each. More is a district: one line counting them
// with examples, and one naming the arrays that every receptor near them sees from behind, the
// ones whose vertices are most likely listed the wrong way round.
constexpr double kHiddenFrontDistanceM = kDefaultMaxDistanceM;
constexpr std::size_t kHiddenFrontPairsListed = 10, kHiddenFrontExamples = 3,
                      kBackOnlyArraysNamed = 5;

std::string receptorWho(const Receptor& receptor, const char* observer_verb,
                        const char* receptor_verb) {
  if (receptor.kind == ReceptorKind::kObserver)
    return "observer \"" + receptor.name + "\" (observers[" + std::to_string(receptor.first) +
           "])" + observer_verb;
  return std::string(receptorKindName(receptor.kind)) + " \"" + receptor.name + "\"" +
         receptor_verb;
}

void warnHiddenFronts(const std::string& file, Scene& scene) {
  const std::vector<std::vector<std::size_t>> near = arraysWithin(scene, kHiddenFrontDistanceM);
  struct Pair {
    std::size_t array, receptor;
    auto operator<=>(const Pair&) const = default;
  };
  std::vector<Pair> hidden;
  // Per array: the receptors within the distance, and of those the ones that see its front.
  std::vector<std::size_t> near_receptors(scene.arrays.size(), 0),
      front_seen(scene.arrays.size(), 0);
  for (std::size_t r = 0; r < scene.receptors.size(); ++r) {
    const Receptor& receptor = scene.receptors[r];
    std::map<std::size_t, bool> seen;  // per array near one of its points: a point sees the front
    for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
      for (const std::size_t a : near[o]) {
        bool& front = seen[a];
        front = front || seesFront(scene.arrays[a], scene.observers[o].position_m);
      }
    }
    for (const auto& [a, front] : seen) {
      ++near_receptors[a];
      if (front)
        ++front_seen[a];
      else
        hidden.push_back({a, r});
    }
  }
  std::sort(hidden.begin(), hidden.end());
  if (hidden.size() <= kHiddenFrontPairsListed) {
    for (const Pair& pair : hidden) {
      scene.warnings.push_back(
          file + ": " + receptorWho(scene.receptors[pair.receptor], " is", " lies wholly") +
          " behind or on the plane of array \"" + scene.arrays[pair.array].name + "\" (arrays[" +
          std::to_string(pair.array) +
          "]) and never sees its front, so that array adds no glare there (are the array's "
          "vertices listed the wrong way round?)");
    }
    return;
  }
  std::set<std::size_t> receptors, arrays;
  for (const Pair& pair : hidden) receptors.insert(pair.receptor), arrays.insert(pair.array);
  std::string examples;
  for (std::size_t i = 0; i < std::min(hidden.size(), kHiddenFrontExamples); ++i) {
    const Pair& pair = hidden[i];
    examples += (i ? "; " : "") + receptorWho(scene.receptors[pair.receptor], "", "") +
                " and array \"" + scene.arrays[pair.array].name + "\" (arrays[" +
                std::to_string(pair.array) + "])";
  }
  scene.warnings.push_back(fmt::format(
      "{}: {} of {} receptors each see some array within {} m only from behind or edge-on "
      "({} receptor–array pairs, {} arrays; in a district mostly windows and roads facing away "
      "from a roof), so those arrays add no glare there (others may); e.g. {}",
      file, receptors.size(), scene.receptors.size(), kHiddenFrontDistanceM, hidden.size(),
      arrays.size(), examples));
  std::vector<std::size_t> back_only;
  for (std::size_t a = 0; a < scene.arrays.size(); ++a)
    if (near_receptors[a] > 0 && front_seen[a] == 0) back_only.push_back(a);
  if (back_only.empty()) return;
  std::string named;
  for (std::size_t i = 0; i < std::min(back_only.size(), kBackOnlyArraysNamed); ++i)
    named += fmt::format("{}\"{}\" (arrays[{}])", i ? ", " : "", scene.arrays[back_only[i]].name,
                         back_only[i]);
  if (back_only.size() > kBackOnlyArraysNamed)
    named += fmt::format(" and {} more", back_only.size() - kBackOnlyArraysNamed);
  scene.warnings.push_back(fmt::format(
      "{}: {} array{} seen only from behind by every receptor within {} m: {} (are {} vertices "
      "listed the wrong way round?)",
      file, back_only.size(), back_only.size() == 1 ? " is" : "s are", kHiddenFrontDistanceM, named,
      back_only.size() == 1 ? "its" : "their"));
}

}  // namespace

Scene::Scene() = default;
Scene::~Scene() = default;
Scene::Scene(const Scene&) = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(const Scene&) = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

const char* receptorKindName(ReceptorKind kind) {
  switch (kind) {
    case ReceptorKind::kObserver:
      return "observer";
    case ReceptorKind::kRoute:
      return "route";
    case ReceptorKind::kArea:
      return "area";
  }
  return "receptor";
}

Result<ArrayPolygon> makeArrayPolygon(std::string name, std::vector<Vec3> vertices_m,
                                      const std::string& file, const std::string& field) {
  const auto fail = [&](const std::string& problem) {
    return badInput(file + ": " + field + " " + problem);
  };
  const std::size_t count = vertices_m.size();
  if (count < 3) return fail("has " + std::to_string(count) + " vertices (a polygon needs 3)");
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) {
      if (norm(vertices_m[i] - vertices_m[j]) < kSameVertexM) {
        return fail("repeats a vertex (" + std::to_string(i) + " and " + std::to_string(j) + ")");
      }
    }
  }
  ArrayPolygon array;
  array.name = std::move(name);
  const Vec3 newell = newellVector(vertices_m, kAllVertices);
  array.area_m2 = norm(newell) / 2;
  if (!std::isfinite(array.area_m2)) return fail("has coordinates too large to use");
  // Newell's normal, the front (the side from which the vertices run counter-clockwise), when
  // they enclose area; else a bow-tie's plane, for the checks below to say what is wrong.
  const VertexPlane plane = fitPlane(vertices_m, kAllVertices);
  if (plane.normal == Vec3{}) return fail("is degenerate (its vertices lie on one line)");
  array.normal = plane.normal;
  array.centroid_m = plane.point_m;
  for (std::size_t i = 0; i < count; ++i) {
    if (!(std::abs(dot(vertices_m[i] - array.centroid_m, array.normal)) <= kPlanarityToleranceM)) {
      // Off the plane of them all: blame the vertex farthest from the plane of the others (the
      // plane of them all leans toward the one that is off, and may pass farther from another).
      const OffPlaneVertex off = farthestOffPlane(vertices_m);
      char text[128];
      std::snprintf(text, sizeof text,
                    "is not planar (vertex %zu lies %.3f m off the plane of the others)", off.index,
                    off.distance_m);
      return fail(text);
    }
    array.radius_m = std::max(array.radius_m, norm(vertices_m[i] - array.centroid_m));
  }
  const Vec3 up{0, 0, 1}, north{0, 1, 0};
  Vec3 slope = up - dot(up, array.normal) * array.normal;
  if (norm(slope) < kLevelTolerance) slope = north - dot(north, array.normal) * array.normal;
  array.up_slope = normalised(slope);
  array.axis_w = array.up_slope;
  array.axis_u = normalised(cross(array.axis_w, array.normal));
  for (const Vec3& vertex : vertices_m) {
    const Vec3 d = vertex - array.centroid_m;
    array.outline.push_back({dot(d, array.axis_u), dot(d, array.axis_w)});
  }
  // Self-intersection before the area: a bow-tie's lobes cancel in the area, and "crosses
  // itself" is what is wrong with it. Any two edges that meet other than at their shared vertex,
  // and adjacent edges that fold back over each other.
  const double epsilon = 1e-12 * array.radius_m * array.radius_m;
  const auto& outline = array.outline;
  const auto edge = [count](std::size_t i) {
    return std::to_string(i) + "\u2013" + std::to_string((i + 1) % count);
  };
  for (std::size_t i = 0; i < count; ++i) {
    const Point2 a = outline[i], b = outline[(i + 1) % count];
    for (std::size_t j = i + 1; j < count; ++j) {
      const Point2 c = outline[j], d = outline[(j + 1) % count];
      const bool adjacent = j == i + 1 || (i == 0 && j == count - 1);
      if (!adjacent) {
        if (segmentsMeet(a, b, c, d, epsilon))
          return fail("crosses itself (edges " + edge(i) + " and " + edge(j) + " cross)");
        continue;
      }
      // Shared vertex; they cross elsewhere only when collinear and doubling back.
      const Point2 shared = j == i + 1 ? b : a;
      const Point2 p = j == i + 1 ? a : b;
      const Point2 q = j == i + 1 ? d : c;
      const double turn = cross2(shared, p, q);
      const double along =
          (p[0] - shared[0]) * (q[0] - shared[0]) + (p[1] - shared[1]) * (q[1] - shared[1]);
      if (std::abs(turn) <= epsilon && along > 0)
        return fail("crosses itself (edges " + edge(i) + " and " + edge(j) + " overlap)");
    }
  }
  if (!(array.area_m2 >= kMinArrayAreaM2))
    return fail("is degenerate (its vertices enclose no area)");
  array.vertices_m = std::move(vertices_m);
  return array;
}

bool seesFront(const ArrayPolygon& array, Vec3 point_m) {
  return dot(point_m - array.centroid_m, array.normal) > kPlanarityToleranceM;
}

std::optional<double> facingAzimuthDeg(const ArrayPolygon& array) {
  if (std::hypot(array.normal.x, array.normal.y) < kLevelTolerance) return std::nullopt;
  const double azimuth_deg = degrees(std::atan2(array.normal.x, array.normal.y));
  return azimuth_deg < 0 ? azimuth_deg + 360 : azimuth_deg;
}

double tiltDeg(const ArrayPolygon& array) {
  return degrees(angleBetweenRad(array.normal, Vec3{0, 0, 1}));
}

Result<Scene> parseScene(const nlohmann::json& document, const std::string& file,
                         const std::filesystem::path& base) {
  const JsonReader fields(document, file);
  std::string schema;
  GLARECAM_ASSIGN(schema, fields.schema(kSceneSchema, "a hazard scene", {kSceneSchemaV1}));
  Scene scene;
  scene.version = schema == kSceneSchemaV1 ? 1 : 2;
  // Every object's keys are checked: a typo in an optional key ("profil", "hour") must never
  // silently change the result.
  if (scene.version == 1) {
    GLARECAM_CHECK(refuseNewerKeys(fields, {"routes", "areas", "obstructions"}));
    GLARECAM_CHECK(fields.onlyKeys({"schema", "site", "arrays", "observers"}));
  } else {
    GLARECAM_CHECK(fields.onlyKeys(
        {"schema", "site", "arrays", "observers", "routes", "areas", "obstructions"}));
  }
  GLARECAM_CHECK(readSite(fields, scene.site));
  GLARECAM_CHECK(readArrays(fields, base, scene));
  std::set<std::string> receptor_names;
  GLARECAM_CHECK(readObservers(fields, scene, receptor_names));
  GLARECAM_CHECK(readRoutes(fields, scene, receptor_names));
  GLARECAM_CHECK(readAreas(fields, scene, receptor_names));
  if (scene.observers.empty())
    return fields.fail("has no observer, route or area (the scene needs a receptor)");
  GLARECAM_CHECK(readObstructions(fields, scene));
  warnHiddenFronts(file, scene);
  return scene;
}

Result<Scene> readScene(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::ranges::transform(extension, extension.begin(),
                         [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".kml") return readKmlScene(path);
  nlohmann::json document;
  GLARECAM_ASSIGN(document, readJsonFile(path.string()));
  Scene scene;
  if (isGeoJson(document)) {
    GLARECAM_ASSIGN(scene, parseGeoJsonScene(document, path.string(), path.parent_path()));
  } else {
    GLARECAM_ASSIGN(scene, parseScene(document, path.string(), path.parent_path()));
  }
  scene.path = path;
  return scene;
}

}  // namespace glarecam::hazard
