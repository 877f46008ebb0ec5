// hazard.geojson of an ordinary `glarecam hazard` run (hazard/hazard_geojson.h): a valid
// FeatureCollection with every receptor point and every array, the numbers of hazard.json, and
// positions that go back to the scene's local metres through the frame it names.
#include "hazard/hazard_geojson.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "hazard/geo_frame.h"
#include "hazard/hazard_report.h"
#include "hazard/hazard_run.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

// The method docs' roof and window (which glares), a terrace behind the roof, a route past it.
json metresScene() {
  return json::parse(R"({
    "schema": "glarecam.hazard-scene/2",
    "site": {"latitude_deg": 47.37, "longitude_deg": 8.54, "elevation_m": 410, "utc_offset_h": 1.0},
    "arrays": [{"name": "roof-north", "vertices_m": [[-6,0,9],[6,0,9],[6,5.2,6],[-6,5.2,6]]},
               {"name": "shed", "vertices_m": [[20,10,3],[24,10,3],[24,14,3],[20,14,3]]}],
    "observers": [{"name": "window-3", "position_m": [0,30,12]},
                  {"name": "terrace", "position_m": [10,-20,3]}],
    "routes": [{"name": "road", "points_m": [[-30,40,1.1],[30,40,1.1]], "spacing_m": 20}]
  })");
}

class HazardGeoJson : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "profile.json") << testing::constantProfileJson(4, 8).dump();
  }

  // Runs the scene (written as `file`) and reads back hazard.json and hazard.geojson.
  void run(const json& scene, const std::string& file) {
    std::ofstream(dir_ / file) << scene.dump(1);
    HazardRunOptions options;
    options.scene = dir_ / file;
    options.profile = dir_ / "profile.json";
    options.out = dir_ / "out";
    options.hazard.year = 2027;
    // Ten-minute steps: the year in a fraction of a second; the map's layout does not depend on
    // the step.
    options.hazard.step_s = 600;
    options.hazard.max_distance_m = kDefaultMaxDistanceM;
    options.hazard.sun = SunBrightness{};  // the reference sun: the constant profile has no ladder
    options.show_progress = false;
    const Result<HazardRunSummary> summary = runHazard(options);
    ASSERT_TRUE(summary) << summary.error().message;
    hazard_ = json::parse(glarecam::testing::readText(dir_ / "out" / kHazardJson));
    geojson_ = json::parse(glarecam::testing::readText(dir_ / "out" / kHazardGeoJson));
    const Result<Scene> read = readScene(dir_ / file);
    ASSERT_TRUE(read) << read.error().message;
    scene_ = *read;
  }

  // The checks every scene passes, geographic or in metres.
  void checkMap() {
    ASSERT_EQ(geojson_["type"], "FeatureCollection");
    const json& member = geojson_["glarecam"];
    EXPECT_EQ(member["schema"], kHazardGeoJsonSchema);
    EXPECT_EQ(member["results"], kHazardJson);
    EXPECT_EQ(member["year"], 2027);
    EXPECT_EQ(member["max_distance_m"], kDefaultMaxDistanceM);
    // hazard.json records the same frame and distance.
    EXPECT_EQ(hazard_["inputs"]["frame"], member["frame"]);
    EXPECT_EQ(hazard_["inputs"]["max_distance_m"], kDefaultMaxDistanceM);
    const json& frame = member["frame"];
    const Result<GeoFrame> geo =
        GeoFrame::make(frame["longitude_deg"].get<double>(), frame["latitude_deg"].get<double>(),
                       frame["height_m"].get<double>());
    ASSERT_TRUE(geo) << geo.error().message;
    EXPECT_EQ(frame["pipeline"], geo->pipeline());

    std::size_t points = 0, polygons = 0;
    bool a_point_glares = false;
    for (const json& feature : geojson_["features"]) {
      ASSERT_EQ(feature["type"], "Feature");
      const json& geometry = feature["geometry"];
      const json& properties = feature["properties"];
      if (geometry["type"] == "Polygon") {
        // RFC 7946: one closed ring of [lon, lat, height], its first position repeated last.
        const ArrayPolygon& array = scene_.arrays.at(polygons++);
        EXPECT_EQ(properties["kind"], "array");
        EXPECT_EQ(properties["name"], array.name);
        const json& ring = geometry["coordinates"].at(0);
        ASSERT_EQ(ring.size(), array.vertices_m.size() + 1);
        EXPECT_EQ(ring.front(), ring.back());
        for (std::size_t v = 0; v < array.vertices_m.size(); ++v) {
          const Vec3 back = geo->toEnu(ring[v][0], ring[v][1], ring[v][2]);
          EXPECT_LT(norm(back - array.vertices_m[v]), 1e-3) << array.name << " vertex " << v;
        }
        for (const std::string model : {"ellipse", "circle"})
          EXPECT_EQ(properties[model + "_receptor_points"], properties[model + "_glares"].size());
        continue;
      }
      ASSERT_EQ(geometry["type"], "Point");
      const std::size_t o = points++;
      ASSERT_LT(o, scene_.observers.size());
      const Observer& observer = scene_.observers[o];
      const json& entry = hazard_["observers"][o];
      EXPECT_EQ(properties["name"], observer.name);
      EXPECT_EQ(properties["name"], entry["name"]);
      // The coordinates go back to the ENU position within a millimetre.
      const json& c = geometry["coordinates"];
      ASSERT_EQ(c.size(), 3u);
      const Vec3 back = geo->toEnu(c[0], c[1], c[2]);
      EXPECT_LT(norm(back - observer.position_m), 1e-3) << observer.name;
      for (const std::string model : {"ellipse", "circle"}) {
        // Flat keys, MODEL_FIELD (a GIS column each).
        json mine;
        for (const auto& [key, value] : properties.items())
          if (key.starts_with(model + "_")) mine[key.substr(model.size() + 1)] = value;
        const json& theirs = entry["models"][model];
        EXPECT_EQ(mine["minutes_per_year"], theirs["minutes_per_year"]) << observer.name;
        EXPECT_EQ(mine["days_with_glare"], theirs["days_with_glare"]) << observer.name;
        EXPECT_EQ(mine["max_minutes_per_day"], theirs["max_minutes_per_day"]) << observer.name;
        EXPECT_EQ(mine["lai"], theirs["verdicts"]["lai"]["verdict"]) << observer.name;
        if (mine["minutes_per_year"].get<double>() > 0) {
          a_point_glares = true;
          // The worst day is the day of hazard.json's largest minutes.
          const std::vector<double> days = theirs["minutes_per_day"].get<std::vector<double>>();
          const auto worst = std::max_element(days.begin(), days.end()) - days.begin();
          EXPECT_EQ(mine["worst_day"], isoDate(2027, static_cast<int>(worst)));
          EXPECT_FALSE(mine["arrays"].empty());
        } else {
          EXPECT_TRUE(mine["worst_day"].is_null());
          EXPECT_EQ(mine["ocular_class"], "none");
        }
      }
    }
    EXPECT_EQ(points, scene_.observers.size());
    EXPECT_EQ(polygons, scene_.arrays.size());
    EXPECT_TRUE(a_point_glares) << "the window should see the roof's glare";
  }

  glarecam::testing::TempDir dir_;
  json hazard_, geojson_;
  Scene scene_;
};

TEST_F(HazardGeoJson, AnOrdinaryRunMapsEveryPointAndArrayInTheSitesFrame) {
  run(metresScene(), "scene.json");
  checkMap();
  // A scene in metres: the frame at the site.
  const json& frame = geojson_["glarecam"]["frame"];
  EXPECT_EQ(frame["origin"], "site");
  EXPECT_DOUBLE_EQ(frame["longitude_deg"].get<double>(), 8.54);
  EXPECT_DOUBLE_EQ(frame["latitude_deg"].get<double>(), 47.37);
  // window-3 glares: its minutes are hazard.json's (checked above), and the roof names it.
  const json& roof = geojson_["features"][0]["properties"];
  EXPECT_EQ(roof["name"], "roof-north");
  EXPECT_NE(std::find(roof["ellipse_glares"].begin(), roof["ellipse_glares"].end(), "window-3"),
            roof["ellipse_glares"].end());
  EXPECT_EQ(hazard_["observers"][0]["name"], "window-3");
  EXPECT_GT(hazard_["observers"][0]["models"]["ellipse"]["minutes_per_year"].get<double>(), 0);
}

TEST_F(HazardGeoJson, AGeographicSceneMapsThroughItsOwnFrame) {
  // The same scene drawn on a map, in a frame somewhere else (so that the site's frame would
  // not do): every position through a frame at the roof's first vertex.
  const Result<GeoFrame> frame = GeoFrame::make(7.45, 46.95, 540 - 9);
  ASSERT_TRUE(frame) << frame.error().message;
  const json metres = metresScene();
  const auto position = [&](const json& p) {
    const LonLatH g =
        frame->toLonLatH({p[0].get<double>(), p[1].get<double>(), p[2].get<double>()});
    return json::array({g[0], g[1], g[2]});
  };
  json features = json::array();
  for (const json& array : metres["arrays"]) {
    json ring = json::array();
    for (const json& v : array["vertices_m"]) ring.push_back(position(v));
    ring.push_back(ring.front());
    features.push_back({{"type", "Feature"},
                        {"properties", {{"kind", "array"}, {"name", array["name"]}}},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}});
  }
  for (const json& observer : metres["observers"])
    features.push_back(
        {{"type", "Feature"},
         {"properties", {{"kind", "observer"}, {"name", observer["name"]}}},
         {"geometry", {{"type", "Point"}, {"coordinates", position(observer["position_m"])}}}});
  const json scene = {
      {"type", "FeatureCollection"},
      {"glarecam",
       {{"schema", "glarecam.hazard-geo/1"}, {"utc_offset_h", 1.0}, {"vertical_reference", "sea"}}},
      {"features", features}};
  run(scene, "scene.geojson");
  ASSERT_TRUE(scene_.geo);
  checkMap();
  const json& member = geojson_["glarecam"]["frame"];
  EXPECT_EQ(member["origin"], "first array's first vertex");
  EXPECT_EQ(member["pipeline"], scene_.geo->pipeline());
}

}  // namespace
}  // namespace glarecam::hazard
