#include "hazard/geo_scene.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>

#include "hazard/geo_frame.h"
#include "hazard/hazard_calculation.h"
#include "hazard/obstruction.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

// The site of hazard.md's example: the first array's first vertex 10 m above the ground there.
constexpr double kLon = 8.54, kLat = 47.37, kGround = 410, kSiteHeight = 10;

// What PROJ's own command-line tool says of the points: cct with the frame's pipeline, each
// point's x, y, z (or lon, lat, h with `inverse`). Empty when cct is not installed.
std::vector<std::array<double, 3>> cctSays(const std::string& pipeline,
                                           const std::vector<std::array<double, 3>>& points,
                                           bool inverse = false) {
  if (std::system("command -v cct >/dev/null 2>&1") != 0) return {};
  std::string input;
  for (const auto& p : points) input += fmt::format("{:.12f} {:.12f} {:.12f}\n", p[0], p[1], p[2]);
  const std::string command =
      fmt::format("printf '{}' | cct -d 10 {} {}", input, inverse ? "-I" : "", pipeline);
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::vector<std::array<double, 3>> out;
  if (!pipe) return out;
  char line[512];
  while (std::fgets(line, sizeof line, pipe.get())) {
    std::array<double, 3> p{};
    if (std::sscanf(line, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3) out.push_back(p);
  }
  return out;
}

GeoFrame siteFrame() { return *GeoFrame::make(kLon, kLat, kGround + kSiteHeight); }

TEST(GeoFrame, AgreesWithProjsCommandLineToolBothWays) {
  const GeoFrame frame = siteFrame();
  const std::vector<std::array<double, 3>> points{
      {kLon, kLat, kGround + kSiteHeight}, {8.5412, 47.3721, 432.1}, {8.60, 47.40, 500}};
  const std::vector<std::array<double, 3>> expected = cctSays(frame.pipeline(), points);
  if (expected.empty()) GTEST_SKIP() << "PROJ's cct is not installed (Debian proj-bin)";
  ASSERT_EQ(expected.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 enu = frame.toEnu(points[i][0], points[i][1], points[i][2]);
    // A millimetre: the contract's "exactly" at survey precision (cct prints 10 decimals).
    EXPECT_NEAR(enu.x, expected[i][0], 1e-3) << i;
    EXPECT_NEAR(enu.y, expected[i][1], 1e-3) << i;
    EXPECT_NEAR(enu.z, expected[i][2], 1e-3) << i;
    // The origin is the origin; 5 km away the Earth has curved 2 m below the horizontal plane.
    if (i == 0) {
      EXPECT_NEAR(norm(enu), 0, 1e-6);
    }
    const LonLatH back = frame.toLonLatH(enu);
    EXPECT_NEAR(back[0], points[i][0], 1e-10) << i;  // 1e-10° is 11 µm
    EXPECT_NEAR(back[1], points[i][1], 1e-10) << i;
    EXPECT_NEAR(back[2], points[i][2], 1e-6) << i;
  }
  const Vec3 far = frame.toEnu(8.60, 47.40, kGround + kSiteHeight);
  const double distance = std::hypot(far.x, far.y);
  EXPECT_NEAR(far.z, -distance * distance / (2 * 6.371e6), 0.05 * distance * distance / 6.371e6);
  // And the inverse against cct -I.
  const std::vector<std::array<double, 3>> inverse =
      cctSays(frame.pipeline(), {{100, -200, 5}}, true);
  ASSERT_EQ(inverse.size(), 1u);
  const LonLatH ours = frame.toLonLatH({100, -200, 5});
  EXPECT_NEAR(ours[0], inverse[0][0], 1e-9);
  EXPECT_NEAR(ours[1], inverse[0][1], 1e-9);
  EXPECT_NEAR(ours[2], inverse[0][2], 1e-3);
}

TEST(GeoFrame, ACopyAndTheVectorFormsConvertAlike) {
  const GeoFrame frame = siteFrame();
  const GeoFrame copy = frame;  // NOLINT(performance-unnecessary-copy-initialization)
  const std::vector<LonLatH> positions{{8.541, 47.371, 415}, {8.539, 47.369, 405}};
  const std::vector<Vec3> points = copy.toEnu(positions);
  ASSERT_EQ(points.size(), 2u);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    EXPECT_EQ(points[i], frame.toEnu(positions[i][0], positions[i][1], positions[i][2]));
    const std::vector<LonLatH> back = frame.toLonLatH(std::vector<Vec3>{points[i]});
    EXPECT_NEAR(back[0][0], positions[i][0], 1e-12);
  }
  EXPECT_FALSE(GeoFrame::make(47.37, 95, 0));  // no latitude
}

// A scene designed in metres around the site: a west-facing facade, a window and a road west of
// it, a terrace, and a shed in between; `geoJsonOf` draws it on the map.
struct DesignedFeature {
  std::string kind, name, geometry;
  std::vector<Vec3> points_m;  // in the frame
  json extra = json::object();
};

std::vector<DesignedFeature> designedScene() {
  return {
      {"array", "facade", "Polygon", {{0, 0, 0}, {0, 0, -5}, {0, -10, -5}, {0, -10, 0}}},
      {"observer", "window", "Point", {{-31, 12, -3}}, {{"hours", {6, 22}}}},
      {"route",
       "road",
       "LineString",
       {{-40, -20, -8.4}, {-40, 40, -8.4}},
       {{"spacing_m", 30}, {"direction", "both"}}},
      {"area",
       "terrace",
       "Polygon",
       {{-25, 0, -10}, {-21, 0, -10}, {-21, 4, -10}, {-25, 4, -10}},
       {{"spacing_m", 2}}},
      {"obstruction",
       "shed",
       "Polygon",
       {{-15, -14, -10}, {-12, -14, -10}, {-12, -10, -10}, {-15, -10, -10}},
       {{"base_m", 0}, {"height_m", 3}}},
  };
}

// The designed scene as GeoJSON, heights above the ground at kGround (the frame's origin is
// kSiteHeight above it).
json geoJsonOf(const std::vector<DesignedFeature>& design, const GeoFrame& frame) {
  json features = json::array();
  for (const DesignedFeature& feature : design) {
    json coordinates = json::array();
    for (const Vec3& p : feature.points_m) {
      const LonLatH position = frame.toLonLatH(p);
      coordinates.push_back({position[0], position[1], position[2] - kGround});
    }
    if (feature.geometry == "Point") coordinates = coordinates[0];
    if (feature.geometry == "Polygon") {
      coordinates.push_back(coordinates[0]);  // RFC 7946's closed ring
      coordinates = json::array({coordinates});
    }
    json properties = feature.extra;
    properties["kind"] = feature.kind;
    properties["name"] = feature.name;
    features.push_back({{"type", "Feature"},
                        {"properties", properties},
                        {"geometry", {{"type", feature.geometry}, {"coordinates", coordinates}}}});
  }
  return {{"type", "FeatureCollection"},
          {"glarecam",
           {{"schema", "glarecam.hazard-geo/1"},
            {"utc_offset_h", 1.0},
            {"vertical_reference", "ground"},
            {"ground_elevation_m", kGround}}},
          {"features", features}};
}

// The ENU twin: the same features written in metres, each position the frame's conversion of
// the GeoJSON's; a footprint at its mean converted height.
json enuTwinOf(const json& geojson, const GeoFrame& frame) {
  json twin{{"schema", "glarecam.hazard-scene/2"},
            {"site",
             {{"latitude_deg", frame.latitudeDeg()},
              {"longitude_deg", frame.longitudeDeg()},
              {"elevation_m", frame.heightM()},
              {"utc_offset_h", 1.0}}}};
  const auto enu = [&](const json& position, double height) {
    const Vec3 p = frame.toEnu(position[0], position[1], height);
    return std::array<double, 3>{p.x, p.y, p.z};
  };
  for (const json& feature : geojson["features"]) {
    json entry = feature["properties"];
    const std::string kind = entry["kind"];
    entry.erase("kind");
    const json& coordinates = feature["geometry"]["coordinates"];
    json points = json::array();
    if (kind == "observer") {
      entry["position_m"] = enu(coordinates, kGround + coordinates[2].get<double>());
      twin["observers"].push_back(entry);
      continue;
    }
    const json ring = kind == "route" ? coordinates : coordinates[0];
    const std::size_t count = ring.size() - (kind == "route" ? 0 : 1);
    if (kind == "obstruction") {
      const double base = kGround + entry["base_m"].get<double>();
      double mean_z = 0;
      for (std::size_t v = 0; v < count; ++v) {
        const auto p = enu(ring[v], base);
        points.push_back({p[0], p[1]});
        mean_z += p[2] / static_cast<double>(count);
      }
      entry["footprint_m"] = points;
      entry["height_m"] = mean_z + entry["height_m"].get<double>() - entry["base_m"].get<double>();
      entry["base_m"] = mean_z;
      twin["obstructions"].push_back(entry);
      continue;
    }
    for (std::size_t v = 0; v < count; ++v)
      points.push_back(enu(ring[v], kGround + ring[v][2].get<double>()));
    if (kind == "array")
      twin["arrays"].push_back({{"name", entry["name"]}, {"vertices_m", points}});
    if (kind == "route") {
      entry["points_m"] = points;
      twin["routes"].push_back(entry);
    }
    if (kind == "area") {
      entry["vertices_m"] = points;
      twin["areas"].push_back(entry);
    }
  }
  return twin;
}

TEST(GeoScene, AGeoJsonSceneAndItsEnuTwinGiveTheSameAnswer) {
  const GeoFrame frame = siteFrame();
  const json geojson = geoJsonOf(designedScene(), frame);
  const Result<Scene> geo = parseGeoJsonScene(geojson, "city.geojson", "/base");
  ASSERT_TRUE(geo) << geo.error().message;
  const Result<Scene> twin = parseScene(enuTwinOf(geojson, frame), "twin.json", "/base");
  ASSERT_TRUE(twin) << twin.error().message;
  // The site is the first array's first vertex, at its height above sea level.
  ASSERT_TRUE(geo->geo);
  EXPECT_NEAR(geo->site.location.longitude_deg, kLon, 1e-12);
  EXPECT_NEAR(geo->site.location.latitude_deg, kLat, 1e-12);
  EXPECT_NEAR(geo->site.location.altitude_m, kGround + kSiteHeight, 1e-6);
  EXPECT_NEAR(geo->geo->heightM(), kGround + kSiteHeight, 1e-6);
  // The positions are where they were designed (to the round trip through degrees).
  EXPECT_NEAR(norm(geo->arrays[0].vertices_m[0]), 0, 1e-6);
  EXPECT_NEAR(norm(geo->arrays[0].vertices_m[2] - Vec3{0, -10, -5}), 0, 1e-6);
  EXPECT_NEAR(norm(geo->observers[0].position_m - Vec3{-31, 12, -3}), 0, 1e-6);
  ASSERT_EQ(geo->observers.size(), twin->observers.size());
  ASSERT_EQ(geo->obstructions.size(), 1u);

  const ProfileTable profile = testing::constantProfile(8, 4);
  HazardOptions options;
  options.year = 2027;
  options.models = {{ModelKind::kEllipse}, {ModelKind::kCone, 6.0}};
  options.threads = 1;
  double total_minutes = 0;
  for (const int day : {79, 140, 172}) {  // the equinox, May, the solstice
    options.first_day = day, options.day_count = 1;
    const Result<HazardResult> a = computeHazard(*geo, {&profile}, options);
    const Result<HazardResult> b = computeHazard(*twin, {&profile}, options);
    ASSERT_TRUE(a) << a.error().message;
    ASSERT_TRUE(b) << b.error().message;
    ASSERT_EQ(a->observers.size(), b->observers.size());
    for (std::size_t o = 0; o < a->observers.size(); ++o) {
      EXPECT_EQ(a->observers[o].steps, b->observers[o].steps) << geo->observers[o].name;
      for (std::size_t m = 0; m < options.models.size(); ++m) {
        EXPECT_EQ(a->observers[o].models[m].minutes_per_day,
                  b->observers[o].models[m].minutes_per_day);
        total_minutes += a->observers[o].models[m].minutes_per_year;
      }
    }
    EXPECT_EQ(a->events.size(), b->events.size());
  }
  EXPECT_GT(total_minutes, 0) << "the designed scene should glare somewhere on these days";
}

TEST(GeoScene, RingsLoseTheirClosingVertexAndWarningsNameTheFeature) {
  const GeoFrame frame = siteFrame();
  std::vector<DesignedFeature> design = designedScene();
  design.push_back({"observer", "inside", "Point", {{5, 0, -2}}});  // behind the facade
  const Result<Scene> scene = parseGeoJsonScene(geoJsonOf(design, frame), "city.geojson", "/base");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_EQ(scene->arrays[0].vertices_m.size(), 4u);
  ASSERT_EQ(scene->warnings.size(), 1u) << ::testing::PrintToString(scene->warnings);
  EXPECT_NE(scene->warnings[0].find("observer \"inside\" (features[5]) is behind"),
            std::string::npos)
      << scene->warnings[0];
  EXPECT_NE(scene->warnings[0].find("array \"facade\" (features[0])"), std::string::npos)
      << scene->warnings[0];
}

// The first line of the error a GeoJSON scene gets, or "" when it is accepted.
std::string geoErrorOf(const json& geojson) {
  const Result<Scene> read = parseGeoJsonScene(geojson, "city.geojson", "/base");
  if (read) return "";
  EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(read.error().message.find('\n'), std::string::npos);
  return read.error().message;
}

TEST(GeoScene, RefusesBadGeographicInputNamingTheFeature) {
  const GeoFrame frame = siteFrame();
  const json good = geoJsonOf(designedScene(), frame);
  ASSERT_EQ(geoErrorOf(good), "");
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases{
      {[](json& g) {  // a bow-tie
         auto& ring = g["features"][0]["geometry"]["coordinates"][0];
         std::swap(ring[1], ring[2]);
       },
       "city.geojson: features[0] (\"facade\"): geometry crosses itself (edges 0\u20131 and "
       "2\u20133 cross)"},
      {[](json& g) {
         auto& point = g["features"][1]["geometry"]["coordinates"];
         point[1] = 95.0;
       },
       "city.geojson: features[1] (\"window\"): geometry.coordinates has latitude 95 outside "
       "[-90, 90] (lon/lat swapped? GeoJSON gives [lon, lat, height])"},
      {[](json& g) {  // swapped, yet both in range: 4 000 km away
         auto& point = g["features"][1]["geometry"]["coordinates"];
         std::swap(point[0], point[1]);
       },
       "lon/lat swapped?"},
      {[](json& g) { g["glarecam"].erase("vertical_reference"); },
       "city.geojson: glarecam.vertical_reference is missing (\"ground\": heights are metres "
       "above the ground at ground_elevation_m; \"sea\": metres above sea level)"},
      {[](json& g) { g["features"][1]["properties"]["kind"] = "observr"; },
       "city.geojson: features[1] (\"window\"): properties.kind \"observr\" is not a kind (did "
       "you mean \"observer\"?; known: array, observer, route, area, obstruction)"},
      {[](json& g) { g.erase("glarecam"); }, "city.geojson: the document has no \"glarecam\""},
      {[](json& g) { g["glarecam"].erase("schema"); }, "city.geojson: glarecam.schema is missing"},
      {[](json& g) { g["features"][1]["geometry"] = g["features"][2]["geometry"]; },
       "city.geojson: features[1] (\"window\"): geometry is a LineString; a feature of kind "
       "observer is a Point"},
      {[](json& g) {
         g["features"][1]["properties"]["hour"] = {6, 22};
       },
       "city.geojson: features[1] (\"window\"): properties has an unknown key \"hour\" (did you "
       "mean \"hours\"?)"},
      {[](json& g) { g["features"][2]["properties"]["name"] = "window"; },
       "city.geojson: features[2] (\"window\"): properties.name repeats the receptor name"},
      {[](json& g) {
         g["features"][1]["properties"]["hours"] = {22, 6, 1};
       },
       "city.geojson: features[1] (\"window\"): properties.hours"},
      {[](json& g) {
         auto& ring = g["features"][0]["geometry"]["coordinates"];
         ring.push_back(ring[0]);
       },
       "city.geojson: features[0] (\"facade\"): geometry has 2 rings (a polygon of the scene "
       "has one: no holes)"},
      {[](json& g) { g["features"][0]["properties"]["kind"] = "area"; },
       "city.geojson: has no feature of kind array"},
  };
  for (const auto& [change, expected] : cases) {
    json scene = good;
    change(scene);
    const std::string error = geoErrorOf(scene);
    EXPECT_NE(error.find(expected), std::string::npos)
        << "expected: " << expected << "\n     got: " << error;
  }
}

// A KML as Google Earth writes it: a roof relative to the ground, an observer at an absolute
// height, a road clamped to the ground.
std::string kmlScene(const std::string& observer_mode = "absolute") {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2" xmlns:gx="http://www.google.com/kml/ext/2.2">
<Document>
  <name>plant</name>
  <ExtendedData>
    <Data name="schema"><value>glarecam.hazard-geo/1</value></Data>
    <Data name="utc_offset_h"><value>1</value></Data>
    <Data name="ground_elevation_m"><value>410</value></Data>
  </ExtendedData>
  <Folder>
    <Placemark>
      <name>roof</name>
      <ExtendedData><Data name="kind"><value>array</value></Data></ExtendedData>
      <Polygon>
        <altitudeMode>relativeToGround</altitudeMode>
        <outerBoundaryIs><LinearRing><coordinates>
          8.54,47.37,10 8.5401,47.37,10 8.5401,47.37004,13 8.54,47.37004,13 8.54,47.37,10
        </coordinates></LinearRing></outerBoundaryIs>
      </Polygon>
    </Placemark>
    <Placemark>
      <name>window</name>
      <ExtendedData>
        <Data name="kind"><value>observer</value></Data>
        <Data name="hours"><value>[6, 22]</value></Data>
        <Data name="facing_azimuth_deg"><value>180</value></Data>
      </ExtendedData>
      <Point><)" +
         (observer_mode.starts_with("gx:") ? observer_mode : "altitudeMode>" + observer_mode) +
         R"(</)" + (observer_mode.starts_with("gx:") ? "gx:altitudeMode" : "altitudeMode") +
         R"(><coordinates>8.5402,47.3708,425.5</coordinates></Point>
    </Placemark>
    <Placemark>
      <name>road</name>
      <ExtendedData>
        <Data name="kind"><value>route</value></Data>
        <Data name="direction"><value>forward</value></Data>
      </ExtendedData>
      <LineString><coordinates>8.539,47.371 8.542,47.371</coordinates></LineString>
    </Placemark>
  </Folder>
</Document>
</kml>
)";
}

TEST(KmlScene, RelativeAndAbsoluteHeightsLandWherePROJSays) {
  const Result<Scene> scene = parseKmlScene(kmlScene(), "plant.kml", "/base");
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_TRUE(scene->geo);
  EXPECT_NEAR(scene->site.location.altitude_m, 420, 1e-9);  // 410 + 10 relative to the ground
  ASSERT_EQ(scene->arrays[0].vertices_m.size(), 4u);        // the closing vertex dropped
  const std::string pipeline = geoFramePipeline(8.54, 47.37, 420);
  EXPECT_EQ(scene->geo->pipeline(), pipeline);
  const std::vector<std::array<double, 3>> expected = cctSays(pipeline, {{8.54, 47.37, 420},
                                                                         {8.5401, 47.37004, 423},
                                                                         {8.5402, 47.3708, 425.5},
                                                                         {8.539, 47.371, 410}});
  if (expected.empty()) GTEST_SKIP() << "PROJ's cct is not installed (Debian proj-bin)";
  const auto near = [](Vec3 ours, std::array<double, 3> proj) {
    return std::max(
        {std::abs(ours.x - proj[0]), std::abs(ours.y - proj[1]), std::abs(ours.z - proj[2])});
  };
  EXPECT_LT(near(scene->arrays[0].vertices_m[0], expected[0]), 1e-3);
  EXPECT_LT(near(scene->arrays[0].vertices_m[2], expected[1]), 1e-3);
  const Observer& window = scene->observers[0];
  EXPECT_EQ(window.name, "window");
  EXPECT_LT(near(window.position_m, expected[2]), 1e-3);  // absolute: 425.5 m above sea
  EXPECT_EQ(window.from_h, 6);
  EXPECT_EQ(window.view_azimuths_deg, std::vector<double>{180});
  // The road is clamped to the ground (its first sample is its first point).
  EXPECT_LT(near(scene->observers[1].position_m, expected[3]), 1e-3);
  // relativeToGround places the observer 425.5 m above the ground instead.
  const Result<Scene> relative = parseKmlScene(kmlScene("relativeToGround"), "plant.kml", "/base");
  ASSERT_TRUE(relative) << relative.error().message;
  EXPECT_NEAR(relative->observers[0].position_m.z - window.position_m.z, 410, 1e-6);
}

TEST(KmlScene, RefusesWhatItCannotPlaceNamingThePlacemark) {
  const auto errorOf = [](const std::string& text) {
    const Result<Scene> read = parseKmlScene(text, "plant.kml", "/base");
    return read ? std::string() : read.error().message;
  };
  EXPECT_EQ(errorOf(kmlScene("gx:altitudeMode>relativeToSeaFloor")),
            "plant.kml: Placemark[1] (\"window\", line 21): Point has gx:altitudeMode "
            "relativeToSeaFloor, which the scene cannot place (use clampToGround, "
            "relativeToGround or absolute)");
  std::string no_kind = kmlScene();
  no_kind.replace(no_kind.find("<Data name=\"kind\"><value>route</value></Data>"),
                  std::string("<Data name=\"kind\"><value>route</value></Data>").size(), "");
  EXPECT_NE(errorOf(no_kind).find("plant.kml: Placemark[2] (\"road\", line 30): has no kind"),
            std::string::npos)
      << errorOf(no_kind);
  std::string typo = kmlScene();
  typo.replace(typo.find("facing_azimuth_deg"), 18, "facing_azimut_deg");
  EXPECT_EQ(errorOf(typo),
            "plant.kml: Placemark[1] (\"window\", line 21): properties has an unknown key "
            "\"facing_azimut_deg\" (did you mean \"facing_azimuth_deg\"?)");
  std::string swapped = kmlScene();
  swapped.replace(swapped.find("8.5402,47.3708"), 14, "47.3708,8.5402");
  EXPECT_NE(errorOf(swapped).find("Placemark[1] (\"window\", line 21): geometry vertex 0 "),
            std::string::npos)
      << errorOf(swapped);
  EXPECT_NE(errorOf(swapped).find("lon/lat swapped?"), std::string::npos);
  EXPECT_NE(errorOf("<kml><Document>").find("plant.kml: line"), std::string::npos);
}

TEST(GeoScene, ReadSceneDispatchesOnTheFilesKind) {
  const std::filesystem::path dir = ::testing::TempDir() + "/geo_scene_dispatch";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "city.geojson") << geoJsonOf(designedScene(), siteFrame()).dump();
  std::ofstream(dir / "plant.KML") << kmlScene();
  const Result<Scene> geojson = readScene(dir / "city.geojson");
  ASSERT_TRUE(geojson) << geojson.error().message;
  EXPECT_TRUE(geojson->geo);
  EXPECT_EQ(geojson->path, dir / "city.geojson");
  const Result<Scene> kml = readScene(dir / "plant.KML");
  ASSERT_TRUE(kml) << kml.error().message;
  EXPECT_TRUE(kml->geo);
  EXPECT_EQ(kml->path, dir / "plant.KML");
}

TEST(GeoScene, TheDocsGeoJsonExampleHasTheEnuExamplesReceptors) {
  // The same scene drawn on a map, its coordinates rounded to 1e-9°: a terrace level but for the
  // Earth's curvature keeps its north-aligned grid, and neither the rounded terrace nor the
  // rounded street gains a receptor.
  const std::filesystem::path examples =
      std::filesystem::path(GLARECAM_TEST_DATA_DIR) / ".." / ".." / "docs" / "examples";
  const Result<Scene> enu = readScene(examples / "hazard-scene-v2.json");
  const Result<Scene> geo = readScene(examples / "hazard-scene.geojson");
  ASSERT_TRUE(enu) << enu.error().message;
  ASSERT_TRUE(geo) << geo.error().message;
  ASSERT_EQ(geo->observers.size(), enu->observers.size());
  // The geographic frame's origin is the roof's first vertex, (-6, 0, 9) in the ENU example's.
  const Vec3 shift{-6, 0, 9};
  for (std::size_t o = 0; o < enu->observers.size(); ++o) {
    EXPECT_EQ(geo->observers[o].name, enu->observers[o].name);
    // Within 2 mm: the curvature (0.1 mm at 60 m) and the rounding to 1e-9° and 0.1 mm.
    EXPECT_LT(norm(geo->observers[o].position_m + shift - enu->observers[o].position_m), 2e-3)
        << enu->observers[o].name;
  }
  EXPECT_EQ(geo->obstructions.size(), enu->obstructions.size());
  EXPECT_TRUE(geo->warnings.empty()) << ::testing::PrintToString(geo->warnings);
}

}  // namespace
}  // namespace glarecam::hazard
