// hazard.geojson: the map of a run, one schema for `glarecam hazard` and its screening
// (docs/hazard.md, "Outputs"), that QGIS or geojson.io open as it is. RFC 7946: coordinates
// [longitude, latitude, height] on WGS84 (height above the ellipsoid; for a scene in metres the
// site's elevation is taken as its height above the ellipsoid), each Polygon's ring closed.
//
// A FeatureCollection of every array (a Polygon; properties kind "array", name, and per model
// `glares`: the receptor points it glares, and their number), then every receptor point (a
// Point; kind, name, receptor, candidates: the arrays within the distance whose front it sees,
// and per model minutes_per_year, hours_per_year, days_with_glare, max_minutes_per_day,
// worst_day (ISO date or null), verdicts (per criterion), ocular_class (the worst), ocular_minutes,
// peak_luminance_cd_m2, steps_beyond_method, steps_unknown_spread and the arrays that glare
// there). The foreign member "glarecam" gives the schema, the year, max_distance_m (null: no
// limit), the file with everything else (hazard.json, screen.json) and the local frame the
// positions were converted from (sceneFrameJson).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "hazard/hazard_calculation.h"
#include "hazard/scene.h"
#include "hazard/screening.h"

namespace glarecam::hazard {

inline constexpr const char* kHazardGeoJson = "hazard.geojson";
inline constexpr const char* kHazardGeoJsonSchema = "glarecam.hazard-geojson/1";

// [longitude, latitude, height] of a point of the scene: through the scene's geographic frame,
// or for a scene in metres around its site, the frame at the site (NaN, written as null, where
// PROJ cannot make that frame).
ToLonLat sceneToLonLat(const Scene& scene);
// The frame sceneToLonLat converts through: {"origin": "first array's first vertex" | "site",
// "longitude_deg", "latitude_deg", "height_m", "pipeline"} (the PROJ pipeline from lon/lat/height
// to the local metres, as `cct` takes it).
nlohmann::json sceneFrameJson(const Scene& scene);
// The options' max_distance_m as JSON: null for no limit.
nlohmann::json maxDistanceJson(const HazardOptions& options);

// "2027-06-21" for day 172 (0 = 1 January) of 2027.
std::string isoDate(int year, int day_of_year);
// The worst ocular class with minutes: "red", "yellow", "green", "unclassified" (glare the
// profile gives no luminance for) or "none" (no glare).
const char* worstOcularClass(const ScreenedModel& model);

// The map's numbers of computed receptor points: result.observers[i] is the scene's observer
// observers[i], and an event's array a is the scene's arrays[a]. Each model's arrays are sorted
// and unique, its peak luminance the brightest event's.
std::vector<ScreenedPoint> screenedPoints(const HazardResult& result,
                                          std::span<const std::size_t> observers,
                                          std::span<const std::size_t> arrays);
// The same for a whole scene's result (observers and arrays as the scene has them).
std::vector<ScreenedPoint> screenedPoints(const HazardResult& result);

struct HazardMap {
  const Scene* scene = nullptr;
  const HazardOptions* options = nullptr;
  const std::vector<ScreenedPoint>* points = nullptr;  // one per scene.observers, in order
  ToLonLat to_lon_lat;
  std::string results;  // the file with everything else: "hazard.json", "screen.json"
};
// kBadInput when the points do not cover the scene's receptor points.
Result<nlohmann::json> hazardGeoJson(const HazardMap& map);

}  // namespace glarecam::hazard
