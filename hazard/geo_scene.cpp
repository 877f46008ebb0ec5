#include "hazard/geo_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>

#include "core/json.h"
#include "core/spelling.h"

namespace glarecam::hazard {
namespace {

const std::vector<std::string> kGeoKinds{"array", "observer", "route", "area", "obstruction"};

// The v2 scene's list each kind goes to, and the key of its geometry there.
struct GeoKindTarget {
  const char* section;
  const char* geometry_key;
  const char* geometry;  // the GeoJSON geometry type the kind takes
};

GeoKindTarget geoKindTarget(const std::string& kind) {
  if (kind == "array") return {"arrays", "vertices_m", "Polygon"};
  if (kind == "observer") return {"observers", "position_m", "Point"};
  if (kind == "route") return {"routes", "points_m", "LineString"};
  if (kind == "area") return {"areas", "vertices_m", "Polygon"};
  return {"obstructions", "vertices_m", "Polygon"};
}

// The keys each kind's properties may have (the v2 scene's, but its geometry).
Status onlyGeoKindKeys(const JsonReader& properties, const std::string& kind) {
  if (kind == "array") return properties.onlyKeys({"kind", "name", "profile"});
  if (kind == "observer")
    return properties.onlyKeys(
        {"kind", "name", "hours", "facing_azimuth_deg", "field_of_view_deg"});
  if (kind == "route")
    return properties.onlyKeys(
        {"kind", "name", "hours", "direction", "spacing_m", "field_of_view_deg"});
  if (kind == "area")
    return properties.onlyKeys({"kind", "name", "hours", "eye_height_m", "spacing_m"});
  return properties.onlyKeys({"kind", "name", "base_m", "height_m"});
}

// How a feature is named: where it is in the file, and the list and index it went to in the v2
// document, so that parseScene's messages can be told in the file's terms.
struct GeoFeatureName {
  std::string where, locator;
};

// A v2 field as the geographic file spells it: the geometry, or a property.
std::string geoFieldName(const std::string& field, const char* geometry_key) {
  if (field.empty()) return "";
  const std::string key = field.substr(1);
  if (key == geometry_key || key == "footprint_m" ||
      key.starts_with(std::string(geometry_key) + "["))
    return " geometry";
  return " properties." + key;
}

// parseScene's message or warning in the file's terms: "FILE: arrays[2].vertices_m PROBLEM"
// becomes "FILE: features[7] ("roof"): geometry PROBLEM"; a reference further on ("(observers[1])"
// in a warning) becomes the feature's locator.
std::string inGeoTerms(const std::string& message, const std::string& file,
                       const std::map<std::string, std::vector<GeoFeatureName>>& names) {
  static const std::regex kReference(
      R"((arrays|observers|routes|areas|obstructions)\[(\d+)\]((\.[a-z_]+(\[\d+\])*)?))");
  std::string out;
  auto begin = message.cbegin();
  for (std::sregex_iterator it(message.begin(), message.end(), kReference), end; it != end; ++it) {
    const std::smatch& match = *it;
    out.append(begin, match[0].first);
    begin = match[0].second;
    const auto section = names.find(match[1].str());
    const std::size_t index = std::stoul(match[2].str());
    if (section == names.end() || index >= section->second.size()) {
      out += match[0].str();
      continue;
    }
    const GeoFeatureName& name = section->second[index];
    const bool head = static_cast<std::size_t>(match.position(0)) == file.size() + 2;
    const std::string section_name = match[1].str();
    const std::string target = section_name == "observers" ? "position_m"
                               : section_name == "routes"  ? "points_m"
                                                           : "vertices_m";
    const std::string field = geoFieldName(match[3].str(), target.c_str());
    out += head ? name.where + ":" + (field.empty() ? "" : field) : name.locator + field;
  }
  out.append(begin, message.cend());
  return out;
}

}  // namespace

Result<Scene> sceneFromGeoFeatures(const std::vector<GeoFeature>& features,
                                   const GeoSceneSettings& settings, const std::string& file,
                                   const std::filesystem::path& base) {
  // What each feature is, checked before anything is converted.
  std::vector<std::string> kinds;
  for (const GeoFeature& feature : features) {
    const JsonReader properties(feature.properties, file, feature.where + ": properties");
    GLARECAM_CHECK(properties.object());
    std::string kind;
    GLARECAM_ASSIGN(kind, properties.text("kind"));
    if (std::ranges::find(kGeoKinds, kind) == kGeoKinds.end()) {
      const std::optional<std::string> closest = closestSpelling(kind, kGeoKinds);
      return properties.fail(
          "kind", fmt::format("\"{}\" is not a kind ({}known: array, observer, route, area, "
                              "obstruction)",
                              kind, closest ? "did you mean \"" + *closest + "\"?; " : ""));
    }
    std::string name;
    GLARECAM_ASSIGN(name, properties.text("name"));
    GLARECAM_CHECK(onlyGeoKindKeys(properties, kind));
    const GeoKindTarget target = geoKindTarget(kind);
    if (feature.geometry != target.geometry) {
      return badInput(fmt::format("{}: {}: geometry is a {}; a feature of kind {} is a {}", file,
                                  feature.where, feature.geometry, kind, target.geometry));
    }
    const bool footprint = kind == "obstruction" && feature.properties.contains("height_m");
    if (kind == "obstruction" && !footprint && feature.properties.contains("base_m")) {
      return badInput(fmt::format(
          "{}: {}: properties.base_m needs height_m (an obstruction with heights is its "
          "footprint extruded from base_m to height_m; without them it is the polygon as drawn)",
          file, feature.where));
    }
    if (!footprint) {
      for (std::size_t v = 0; v < feature.positions.size(); ++v) {
        if (!std::isfinite(feature.positions[v][2])) {
          return badInput(
              fmt::format("{}: {}: geometry vertex {} has no height (give [lon, lat, "
                          "height]; only an obstruction's footprint with height_m "
                          "goes without)",
                          file, feature.where, v));
        }
      }
    }
    kinds.push_back(kind);
  }
  const auto first_array = std::ranges::find(kinds, "array");
  if (first_array == kinds.end())
    return badInput(file +
                    ": has no feature of kind array (the scene needs one; its first "
                    "vertex is the site)");
  const GeoFeature& site_feature = features[static_cast<std::size_t>(first_array - kinds.begin())];
  const LonLatH origin = site_feature.positions.at(0);
  Result<GeoFrame> frame = GeoFrame::make(origin[0], origin[1], origin[2]);
  if (!frame) return badInput(file + ": " + site_feature.where + ": " + frame.error().message);

  nlohmann::json document{{"schema", kSceneSchema},
                          {"site",
                           {{"latitude_deg", origin[1]},
                            {"longitude_deg", origin[0]},
                            {"elevation_m", origin[2]},
                            {"utc_offset_h", settings.utc_offset_h}}}};
  if (settings.pressure_hpa) document["site"]["pressure_hpa"] = *settings.pressure_hpa;
  if (settings.temperature_c) document["site"]["temperature_c"] = *settings.temperature_c;
  std::map<std::string, std::vector<GeoFeatureName>> names;
  for (std::size_t f = 0; f < features.size(); ++f) {
    const GeoFeature& feature = features[f];
    const std::string& kind = kinds[f];
    const GeoKindTarget target = geoKindTarget(kind);
    const bool footprint = kind == "obstruction" && feature.properties.contains("height_m");
    // A footprint's vertices at its base; every other vertex where the file puts it.
    double base_m = 0, top_m = 0;
    std::vector<LonLatH> positions = feature.positions;
    if (footprint) {
      const JsonReader properties(feature.properties, file, feature.where + ": properties");
      std::optional<double> base;
      GLARECAM_ASSIGN(
          base, properties.optionalNumberIn("base_m", -kMaxCoordinateM, kMaxCoordinateM, " m"));
      double height = 0;
      GLARECAM_ASSIGN(height,
                      properties.numberIn("height_m", -kMaxCoordinateM, kMaxCoordinateM, " m"));
      if (!base && !feature.ground_m) {
        return properties.fail("base_m",
                               "is missing (heights are above sea level and the "
                               "scene gives no ground_elevation_m to default it to)");
      }
      base_m = base ? feature.heights_from_m + *base : *feature.ground_m;
      top_m = feature.heights_from_m + height;
      for (LonLatH& position : positions) position[2] = base_m;
    }
    const std::vector<Vec3> points = frame->toEnu(positions);
    for (std::size_t v = 0; v < points.size(); ++v) {
      const double distance_m = std::hypot(points[v].x, points[v].y);
      if (!(distance_m <= kMaxGeoDistanceM)) {
        return badInput(fmt::format(
            "{}: {}: geometry vertex {} ({}, {}) lies {:.0f} km from the site (the first "
            "array's first vertex), farther than {:.0f} km: lon/lat swapped?",
            file, feature.where, v, positions[v][0], positions[v][1], distance_m / 1000,
            kMaxGeoDistanceM / 1000));
      }
    }
    nlohmann::json entry = feature.properties;
    entry.erase("kind");
    const auto xyz = [](Vec3 p) { return nlohmann::json::array({p.x, p.y, p.z}); };
    if (footprint) {
      // The footprint in the frame's x, y; its base and top at the footprint's mean height in
      // the frame (the vertices' frame heights differ by the Earth's curvature, 8 cm at 1 km).
      nlohmann::json footprint_m = nlohmann::json::array();
      double mean_z = 0;
      for (const Vec3& p : points) {
        footprint_m.push_back({p.x, p.y});
        mean_z += p.z / static_cast<double>(points.size());
      }
      entry["footprint_m"] = std::move(footprint_m);
      entry["base_m"] = mean_z;
      entry["height_m"] = mean_z + (top_m - base_m);
    } else if (kind == "observer") {
      entry[target.geometry_key] = xyz(points.at(0));
    } else {
      nlohmann::json list = nlohmann::json::array();
      for (const Vec3& p : points) list.push_back(xyz(p));
      entry[target.geometry_key] = std::move(list);
    }
    document[target.section].push_back(std::move(entry));
    names[target.section].push_back({feature.where, feature.locator});
  }

  Result<Scene> scene = parseScene(document, file, base);
  if (!scene) {
    Error error = scene.error();
    error.message = inGeoTerms(error.message, file, names);
    return std::unexpected(std::move(error));
  }
  for (std::string& warning : scene->warnings) warning = inGeoTerms(warning, file, names);
  scene->geo = std::move(*frame);
  return scene;
}

bool isGeoJson(const nlohmann::json& document) {
  return document.is_object() && document.contains("type") && document["type"].is_string() &&
         document["type"].get<std::string>() == "FeatureCollection";
}

namespace {

// GeoJSON's position: [lon, lat] or [lon, lat, height], the height relative to `heights_from_m`.
Result<LonLatH> geoJsonPosition(const JsonReader& json, double heights_from_m) {
  GLARECAM_CHECK(json.array());
  if (json.size() != 2 && json.size() != 3)
    return json.fail("is not [lon, lat, height] (" + std::to_string(json.size()) + " numbers)");
  LonLatH position{0, 0, std::numeric_limits<double>::quiet_NaN()};
  for (std::size_t k = 0; k < json.size(); ++k)
    GLARECAM_ASSIGN(position[k], json.element(k).number());
  const auto swapped = [&](const char* what, double value, double limit) {
    return json.fail(
        fmt::format("has {} {} outside [{}, {}] (lon/lat swapped? GeoJSON gives "
                    "[lon, lat, height])",
                    what, value, -limit, limit));
  };
  if (std::abs(position[0]) > 180) return swapped("longitude", position[0], 180);
  if (std::abs(position[1]) > 90) return swapped("latitude", position[1], 90);
  if (json.size() == 3) {
    if (std::abs(position[2]) > kMaxCoordinateM)
      return json.fail(fmt::format("has height {} m, beyond ±{} m", position[2], kMaxCoordinateM));
    position[2] += heights_from_m;
  }
  return position;
}

Result<std::vector<LonLatH>> geoJsonPositions(const JsonReader& list, double heights_from_m) {
  GLARECAM_CHECK(list.array());
  std::vector<LonLatH> positions;
  for (std::size_t i = 0; i < list.size(); ++i) {
    LonLatH position{};
    GLARECAM_ASSIGN(position, geoJsonPosition(list.element(i), heights_from_m));
    positions.push_back(position);
  }
  return positions;
}

}  // namespace

Result<Scene> parseGeoJsonScene(const nlohmann::json& document, const std::string& file,
                                const std::filesystem::path& base) {
  const JsonReader root(document, file);
  GLARECAM_CHECK(root.object());
  std::string type;
  GLARECAM_ASSIGN(type, root.text("type"));
  if (type != "FeatureCollection")
    return root.fail("type", "is \"" + type + "\", not \"FeatureCollection\"");
  GLARECAM_CHECK(root.onlyKeys({"type", "features", "glarecam", "bbox", "name", "crs"}));
  if (root.has("crs")) {
    // RFC 7946 has no crs; QGIS writes OGC's CRS84 (WGS84, lon/lat), the only one meant here.
    const nlohmann::json& crs = document["crs"];
    const std::string text = crs.dump();
    if (text.find("CRS84") == std::string::npos)
      return root.fail("crs", "is " + jsonSnippet(crs) +
                                  ": coordinates must be WGS84 longitude, latitude (RFC 7946, "
                                  "OGC CRS84); reproject the layer");
  }
  if (!root.has("glarecam")) {
    return root.fail(std::string("has no \"glarecam\" member (a geographic scene needs "
                                 "{\"schema\": \"") +
                     kGeoSceneSchema +
                     "\", \"utc_offset_h\", \"vertical_reference\", \"ground_elevation_m\"})");
  }
  JsonReader header;
  GLARECAM_ASSIGN(header, root.objectMember("glarecam"));
  GLARECAM_CHECK(header.onlyKeys({"schema", "utc_offset_h", "vertical_reference",
                                  "ground_elevation_m", "pressure_hpa", "temperature_c"}));
  GLARECAM_CHECK(header.schema(kGeoSceneSchema, "a geographic hazard scene"));
  GeoSceneSettings settings;
  GLARECAM_ASSIGN(settings.utc_offset_h,
                  header.numberIn("utc_offset_h", kMinUtcOffsetH, kMaxUtcOffsetH, " h"));
  GLARECAM_ASSIGN(settings.pressure_hpa, header.optionalNumberIn("pressure_hpa", 0, 5000, " hPa"));
  GLARECAM_ASSIGN(settings.temperature_c, header.optionalNumberIn("temperature_c", -90, 60, " °C"));
  if (!header.has("vertical_reference")) {
    return header.fail("vertical_reference",
                       "is missing (\"ground\": heights are metres above the ground at "
                       "ground_elevation_m; \"sea\": metres above sea level)");
  }
  std::string reference;
  GLARECAM_ASSIGN(reference, header.word("vertical_reference", {"ground", "sea"}));
  std::optional<double> ground_m;
  GLARECAM_ASSIGN(ground_m, header.optionalNumberIn("ground_elevation_m", -1000, 10000, " m"));
  if (reference == "ground" && !ground_m) {
    return header.fail("ground_elevation_m",
                       "is missing (vertical_reference \"ground\" counts heights from it)");
  }
  const double heights_from_m = reference == "ground" ? *ground_m : 0;

  JsonReader list;
  GLARECAM_ASSIGN(list, root.arrayMember("features"));
  std::vector<GeoFeature> features;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader json = list.element(i);
    GLARECAM_CHECK(json.object());
    GeoFeature feature;
    feature.locator = "features[" + std::to_string(i) + "]";
    feature.where = feature.locator;
    const nlohmann::json& value = json.value();
    if (value.contains("properties") && value["properties"].is_object() &&
        value["properties"].contains("name") && value["properties"]["name"].is_string()) {
      feature.where += " (" + jsonSnippet(value["properties"]["name"]) + ")";
    }
    const auto fail = [&](const std::string& problem) {
      return badInput(file + ": " + feature.where + ": " + problem);
    };
    GLARECAM_CHECK(JsonReader(value, file, feature.where)
                       .onlyKeys({"type", "geometry", "properties", "id", "bbox"}));
    if (!value.contains("type") || value["type"] != "Feature")
      return fail("type is not \"Feature\"");
    if (!value.contains("properties") || !value["properties"].is_object())
      return fail("has no properties (give at least {\"kind\": ..., \"name\": ...})");
    feature.properties = value["properties"];
    feature.heights_from_m = heights_from_m;
    feature.ground_m = ground_m;
    if (!value.contains("geometry") || !value["geometry"].is_object())
      return fail("has no geometry");
    const JsonReader geometry(value["geometry"], file, feature.where + ": geometry");
    GLARECAM_CHECK(geometry.onlyKeys({"type", "coordinates", "bbox"}));
    GLARECAM_ASSIGN(feature.geometry, geometry.text("type"));
    JsonReader coordinates;
    GLARECAM_ASSIGN(coordinates, geometry.arrayMember("coordinates"));
    if (feature.geometry == "Point") {
      LonLatH position{};
      GLARECAM_ASSIGN(position, geoJsonPosition(coordinates, heights_from_m));
      feature.positions.push_back(position);
    } else if (feature.geometry == "LineString") {
      GLARECAM_ASSIGN(feature.positions, geoJsonPositions(coordinates, heights_from_m));
    } else if (feature.geometry == "Polygon") {
      if (coordinates.size() != 1) {
        return fail(
            fmt::format("geometry has {} rings (a polygon of the scene has one: no "
                        "holes)",
                        coordinates.size()));
      }
      GLARECAM_ASSIGN(feature.positions, geoJsonPositions(coordinates.element(0), heights_from_m));
      // RFC 7946 closes a ring by repeating its first position; the scene's polygons do not.
      std::vector<LonLatH>& ring = feature.positions;
      if (ring.size() > 1 && ring.front()[0] == ring.back()[0] &&
          ring.front()[1] == ring.back()[1] &&
          (ring.front()[2] == ring.back()[2] ||
           (std::isnan(ring.front()[2]) && std::isnan(ring.back()[2])))) {
        ring.pop_back();
      }
    } else {
      return fail("geometry is a " + feature.geometry +
                  " (the scene's features are a Polygon, a Point or a LineString)");
    }
    if (feature.positions.empty()) return fail("geometry has no coordinates");
    features.push_back(std::move(feature));
  }
  return sceneFromGeoFeatures(features, settings, file, base);
}

}  // namespace glarecam::hazard
