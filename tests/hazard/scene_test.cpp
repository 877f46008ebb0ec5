#include "hazard/scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "core/angles.h"
#include "hazard/candidate_pairs.h"
#include "hazard/hazard_calculation.h"
#include "hazard/obstruction.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

json goodScene() {
  return json::parse(R"({
    "schema": "glarecam.hazard-scene/1",
    "site": {"latitude_deg": 47.37, "longitude_deg": 8.54, "elevation_m": 410, "utc_offset_h": 1.0},
    "arrays": [{"name": "roof-north", "vertices_m": [[-6,0,9],[6,0,9],[6,5.2,6],[-6,5.2,6]],
                "profile": "profiles/glare-profile.json"}],
    "observers": [{"name": "window-3", "position_m": [0,30,12], "hours": [6, 22]},
                  {"name": "terrace", "position_m": [10,-20,3]}]
  })");
}

// The first line of the error a scene gets, or "" when it is accepted.
std::string errorOf(const json& scene) {
  const Result<Scene> read = parseScene(scene, "scene.json", "/base");
  return read ? "" : read.error().message;
}

TEST(HazardScene, ReadsTheMethodDocsExample) {
  const Result<Scene> scene = parseScene(goodScene(), "scene.json", "/base");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_DOUBLE_EQ(scene->site.location.latitude_deg, 47.37);
  EXPECT_DOUBLE_EQ(scene->site.utc_offset_h, 1.0);
  EXPECT_DOUBLE_EQ(scene->site.location.altitude_m, 410);
  // No pressure given: the standard atmosphere's at the elevation.
  EXPECT_NEAR(scene->site.location.pressure_hpa, sun::standardPressureHpa(410), 1e-9);
  ASSERT_EQ(scene->arrays.size(), 1u);
  const ArrayPolygon& roof = scene->arrays[0];
  // The roof rises from y = 5.2 (z 6) to y = 0 (z 9): it faces north and up. Newell's normal of
  // the counter-clockwise vertices: (0, 3, 5.2)/|.|.
  const double length = std::hypot(3.0, 5.2);
  EXPECT_NEAR(roof.normal.x, 0, 1e-12);
  EXPECT_NEAR(roof.normal.y, 3 / length, 1e-12);
  EXPECT_NEAR(roof.normal.z, 5.2 / length, 1e-12);
  EXPECT_NEAR(roof.area_m2, 12 * std::hypot(5.2, 3.0), 1e-9);
  // Uphill is toward y = 0, z = 9: south.
  EXPECT_LT(roof.up_slope.y, 0);
  EXPECT_GT(roof.up_slope.z, 0);
  EXPECT_NEAR(dot(roof.up_slope, roof.normal), 0, 1e-12);
  EXPECT_NEAR(dot(cross(roof.axis_u, roof.axis_w), roof.normal), 1, 1e-12);
  EXPECT_EQ(*roof.profile, std::filesystem::path("/base/profiles/glare-profile.json"));
  ASSERT_EQ(scene->observers.size(), 2u);
  EXPECT_EQ(scene->observers[0].from_h, 6);
  EXPECT_EQ(scene->observers[0].to_h, 22);
  EXPECT_EQ(scene->observers[1].from_h, 0);  // the whole day by default
  EXPECT_EQ(scene->observers[1].to_h, 24);
  // The terrace lies south of the north-facing roof and below it: it never sees the front.
  ASSERT_EQ(scene->warnings.size(), 1u);
  EXPECT_EQ(scene->warnings[0],
            "scene.json: observer \"terrace\" (observers[1]) is behind or on the plane of array "
            "\"roof-north\" (arrays[0]) and never sees its front, so that array adds no glare "
            "there (are the array's vertices listed the wrong way round?)");
}

TEST(HazardScene, WarnsForEveryObserverThatNeverSeesAnArraysFront) {
  json scene = goodScene();
  scene["observers"] = json::parse(R"([
    {"name": "window-3", "position_m": [0, 30, 12]},
    {"name": "inside", "position_m": [0, 2, 5]},
    {"name": "on-the-roof", "position_m": [0, 2.6, 7.5]},
    {"name": "street", "position_m": [20, 30, 1.6]}])");
  // A facade at y = 0 listed the wrong way round: its normal points south, into the building,
  // and, vertical, it never faces downward, so nothing else warns about it.
  scene["arrays"].push_back(
      {{"name", "facade"}, {"vertices_m", {{10, 0, 0}, {10, 0, 3}, {0, 0, 3}, {0, 0, 0}}}});
  const Result<Scene> read = parseScene(scene, "scene.json", "/base");
  ASSERT_TRUE(read) << read.error().message;
  std::vector<std::string> pairs;
  for (const std::string& warning : read->warnings) {
    const auto quoted = [&](std::size_t from) {
      const std::size_t start = warning.find('"', from) + 1;
      return warning.substr(start, warning.find('"', start) - start);
    };
    const std::string observer = quoted(0);
    pairs.push_back(observer + "/" + quoted(warning.find("array \"")));
  }
  EXPECT_EQ(pairs, (std::vector<std::string>{"inside/roof-north", "on-the-roof/roof-north",
                                             "window-3/facade", "inside/facade",
                                             "on-the-roof/facade", "street/facade"}));
  EXPECT_NE(read->warnings[0].find("(observers[1])"), std::string::npos) << read->warnings[0];
  EXPECT_NE(read->warnings[2].find("(arrays[1])"), std::string::npos) << read->warnings[2];
  // The facade is vertical: no "faces downward" warning, and the facing says where it looks.
  EXPECT_EQ(read->arrays[1].normal.y, -1);
  EXPECT_NEAR(*facingAzimuthDeg(read->arrays[1]), 180, 1e-9);
  EXPECT_NEAR(tiltDeg(read->arrays[1]), 90, 1e-9);
}

// A district: a row of 20 north-facing roofs 15 m apart, 40 windows south of them (behind
// every roof), one north of the first roofs (in front of them) and one behind, but 500 m away.
// Hundreds of pairs see a back: not a line each, but one counting them and one naming the roofs
// that every receptor near them sees from behind; the far one is never counted.
TEST(HazardScene, ADistrictsHiddenFrontsAreCountedNotListed) {
  json scene = goodScene();
  scene["arrays"] = json::array();
  for (int i = 0; i < 20; ++i) {
    const double x = 15.0 * i;
    scene["arrays"].push_back(
        {{"name", "roof-" + std::to_string(i)},
         {"vertices_m", {{x - 6, 0, 9}, {x + 6, 0, 9}, {x + 6, 5.2, 6}, {x - 6, 5.2, 6}}}});
  }
  scene["observers"] = json::array();
  for (int i = 0; i < 40; ++i)
    scene["observers"].push_back(
        {{"name", "south-" + std::to_string(i)}, {"position_m", {7.5 * i, -20, 3}}});
  scene["observers"].push_back({{"name", "north"}, {"position_m", {0, 30, 12}}});
  scene["observers"].push_back({{"name", "far"}, {"position_m", {0, -500, 3}}});
  const Result<Scene> read = parseScene(scene, "scene.json", "/base");
  ASSERT_TRUE(read) << read.error().message;
  // The pairs within 100 m that see a back, counted the slow way, and the roofs the window in
  // the north sees the front of.
  std::size_t hidden = 0, back_only = 0;
  for (const ArrayPolygon& array : read->arrays) {
    bool front = false, near = false;
    for (const Observer& observer : read->observers) {
      if (distanceToArrayM(array, observer.position_m) > kDefaultMaxDistanceM) continue;
      near = true;
      if (seesFront(array, observer.position_m))
        front = true;
      else
        ++hidden;
    }
    back_only += near && !front ? 1 : 0;
  }
  ASSERT_GT(hidden, 200u);
  ASSERT_GT(back_only, 5u);
  ASSERT_LT(back_only, 20u);
  ASSERT_EQ(read->warnings.size(), 2u);
  EXPECT_EQ(read->warnings[0],
            "scene.json: 40 of 42 receptors each see some array within 100 m only from behind "
            "or edge-on (" +
                std::to_string(hidden) +
                " receptor–array pairs, 20 arrays; in a district mostly windows and roads facing "
                "away from a roof), so those arrays add no glare there (others may); e.g. observer "
                "\"south-0\" (observers[0]) and array \"roof-0\" (arrays[0]); observer "
                "\"south-1\" (observers[1]) and array \"roof-0\" (arrays[0]); observer "
                "\"south-2\" (observers[2]) and array \"roof-0\" (arrays[0])");
  EXPECT_EQ(read->warnings[1].substr(0, read->warnings[1].find(':', 12)),
            "scene.json: " + std::to_string(back_only) +
                " arrays are seen only from behind by every receptor within 100 m");
  EXPECT_NE(read->warnings[1].find("and " + std::to_string(back_only - 5) +
                                   " more (are their "
                                   "vertices listed the wrong way round?)"),
            std::string::npos)
      << read->warnings[1];
  // The roofs near the northern window are seen from the front: never named.
  EXPECT_EQ(read->warnings[1].find("\"roof-0\""), std::string::npos) << read->warnings[1];
}

// Pairs farther apart than the distance the run looks within are not warned about.
TEST(HazardScene, AnArrayFarAwayIsNotWarnedAbout) {
  json scene = goodScene();
  scene["observers"][1]["position_m"] = {10, -150, 3};  // behind the roof, 150 m away
  const Result<Scene> read = parseScene(scene, "scene.json", "/base");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_TRUE(read->warnings.empty()) << read->warnings.front();
}

TEST(HazardScene, FacingAzimuthAndTiltOfTheFront) {
  const Result<Scene> scene = parseScene(goodScene(), "scene.json", "/base");
  ASSERT_TRUE(scene) << scene.error().message;
  // The roof slopes 30° down to the north (rise 3 m over 5.2 m): it faces north, tilted 30°.
  EXPECT_NEAR(*facingAzimuthDeg(scene->arrays[0]), 0, 1e-9);
  EXPECT_NEAR(tiltDeg(scene->arrays[0]), degrees(std::atan2(3, 5.2)), 1e-9);
  const ArrayPolygon west = testing::squareArray("west", {0, 0, 5}, {-1, 0, 0}, 2);
  EXPECT_NEAR(*facingAzimuthDeg(west), 270, 1e-9);
  const ArrayPolygon level = testing::squareArray("flat", {0, 0, 5}, {0, 0, 1}, 2);
  EXPECT_FALSE(facingAzimuthDeg(level));
  EXPECT_NEAR(tiltDeg(level), 0, 1e-9);
}

TEST(HazardScene, RefusesUnknownKeysAtEveryLevelSuggestingTheClosest) {
  const std::vector<std::pair<std::function<void(json&)>, std::string>> cases{
      {[](json& s) { s["arrays"][0]["profil"] = s["arrays"][0]["profile"]; },
       "scene.json: arrays[0] has an unknown key \"profil\" (did you mean \"profile\"?)"},
      {[](json& s) {
         s["observers"][1]["hour"] = {6, 22};
       },
       "scene.json: observers[1] has an unknown key \"hour\" (did you mean \"hours\"?)"},
      {[](json& s) { s["site"]["elevation"] = 410; },
       "scene.json: site has an unknown key \"elevation\" (did you mean \"elevation_m\"?)"},
      {[](json& s) { s["observer"] = s["observers"]; },
       "scene.json: the document has an unknown key \"observer\" (did you mean "
       "\"observers\"?)"},
      {[](json& s) { s["site"]["timezone"] = "Europe/Zurich"; },
       "scene.json: site has an unknown key \"timezone\" (known: latitude_deg, longitude_deg, "
       "elevation_m, utc_offset_h, pressure_hpa, temperature_c)"},
      // A key of a later version is no key of version 1: named with the version that has it.
      {[](json& s) { s["observers"][0]["facing_azimuth_deg"] = 180; },
       "scene.json: observers[0].facing_azimuth_deg is a key of glarecam.hazard-scene/2 (give "
       "\"schema\": \"glarecam.hazard-scene/2\")"},
  };
  for (const auto& [change, expected] : cases) {
    json scene = goodScene();
    change(scene);
    EXPECT_EQ(errorOf(scene), expected);
  }
}

TEST(HazardScene, NamesTheVertexThatIsOffThePlane) {
  // The example roof with one vertex at a time moved 0.5 m out of its plane: the message names
  // that vertex and its distance from the plane of the others. (The plane of all four leans
  // toward it and passes a quarter of that from every vertex, so that the first was named.)
  const double length = std::hypot(3.0, 5.2);
  const double normal[3] = {0, 3 / length, 5.2 / length};
  for (std::size_t moved = 0; moved < 4; ++moved) {
    json scene = goodScene();
    json& vertex = scene["arrays"][0]["vertices_m"][moved];
    for (std::size_t axis = 0; axis < 3; ++axis)
      vertex[axis] = vertex[axis].get<double>() + 0.5 * normal[axis];
    char expected[128];
    std::snprintf(expected, sizeof expected,
                  "scene.json: arrays[0].vertices_m is not planar (vertex %zu lies 0.500 m off "
                  "the plane of the others)",
                  moved);
    EXPECT_EQ(errorOf(scene), expected);
  }
  // A hexagon with its vertex 4 lifted: the plane through them all leans toward it.
  json hexagon = goodScene();
  hexagon["arrays"][0]["vertices_m"] = {{2, 0, 0},  {1, 1.7, 0},     {-1, 1.7, 0},
                                        {-2, 0, 0}, {-1, -1.7, 0.3}, {1, -1.7, 0}};
  EXPECT_NE(errorOf(hexagon).find("(vertex 4 lies 0.300 m off the plane of the others)"),
            std::string::npos)
      << errorOf(hexagon);
}

TEST(HazardScene, ABowTieCrossesItselfNamingTheEdges) {
  json scene = goodScene();
  // Symmetric: its two lobes cancel, so that it encloses no area by the signed sum.
  scene["arrays"][0]["vertices_m"] = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(errorOf(scene),
            "scene.json: arrays[0].vertices_m crosses itself (edges 0\u20131 and 2\u20133 cross)");
  // The same standing up (in the plane x = 0), and a quadrilateral whose last edge crosses its
  // second.
  scene["arrays"][0]["vertices_m"] = {{0, 0, 0}, {0, 1, 1}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_NE(errorOf(scene).find("crosses itself (edges 0\u20131 and 2\u20133 cross)"),
            std::string::npos);
  scene["arrays"][0]["vertices_m"] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {3, 1, 0}};
  EXPECT_NE(errorOf(scene).find("crosses itself"), std::string::npos) << errorOf(scene);
}

TEST(HazardScene, ALevelArrayFacesUpAndSlopesNorth) {
  const ArrayPolygon level = testing::squareArray("flat", {0, 0, 5}, {0, 0, 1}, 2);
  EXPECT_NEAR(level.normal.z, 1, 1e-12);
  EXPECT_NEAR(level.up_slope.y, 1, 1e-12);  // hazard.md step 4: north for a level array
}

TEST(HazardScene, WarnsWhenAnArrayFacesDownward) {
  json scene = goodScene();
  scene["arrays"][0]["vertices_m"] = {{-6, 5.2, 6}, {6, 5.2, 6}, {6, 0, 9}, {-6, 0, 9}};
  const Result<Scene> read = parseScene(scene, "scene.json", "/base");
  ASSERT_TRUE(read);
  // Then window-3 is behind it (warned about too).
  ASSERT_EQ(read->warnings.size(), 2u);
  EXPECT_NE(read->warnings[0].find("roof-north"), std::string::npos);
  EXPECT_NE(read->warnings[0].find("downward"), std::string::npos);
  EXPECT_NE(read->warnings[1].find("observer \"window-3\""), std::string::npos);
}

TEST(HazardScene, ContainsPlanePointsOfANonConvexPolygon) {
  // An L shape in the plane z = 0, facing up.
  const ArrayPolygon l_shape =
      *makeArrayPolygon("L", {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}},
                        "scene.json", "arrays[0].vertices_m");
  EXPECT_TRUE(containsPlanePoint(l_shape, {0.5, 0.5, 0}));
  EXPECT_TRUE(containsPlanePoint(l_shape, {0.5, 1.5, 0}));
  EXPECT_TRUE(containsPlanePoint(l_shape, {1.5, 0.5, 0}));
  EXPECT_FALSE(containsPlanePoint(l_shape, {1.5, 1.5, 0}));  // the notch
  EXPECT_FALSE(containsPlanePoint(l_shape, {-0.1, 0.5, 0}));
}

struct BadScene {
  const char* what;
  std::function<void(json&)> change;
  const char* expected;  // in the message
};

TEST(HazardScene, RefusesEachBadInputNamingTheField) {
  const std::vector<BadScene> cases{
      {"wrong schema", [](json& s) { s["schema"] = "glarecam.hazard-scene/3"; }, "schema"},
      {"no schema", [](json& s) { s.erase("schema"); }, "schema is missing"},
      {"latitude", [](json& s) { s["site"]["latitude_deg"] = 91; },
       "site.latitude_deg 91° is outside [-90, 90]"},
      {"longitude", [](json& s) { s["site"]["longitude_deg"] = -181; }, "site.longitude_deg"},
      {"text latitude", [](json& s) { s["site"]["latitude_deg"] = "47"; },
       "site.latitude_deg must be a number, not \"47\""},
      {"no offset", [](json& s) { s["site"].erase("utc_offset_h"); },
       "site.utc_offset_h is missing"},
      {"offset", [](json& s) { s["site"]["utc_offset_h"] = 15; }, "site.utc_offset_h"},
      {"no arrays", [](json& s) { s["arrays"] = json::array(); }, "arrays is empty"},
      {"arrays not a list", [](json& s) { s["arrays"] = 3; }, "arrays must be an array, not 3"},
      {"no observers", [](json& s) { s["observers"] = json::array(); }, "observers is empty"},
      {"two vertices",
       [](json& s) {
         s["arrays"][0]["vertices_m"] = {{0, 0, 0}, {1, 0, 0}};
       },
       "arrays[0].vertices_m has 2 vertices"},
      {"text coordinate", [](json& s) { s["arrays"][0]["vertices_m"][2][1] = "5.2"; },
       "arrays[0].vertices_m[2][1] must be a number, not \"5.2\""},
      {"far coordinate", [](json& s) { s["arrays"][0]["vertices_m"][1][0] = 2e6; },
       "arrays[0].vertices_m[1][0] 2e+06 m is outside [-1e+06, 1e+06]"},
      {"two coordinates",
       [](json& s) {
         s["arrays"][0]["vertices_m"][1] = {6, 0};
       },
       "arrays[0].vertices_m[1] is not [x, y, z]"},
      {"not planar",
       [](json& s) {
         s["arrays"][0]["vertices_m"][2] = {6, 5.2, 6.05};
       },
       "is not planar"},
      {"self-intersecting",
       [](json& s) {
         s["arrays"][0]["vertices_m"] = {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 1, 0}};
       },
       "crosses itself"},
      {"symmetric bow tie (no area)",
       [](json& s) {
         s["arrays"][0]["vertices_m"] = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
       },
       "crosses itself"},
      {"collinear",
       [](json& s) {
         s["arrays"][0]["vertices_m"] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
       },
       "is degenerate"},
      {"repeated vertex",
       [](json& s) {
         s["arrays"][0]["vertices_m"] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 0, 0}};
       },
       "repeats a vertex"},
      {"duplicate array", [](json& s) { s["arrays"].push_back(s["arrays"][0]); },
       "arrays[1].name repeats"},
      {"duplicate observer", [](json& s) { s["observers"][1]["name"] = "window-3"; },
       "observers[1].name repeats the observer name \"window-3\""},
      {"empty name", [](json& s) { s["observers"][0]["name"] = ""; }, "observers[0].name is empty"},
      {"hours backwards",
       [](json& s) {
         s["observers"][0]["hours"] = {22, 6};
       },
       "observers[0].hours is an empty window"},
      {"hours past midnight",
       [](json& s) {
         s["observers"][0]["hours"] = {6, 25};
       },
       "observers[0].hours[1]"},
      {"observer position",
       [](json& s) {
         s["observers"][0]["position_m"] = {0, "a", 1};
       },
       "observers[0].position_m[1] must be a number, not \"a\""},
      {"profile not text", [](json& s) { s["arrays"][0]["profile"] = 3; },
       "arrays[0].profile must be a string, not 3"},
      {"not an object", [](json& s) { s = json::array(); },
       "the document must be an object, not []"},
  };
  for (const BadScene& bad : cases) {
    json scene = goodScene();
    bad.change(scene);
    const std::string message = errorOf(scene);
    EXPECT_NE(message.find(bad.expected), std::string::npos)
        << bad.what << ": \"" << message << "\" lacks \"" << bad.expected << "\"";
    EXPECT_TRUE(message.starts_with("scene.json: ")) << bad.what << ": " << message;
  }
}

TEST(HazardScene, PlanarWithinOneCentimetre) {
  json scene = goodScene();
  scene["arrays"][0]["vertices_m"][2] = {6, 5.2, 6.009};  // 9 mm off: about 4 mm off the plane
  EXPECT_EQ(errorOf(scene), "");
}

TEST(HazardScene, ReadsAFileAndNamesAMissingOne) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "scene.json", goodScene().dump());
  const Result<Scene> scene = readScene(dir / "scene.json");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_EQ(*scene->arrays[0].profile, dir.path() / "profiles/glare-profile.json");
  const Result<Scene> missing = readScene(dir / "missing.json");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::kBadInput);
  EXPECT_NE(missing.error().message.find("missing.json"), std::string::npos);
  glarecam::testing::writeText(dir / "broken.json", "{\"schema\": ");
  const Result<Scene> broken = readScene(dir / "broken.json");
  ASSERT_FALSE(broken);
  EXPECT_NE(broken.error().message.find("broken.json"), std::string::npos);
}

}  // namespace
}  // namespace glarecam::hazard

namespace glarecam::hazard {
namespace {

json sceneV2() {
  json scene = goodScene();
  scene["schema"] = "glarecam.hazard-scene/2";
  scene["observers"][0]["facing_azimuth_deg"] = 180;
  scene["routes"] = json::parse(R"([{"name": "road-b", "points_m": [[60, -50, 1.1], [60, 0, 1.1],
      [90, 0, 1.1]], "spacing_m": 10, "direction": "forward", "field_of_view_deg": 50}])");
  scene["areas"] = json::parse(R"([{"name": "garden", "vertices_m": [[5, 35, 0], [15, 35, 0],
      [15, 45, 0], [5, 45, 0]], "eye_height_m": 1.6, "spacing_m": 2}])");
  scene["obstructions"] = json::parse(R"([
      {"name": "house-7", "footprint_m": [[-8, 15], [8, 15], [8, 20], [-8, 20]], "height_m": 9},
      {"name": "wall", "vertices_m": [[20, 0, 0], [20, 10, 0], [20, 10, 3], [20, 0, 3]]}])");
  return scene;
}

TEST(HazardSceneV2, ExpandsRoutesAndAreasIntoPoints) {
  const Result<Scene> scene = parseScene(sceneV2(), "scene.json", "/base");
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_EQ(scene->version, 2);
  ASSERT_EQ(scene->receptors.size(), 4u);  // two observers, a route, an area
  const Observer& window = scene->observers[0];
  ASSERT_EQ(window.view_azimuths_deg.size(), 1u);
  EXPECT_EQ(window.view_azimuths_deg[0], 180);
  EXPECT_EQ(window.field_of_view_deg, kWindowFieldOfViewDeg);  // the default: the half-space
  EXPECT_TRUE(scene->observers[1].view_azimuths_deg.empty());  // no facing: every direction

  // The route: 80 m long, every 10 m with both ends: 9 points, names by their station; the
  // first leg runs north (0°), the second east (90°), forward only.
  const Receptor& road = scene->receptors[2];
  EXPECT_EQ(road.kind, ReceptorKind::kRoute);
  ASSERT_EQ(road.count, 9u);
  const Observer& start = scene->observers[road.first];
  EXPECT_EQ(start.name, "road-b@0m");
  EXPECT_EQ(start.view_azimuths_deg, std::vector<double>{0});
  EXPECT_EQ(start.field_of_view_deg, 50);
  const Observer& corner = scene->observers[road.first + 5];
  EXPECT_EQ(corner.name, "road-b@50m");
  EXPECT_NEAR(corner.position_m.x, 60, 1e-12);
  EXPECT_NEAR(corner.position_m.y, 0, 1e-12);
  EXPECT_NEAR(corner.view_azimuths_deg[0], 90, 1e-9);  // at the corner: the leg leaving it
  const Observer& end = scene->observers[road.first + 8];
  EXPECT_EQ(end.name, "road-b@80m");
  EXPECT_NEAR(end.position_m.x, 90, 1e-12);
  EXPECT_EQ(end.receptor, 2u);

  // The area: 10 × 10 m at 2 m: the centres of a 5 × 5 grid of cells, 1.6 m above the ground.
  const Receptor& garden = scene->receptors[3];
  EXPECT_EQ(garden.kind, ReceptorKind::kArea);
  EXPECT_EQ(garden.count, 25u);
  for (std::size_t o = garden.first; o < garden.first + garden.count; ++o) {
    const Vec3 p = scene->observers[o].position_m;
    EXPECT_NEAR(p.z, 1.6, 1e-12);
    EXPECT_GE(p.x, 6 - 1e-9);
    EXPECT_LE(p.x, 14 + 1e-9);
  }
  EXPECT_EQ(scene->observers[garden.first].name, "garden[0]");

  ASSERT_EQ(scene->obstructions.size(), 2u);
  EXPECT_EQ(scene->obstructions[0].faces.size(), 6u);  // bottom, top, four walls
  EXPECT_EQ(scene->obstructions[1].faces.size(), 1u);
}

TEST(HazardSceneV2, ARouteOfExactlyTheMostPointsIsAccepted) {
  // 19 999 spacings of 0.5 m: 20 000 points with both ends, the most; one more is refused.
  json scene = sceneV2();
  scene["routes"][0]["points_m"] = {{0, 0, 1.1}, {9999.5, 0, 1.1}};
  scene["routes"][0]["spacing_m"] = 0.5;
  const Result<Scene> most = parseScene(scene, "scene.json", "/base");
  ASSERT_TRUE(most) << most.error().message;
  EXPECT_EQ(most->receptors[2].count, kMaxReceptorPoints);
  scene["routes"][0]["points_m"][1] = {10000, 0, 1.1};
  EXPECT_NE(errorOf(scene).find("samples 20001 points, more than 20000"), std::string::npos)
      << errorOf(scene);
}

TEST(HazardSceneV2, BothDirectionsAndTheDefaults) {
  json scene = sceneV2();
  scene["routes"][0].erase("direction");
  scene["routes"][0].erase("field_of_view_deg");
  const Result<Scene> read = parseScene(scene, "scene.json", "/base");
  ASSERT_TRUE(read) << read.error().message;
  const Observer& start = read->observers[read->receptors[2].first];
  EXPECT_EQ(start.view_azimuths_deg, (std::vector<double>{0, 180}));
  EXPECT_EQ(start.field_of_view_deg, kDriverFieldOfViewDeg);
}

TEST(HazardSceneV2, AVersion1SceneReadsAsBeforeAndRefusesTheNewKeys) {
  const Result<Scene> v1 = parseScene(goodScene(), "scene.json", "/base");
  ASSERT_TRUE(v1);
  EXPECT_EQ(v1->version, 1);
  EXPECT_EQ(v1->receptors.size(), 2u);
  json scene = goodScene();
  scene["routes"] = json::array();
  EXPECT_EQ(errorOf(scene),
            "scene.json: routes is a key of glarecam.hazard-scene/2 (give "
            "\"schema\": \"glarecam.hazard-scene/2\")");
  scene = goodScene();
  scene["observers"][0]["facing_azimuth_deg"] = 180;
  EXPECT_NE(
      errorOf(scene).find("observers[0].facing_azimuth_deg is a key of glarecam.hazard-scene/2"),
      std::string::npos)
      << errorOf(scene);
}

TEST(HazardSceneV2, RefusesEachBadInputNamingTheField) {
  const std::vector<BadScene> cases{
      {"route typo", [](json& s) { s["routes"][0]["spacing"] = 5; },
       "routes[0] has an unknown key \"spacing\" (did you mean \"spacing_m\"?)"},
      {"one point",
       [](json& s) {
         s["routes"][0]["points_m"] = {{0, 0, 1}};
       },
       "routes[0].points_m has fewer than 2 points"},
      {"vertical leg",
       [](json& s) {
         s["routes"][0]["points_m"][1] = {60, -50, 5};
       },
       "routes[0].points_m[1] is straight above or below"},
      {"direction", [](json& s) { s["routes"][0]["direction"] = "north"; }, "routes[0].direction"},
      {"field of view", [](json& s) { s["routes"][0]["field_of_view_deg"] = 0; },
       "routes[0].field_of_view_deg is 0°"},
      {"too fine", [](json& s) { s["routes"][0]["spacing_m"] = 0.001; },
       "routes[0].spacing_m samples"},
      {"repeated point",
       [](json& s) {
         s["routes"][0]["points_m"][1] = {60, -50, 1.1};
       },
       "routes[0].points_m[1] repeats the point before it"},
      {"fov without facing", [](json& s) { s["observers"][1]["field_of_view_deg"] = 30; },
       "observers[1].field_of_view_deg needs facing_azimuth_deg"},
      {"facing", [](json& s) { s["observers"][0]["facing_azimuth_deg"] = 400; },
       "observers[0].facing_azimuth_deg"},
      {"same name", [](json& s) { s["areas"][0]["name"] = "road-b"; },
       "areas[0].name repeats the receptor name \"road-b\""},
      {"area crossing",
       [](json& s) {
         s["areas"][0]["vertices_m"][1] = {5, 45, 0};
       },
       "areas[0].vertices_m"},
      {"eye height", [](json& s) { s["areas"][0]["eye_height_m"] = -1; }, "areas[0].eye_height_m"},
      {"both shapes",
       [](json& s) {
         s["obstructions"][0]["vertices_m"] = {{0, 0, 0}};
       },
       "obstructions[0] has both footprint_m and vertices_m"},
      {"no shape", [](json& s) { s["obstructions"][1].erase("vertices_m"); },
       "obstructions[1] has neither footprint_m nor vertices_m"},
      {"no height", [](json& s) { s["obstructions"][0].erase("height_m"); },
       "obstructions[0].height_m is missing"},
      {"height below base", [](json& s) { s["obstructions"][0]["base_m"] = 10; },
       "obstructions[0]: height_m 9"},
      {"footprint point",
       [](json& s) {
         s["obstructions"][0]["footprint_m"][0] = {1, 2, 3};
       },
       "obstructions[0].footprint_m[0] is not [x, y]"},
      {"height on a polygon", [](json& s) { s["obstructions"][1]["height_m"] = 3; },
       "base_m and height_m belong to a footprint_m"},
      {"no receptor",
       [](json& s) {
         s.erase("observers");
         s.erase("routes");
         s.erase("areas");
       },
       "has no observer, route or area"},
  };
  for (const BadScene& bad : cases) {
    json scene = sceneV2();
    bad.change(scene);
    const std::string message = errorOf(scene);
    EXPECT_NE(message.find(bad.expected), std::string::npos)
        << bad.what << ": \"" << message << "\" lacks \"" << bad.expected << "\"";
    EXPECT_TRUE(message.starts_with("scene.json: ")) << bad.what << ": " << message;
  }
}

}  // namespace
}  // namespace glarecam::hazard
