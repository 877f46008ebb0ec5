// KML scenes (geo_scene.h; docs/hazard.md, "Geographic scenes"): Google Earth's Placemarks read
// with pugixml into GeoFeatures. Namespaces are ignored as pugixml does (a "kml:" prefix is
// dropped), but for Google's extensions ("gx:altitudeMode").
#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <pugixml.hpp>
#include <string>

#include "core/json.h"
#include "core/spelling.h"
#include "core/text_file.h"
#include "hazard/geo_scene.h"

namespace glarecam::hazard {
namespace {

// A district's scene is kilobytes to a few megabytes; a larger file is not a scene.
constexpr std::uintmax_t kMaxKmlBytes = 64 << 20;

// An element's name without an OGC namespace prefix ("kml:Placemark" is "Placemark").
std::string_view kmlLocalName(const pugi::xml_node& node) {
  std::string_view name = node.name();
  if (name.starts_with("kml:")) name.remove_prefix(4);
  return name;
}

pugi::xml_node kmlChild(const pugi::xml_node& node, std::string_view name) {
  for (pugi::xml_node child : node.children())
    if (child.type() == pugi::node_element && kmlLocalName(child) == name) return child;
  return {};
}

std::string kmlTrimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return "";
  const auto last = text.find_last_not_of(" \t\r\n");
  return std::string(text.substr(first, last - first + 1));
}

std::string kmlText(const pugi::xml_node& node) { return kmlTrimmed(node.child_value()); }

// A Data value as the JSON it reads as ("[6, 22]", "180", "true"), else as text ("forward",
// "profiles/roof.json").
nlohmann::json kmlValue(const std::string& text) {
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (value.is_discarded() || value.is_object()) return text;
  return value;
}

// The ExtendedData of a Placemark or the Document as name → value: <Data name="k"><value>
// and <SchemaData><SimpleData name="k"> (QGIS writes the latter). A name given twice is an
// error, as is a Data without a name.
Result<nlohmann::json> kmlExtendedData(const pugi::xml_node& node, const std::string& where) {
  nlohmann::json data = nlohmann::json::object();
  const pugi::xml_node extended = kmlChild(node, "ExtendedData");
  const auto add = [&](const char* name, const std::string& text) -> Status {
    if (std::string(name).empty())
      return badInput(where + ": ExtendedData has a Data without a name");
    if (data.contains(name)) return badInput(where + ": ExtendedData gives \"" + name + "\" twice");
    data[name] = kmlValue(text);
    return {};
  };
  for (pugi::xml_node child : extended.children()) {
    if (kmlLocalName(child) == "Data") {
      GLARECAM_CHECK(add(child.attribute("name").value(), kmlText(kmlChild(child, "value"))));
    } else if (kmlLocalName(child) == "SchemaData") {
      for (pugi::xml_node simple : child.children()) {
        if (kmlLocalName(simple) == "SimpleData")
          GLARECAM_CHECK(add(simple.attribute("name").value(), kmlText(simple)));
      }
    }
  }
  return data;
}

// Every Placemark below `node`, in document order.
void kmlPlacemarks(const pugi::xml_node& node, std::vector<pugi::xml_node>& placemarks) {
  for (pugi::xml_node child : node.children()) {
    if (child.type() != pugi::node_element) continue;
    if (kmlLocalName(child) == "Placemark") {
      placemarks.push_back(child);
    } else {
      kmlPlacemarks(child, placemarks);
    }
  }
}

// The line of a byte offset in the text (1-based).
std::size_t kmlLine(std::string_view text, std::ptrdiff_t offset) {
  const auto end = text.begin() + std::clamp<std::ptrdiff_t>(offset, 0, std::ssize(text));
  return 1 + static_cast<std::size_t>(std::count(text.begin(), end, '\n'));
}

struct KmlHeights {
  std::optional<double> ground_m;  // the Document's ground_elevation_m
};

// A geometry's coordinates ("lon,lat[,alt] lon,lat[,alt] ...") with heights above sea level by
// its altitudeMode (KML's default: clampToGround).
Result<std::vector<LonLatH>> kmlCoordinates(const pugi::xml_node& geometry,
                                            const pugi::xml_node& coordinates_node,
                                            const KmlHeights& heights, const std::string& file,
                                            GeoFeature& feature) {
  const std::string kind = std::string(kmlLocalName(geometry));
  const auto fail = [&](const std::string& problem) {
    return badInput(file + ": " + feature.where + ": " + kind + " " + problem);
  };
  std::string mode = "clampToGround";
  if (const pugi::xml_node node = kmlChild(geometry, "altitudeMode")) mode = kmlText(node);
  if (const pugi::xml_node node = kmlChild(geometry, "gx:altitudeMode")) {
    mode = kmlText(node);
    if (mode == "clampToSeaFloor" || mode == "relativeToSeaFloor") {
      return fail("has gx:altitudeMode " + mode +
                  ", which the scene cannot place (use clampToGround, relativeToGround or "
                  "absolute)");
    }
  }
  if (mode != "clampToGround" && mode != "relativeToGround" && mode != "absolute") {
    return fail("has altitudeMode \"" + mode +
                "\" (known: clampToGround, relativeToGround, absolute)");
  }
  if (mode != "absolute" && !heights.ground_m) {
    return fail("has altitudeMode " + mode +
                " but the Document's ExtendedData gives no ground_elevation_m to count from");
  }
  feature.heights_from_m = mode == "absolute" ? 0 : *heights.ground_m;
  feature.ground_m = heights.ground_m;
  if (!coordinates_node) return fail("has no coordinates");
  const std::string text = coordinates_node.child_value();
  std::vector<LonLatH> positions;
  std::size_t at = 0;
  while (true) {
    at = text.find_first_not_of(" \t\r\n", at);
    if (at == std::string::npos) break;
    const std::size_t end = std::min(text.find_first_of(" \t\r\n", at), text.size());
    const std::string tuple = text.substr(at, end - at);
    at = end;
    std::vector<double> values;
    std::size_t from = 0;
    while (from <= tuple.size()) {
      const std::size_t comma = std::min(tuple.find(',', from), tuple.size());
      const std::string number = tuple.substr(from, comma - from);
      char* stop = nullptr;
      errno = 0;
      const double value = std::strtod(number.c_str(), &stop);
      if (number.empty() || *stop != '\0' || errno != 0 || !std::isfinite(value)) {
        return fail(
            fmt::format("coordinate {} \"{}\" is not lon,lat[,alt]", positions.size(), tuple));
      }
      values.push_back(value);
      from = comma + 1;
    }
    if (values.size() != 2 && values.size() != 3) {
      return fail(
          fmt::format("coordinate {} \"{}\" is not lon,lat[,alt]", positions.size(), tuple));
    }
    const double altitude_m = values.size() == 3 ? values[2] : 0;
    if (std::abs(values[0]) > 180 || std::abs(values[1]) > 90) {
      return fail(
          fmt::format("coordinate {} \"{}\" has a longitude or latitude out of range "
                      "(lon/lat swapped? KML gives lon,lat,alt)",
                      positions.size(), tuple));
    }
    if (std::abs(altitude_m) > kMaxCoordinateM)
      return fail(fmt::format("coordinate {} has altitude {} m", positions.size(), altitude_m));
    const double height_m = mode == "clampToGround"      ? *heights.ground_m
                            : mode == "relativeToGround" ? *heights.ground_m + altitude_m
                                                         : altitude_m;
    positions.push_back({values[0], values[1], height_m});
  }
  if (positions.empty()) return fail("has no coordinates");
  return positions;
}

// The GeoFeatures of one geometry of a Placemark (a MultiGeometry gives one per part).
Status kmlGeometry(const pugi::xml_node& geometry, const KmlHeights& heights,
                   const std::string& file, const GeoFeature& placemark,
                   std::vector<GeoFeature>& features) {
  const std::string_view type = kmlLocalName(geometry);
  GeoFeature feature = placemark;
  feature.geometry = std::string(type);
  if (type == "Point" || type == "LineString") {
    GLARECAM_ASSIGN(feature.positions, kmlCoordinates(geometry, kmlChild(geometry, "coordinates"),
                                                      heights, file, feature));
  } else if (type == "Polygon") {
    if (kmlChild(geometry, "innerBoundaryIs"))
      return badInput(file + ": " + placemark.where +
                      ": Polygon has an innerBoundaryIs (a polygon of the "
                      "scene has no holes)");
    const pugi::xml_node ring = kmlChild(kmlChild(geometry, "outerBoundaryIs"), "LinearRing");
    GLARECAM_ASSIGN(feature.positions, kmlCoordinates(geometry, kmlChild(ring, "coordinates"),
                                                      heights, file, feature));
    // KML closes a ring by repeating its first position; the scene's polygons do not.
    if (feature.positions.size() > 1 && feature.positions.front() == feature.positions.back())
      feature.positions.pop_back();
  } else {
    return badInput(file + ": " + placemark.where + ": has a " + std::string(type) +
                    " (the scene's Placemarks are a Polygon, a Point or a LineString)");
  }
  features.push_back(std::move(feature));
  return {};
}

bool isKmlGeometry(std::string_view name) {
  return name == "Point" || name == "LineString" || name == "Polygon" || name == "LinearRing" ||
         name == "MultiGeometry" || name == "Model" || name == "gx:Track" ||
         name == "gx:MultiTrack";
}

Result<GeoSceneSettings> kmlSettings(const pugi::xml_node& document, const std::string& file,
                                     KmlHeights& heights) {
  nlohmann::json data;
  GLARECAM_ASSIGN(data, kmlExtendedData(document, file + ": Document"));
  const JsonReader json(data, file, "Document ExtendedData");
  GLARECAM_CHECK(json.onlyKeys(
      {"schema", "utc_offset_h", "ground_elevation_m", "pressure_hpa", "temperature_c"}));
  if (json.has("schema")) GLARECAM_CHECK(json.schema(kGeoSceneSchema, "a geographic scene"));
  GeoSceneSettings settings;
  if (!json.has("utc_offset_h")) {
    return json.fail("utc_offset_h",
                     "is missing (give <Data name=\"utc_offset_h\"><value>1"
                     "</value></Data> in the Document's ExtendedData)");
  }
  GLARECAM_ASSIGN(settings.utc_offset_h,
                  json.numberIn("utc_offset_h", kMinUtcOffsetH, kMaxUtcOffsetH, " h"));
  GLARECAM_ASSIGN(heights.ground_m,
                  json.optionalNumberIn("ground_elevation_m", -1000, 10000, " m"));
  GLARECAM_ASSIGN(settings.pressure_hpa, json.optionalNumberIn("pressure_hpa", 0, 5000, " hPa"));
  GLARECAM_ASSIGN(settings.temperature_c, json.optionalNumberIn("temperature_c", -90, 60, " °C"));
  return settings;
}

}  // namespace

Result<Scene> parseKmlScene(std::string_view text, const std::string& file,
                            const std::filesystem::path& base) {
  pugi::xml_document xml;
  const pugi::xml_parse_result parsed = xml.load_buffer(text.data(), text.size());
  if (!parsed) {
    return badInput(fmt::format("{}: line {}: not KML ({})", file, kmlLine(text, parsed.offset),
                                parsed.description()));
  }
  const pugi::xml_node kml = xml.document_element();
  if (kmlLocalName(kml) != "kml")
    return badInput(file + ": is not KML (its root element is <" + kml.name() + ">, not <kml>)");
  pugi::xml_node document = kmlChild(kml, "Document");
  if (!document) document = kml;
  KmlHeights heights;
  GeoSceneSettings settings;
  GLARECAM_ASSIGN(settings, kmlSettings(document, file, heights));

  std::vector<pugi::xml_node> placemarks;
  kmlPlacemarks(document, placemarks);
  std::vector<GeoFeature> features;
  for (std::size_t p = 0; p < placemarks.size(); ++p) {
    const pugi::xml_node node = placemarks[p];
    GeoFeature placemark;
    const std::string name = kmlText(kmlChild(node, "name"));
    placemark.locator = "Placemark[" + std::to_string(p) + "]";
    placemark.where = fmt::format("{} (\"{}\", line {})", placemark.locator, name,
                                  kmlLine(text, node.offset_debug()));
    GLARECAM_ASSIGN(placemark.properties, kmlExtendedData(node, file + ": " + placemark.where));
    if (placemark.properties.contains("name")) {
      return badInput(file + ": " + placemark.where +
                      ": ExtendedData gives a name (the Placemark's <name> is its name)");
    }
    if (!placemark.properties.contains("kind")) {
      return badInput(file + ": " + placemark.where +
                      ": has no kind (give <ExtendedData><Data name=\"kind\"><value>array"
                      "</value></Data></ExtendedData>; kinds: array, observer, route, area, "
                      "obstruction)");
    }
    placemark.properties["name"] = name;
    std::vector<pugi::xml_node> geometries;
    for (pugi::xml_node child : node.children()) {
      if (kmlLocalName(child) == "MultiGeometry") {
        for (pugi::xml_node part : child.children())
          if (isKmlGeometry(kmlLocalName(part))) geometries.push_back(part);
      } else if (isKmlGeometry(kmlLocalName(child))) {
        geometries.push_back(child);
      }
    }
    if (geometries.empty())
      return badInput(file + ": " + placemark.where + ": has no Polygon, Point or LineString");
    const std::size_t first = features.size();
    for (const pugi::xml_node& geometry : geometries)
      GLARECAM_CHECK(kmlGeometry(geometry, heights, file, placemark, features));
    // A MultiGeometry's parts are features of their own: "roof/1", "roof/2".
    if (features.size() - first > 1) {
      for (std::size_t k = first; k < features.size(); ++k) {
        const std::string part_name = fmt::format("{}/{}", name, k - first + 1);
        features[k].properties["name"] = part_name;
        features[k].where = fmt::format("{} (\"{}\", line {})", placemark.locator, part_name,
                                        kmlLine(text, node.offset_debug()));
      }
    }
  }
  if (features.empty()) return badInput(file + ": has no Placemark");
  return sceneFromGeoFeatures(features, settings, file, base);
}

Result<Scene> readKmlScene(const std::filesystem::path& path) {
  std::string text;
  GLARECAM_ASSIGN(text, readTextFile(path, kMaxKmlBytes, "a KML scene"));
  Scene scene;
  GLARECAM_ASSIGN(scene, parseKmlScene(text, path.string(), path.parent_path()));
  scene.path = path;
  return scene;
}

}  // namespace glarecam::hazard
