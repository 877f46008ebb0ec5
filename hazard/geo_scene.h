// Geographic hazard scenes (../shared/docs/hazard.md, "Geographic scenes"; docs/hazard.md): the
// same arrays, receptors and obstructions as a glarecam.hazard-scene/2, drawn on a map instead
// of in local metres. Two formats:
//   - GeoJSON (RFC 7946): a FeatureCollection with the foreign member "glarecam" ({"schema":
//     "glarecam.hazard-geo/1", "utc_offset_h", "vertical_reference": "ground" | "sea",
//     "ground_elevation_m"}), each feature's properties.kind (array, observer, route, area,
//     obstruction), properties.name and the kind's keys; coordinates [lon, lat, height];
//   - KML (Google Earth): Placemarks whose ExtendedData gives the kind and keys, heights by
//     their altitudeMode; the scene's keys in the Document's ExtendedData.
// Both become the scene's v2 document in local east–north–up metres around the site, the first
// array's first vertex (geo_frame.h, exact geodetic conversion), which parseScene reads: one
// code path validates and expands every scene. Every error is kBadInput and reads "FILE: FEATURE:
// PROBLEM", naming the feature as the file has it: `city.geojson: features[12] ("roof-7"):
// geometry crosses itself (edges 0–1 and 2–3 cross)`, `city.kml: Placemark[3] ("roof-7", line
// 41): ...`. Refused besides what parseScene refuses: a longitude or latitude out of range or a
// feature farther than kMaxGeoDistanceM from the site (both most likely lon/lat swapped), a
// missing vertical reference, an unknown kind or key (with the closest known one), a geometry
// that is not its kind's, a polygon with holes.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "hazard/geo_frame.h"
#include "hazard/scene.h"

namespace glarecam::hazard {

inline constexpr const char* kGeoSceneSchema = "glarecam.hazard-geo/1";
// A glare assessment covers a plant and its neighbourhood: a feature farther than this from the
// site is a typing error, most often longitude and latitude swapped (which moves a point in
// central Europe by thousands of kilometres). Within it the frame is exact (geo_frame.h).
inline constexpr double kMaxGeoDistanceM = 50'000;

// One feature of a geographic scene as its file gives it, before conversion: what the GeoJSON
// and KML readers both produce.
struct GeoFeature {
  std::string where;    // how messages name it: `features[12] ("roof-7")`
  std::string locator;  // the same without its name, for references inside a message
  // kind, name and the kind's keys (hours, profile, ..., base_m, height_m) as the file has them
  nlohmann::json properties = nlohmann::json::object();
  std::string geometry;  // "Polygon" (without the closing vertex), "Point", "LineString"
  // Longitude, latitude, height above the ellipsoid ("sea level"); the height NaN where the file
  // gives none (a footprint's vertices need none).
  std::vector<LonLatH> positions;
  // The height above sea level that the feature's base_m and height_m count from: the ground's
  // (heights above the ground) or 0 (heights above sea level); and the ground's, when known,
  // where base_m defaults to it.
  double heights_from_m = 0;
  std::optional<double> ground_m;
};

// The scene-wide settings of a geographic scene (the site's, but for its position).
struct GeoSceneSettings {
  double utc_offset_h = 0;
  std::optional<double> pressure_hpa, temperature_c;
};

// The scene of the features: validated, converted to the frame around the first array's first
// vertex, read by parseScene, errors and warnings naming the features. Scene::geo holds the frame.
Result<Scene> sceneFromGeoFeatures(const std::vector<GeoFeature>& features,
                                   const GeoSceneSettings& settings, const std::string& file,
                                   const std::filesystem::path& base);

// Whether a JSON document is GeoJSON (a FeatureCollection), which readScene reads as a
// geographic scene.
bool isGeoJson(const nlohmann::json& document);
// A GeoJSON scene; `file` names it in messages, `base` resolves profile paths.
Result<Scene> parseGeoJsonScene(const nlohmann::json& document, const std::string& file,
                                const std::filesystem::path& base);
// A KML scene from its text, and from a file (kml_scene.cpp).
Result<Scene> parseKmlScene(std::string_view text, const std::string& file,
                            const std::filesystem::path& base);
Result<Scene> readKmlScene(const std::filesystem::path& path);

}  // namespace glarecam::hazard
