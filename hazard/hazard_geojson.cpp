#include "hazard/hazard_geojson.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include "core/time.h"
#include "hazard/criteria.h"
#include "hazard/geo_frame.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

// The frame's origin: the geographic scene's, else the site's.
std::array<double, 3> frameOrigin(const Scene& scene) {
  if (scene.geo) return {scene.geo->longitudeDeg(), scene.geo->latitudeDeg(), scene.geo->heightM()};
  const sun::SiteLocation& site = scene.site.location;
  return {site.longitude_deg, site.latitude_deg, site.altitude_m};
}

json mapPointProperties(const HazardMap& map, const ScreenedPoint& point) {
  const Scene& scene = *map.scene;
  const HazardOptions& options = *map.options;
  const Observer& observer = scene.observers[point.observer];
  const bool has_receptor = observer.receptor < scene.receptors.size();
  json properties = {
      {"kind",
       has_receptor ? receptorKindName(scene.receptors[observer.receptor].kind) : "observer"},
      {"name", observer.name},
      {"receptor", has_receptor ? scene.receptors[observer.receptor].name : observer.name},
      {"candidates", point.candidates}};
  // Flat keys, MODEL_FIELD: a GIS reads each as a column it can style a map by (QGIS reads a
  // nested object as one JSON string).
  for (std::size_t m = 0; m < options.models.size(); ++m) {
    const ScreenedModel& model = point.models[m];
    const std::string key = options.models[m].name() + "_";
    json array_names = json::array();
    for (const std::size_t a : model.arrays) array_names.push_back(scene.arrays[a].name);
    properties[key + "minutes_per_year"] = model.minutes_per_year;
    properties[key + "hours_per_year"] = model.minutes_per_year / 60.0;
    properties[key + "days_with_glare"] = model.days_with_glare;
    properties[key + "max_minutes_per_day"] = model.max_minutes_per_day;
    properties[key + "worst_day"] =
        model.worst_day >= 0 ? json(isoDate(options.year, model.worst_day)) : json(nullptr);
    for (const Criterion& criterion : options.criteria)
      properties[key + criterion.id] =
          assess(criterion, model.max_minutes_per_day, model.minutes_per_year / 60.0).text;
    properties[key + "ocular_class"] = worstOcularClass(model);
    properties[key + "ocular_green_minutes"] = model.ocular_minutes[0];
    properties[key + "ocular_yellow_minutes"] = model.ocular_minutes[1];
    properties[key + "ocular_red_minutes"] = model.ocular_minutes[2];
    properties[key + "peak_luminance_cd_m2"] =
        model.peak_luminance_cd_m2 ? json(*model.peak_luminance_cd_m2) : json(nullptr);
    properties[key + "steps_beyond_method"] = model.steps_beyond_method;
    properties[key + "steps_unknown_spread"] = model.steps_unknown_spread;
    properties[key + "arrays"] = array_names;
  }
  return properties;
}

}  // namespace

ToLonLat sceneToLonLat(const Scene& scene) {
  std::shared_ptr<const GeoFrame> frame;
  if (scene.geo) {
    frame = std::make_shared<GeoFrame>(*scene.geo);
  } else {
    Result<GeoFrame> made =
        GeoFrame::make(scene.site.location.longitude_deg, scene.site.location.latitude_deg,
                       scene.site.location.altitude_m);
    if (made) frame = std::make_shared<GeoFrame>(std::move(*made));
  }
  if (!frame) {
    return [](Vec3) {
      constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
      return std::array<double, 3>{kNaN, kNaN, kNaN};
    };
  }
  return [frame](Vec3 point_m) { return frame->toLonLatH(point_m); };
}

json sceneFrameJson(const Scene& scene) {
  const std::array<double, 3> origin = frameOrigin(scene);
  return {{"origin", scene.geo ? "first array's first vertex" : "site"},
          {"longitude_deg", origin[0]},
          {"latitude_deg", origin[1]},
          {"height_m", origin[2]},
          {"pipeline", geoFramePipeline(origin[0], origin[1], origin[2])}};
}

json maxDistanceJson(const HazardOptions& options) {
  return std::isfinite(options.max_distance_m) ? json(options.max_distance_m) : json(nullptr);
}

std::string isoDate(int year, int day_of_year) {
  return formatIsoDay(std::chrono::sys_days{std::chrono::year{year} / 1 / 1} +
                      std::chrono::days(day_of_year));
}

const char* worstOcularClass(const ScreenedModel& model) {
  if (model.ocular_minutes[2] > 0) return "red";
  if (model.ocular_minutes[1] > 0) return "yellow";
  if (model.ocular_minutes[0] > 0) return "green";
  return model.minutes_per_year > 0 ? "unclassified" : "none";
}

std::vector<ScreenedPoint> screenedPoints(const HazardResult& result,
                                          std::span<const std::size_t> observers,
                                          std::span<const std::size_t> arrays) {
  std::vector<ScreenedPoint> points(result.observers.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ObserverHazard& observer = result.observers[i];
    ScreenedPoint& point = points[i];
    point.observer = observers[i];
    point.candidates = observer.candidates;
    point.pair_days = observer.pair_days;
    point.models.resize(observer.models.size());
    for (std::size_t m = 0; m < observer.models.size(); ++m) {
      const ModelSummary& summary = observer.models[m];
      ScreenedModel& model = point.models[m];
      model.minutes_per_year = summary.minutes_per_year;
      model.days_with_glare = summary.days_with_glare;
      model.max_minutes_per_day = summary.max_minutes_per_day;
      if (summary.max_minutes_per_day > 0) {
        const auto worst =
            std::max_element(summary.minutes_per_day.begin(), summary.minutes_per_day.end());
        model.worst_day =
            result.first_day + static_cast<int>(worst - summary.minutes_per_day.begin());
      }
      model.steps_beyond_method = summary.steps_beyond_method;
      model.steps_unknown_spread = summary.steps_unknown_spread;
      model.ocular_minutes = summary.ocular_minutes;
      model.unclassified_minutes = summary.unclassified_minutes;
    }
  }
  for (const GlareEvent& event : result.events) {
    ScreenedModel& model = points[event.observer].models[event.model];
    model.arrays.push_back(arrays[event.array]);
    if (event.peak_luminance_cd_m2 &&
        (!model.peak_luminance_cd_m2 || *event.peak_luminance_cd_m2 > *model.peak_luminance_cd_m2))
      model.peak_luminance_cd_m2 = event.peak_luminance_cd_m2;
  }
  for (ScreenedPoint& point : points) {
    for (ScreenedModel& model : point.models) {
      std::sort(model.arrays.begin(), model.arrays.end());
      model.arrays.erase(std::unique(model.arrays.begin(), model.arrays.end()), model.arrays.end());
    }
  }
  return points;
}

std::vector<ScreenedPoint> screenedPoints(const HazardResult& result) {
  std::size_t arrays = 0;
  for (const GlareEvent& event : result.events) arrays = std::max(arrays, event.array + 1);
  std::vector<std::size_t> observer_indices(result.observers.size()), array_indices(arrays);
  std::iota(observer_indices.begin(), observer_indices.end(), std::size_t{0});
  std::iota(array_indices.begin(), array_indices.end(), std::size_t{0});
  return screenedPoints(result, observer_indices, array_indices);
}

Result<json> hazardGeoJson(const HazardMap& map) {
  const Scene& scene = *map.scene;
  const HazardOptions& options = *map.options;
  const std::vector<ScreenedPoint>& points = *map.points;
  if (points.size() != scene.observers.size())
    return badInput("hazard.geojson: the result does not cover the scene's receptor points");
  const std::size_t models = options.models.size();
  // Per array and model, the receptor points it glares.
  std::vector<std::vector<json>> glared(scene.arrays.size(),
                                        std::vector<json>(models, json::array()));
  json point_features = json::array();
  for (const ScreenedPoint& point : points) {
    if (point.observer >= scene.observers.size() || point.models.size() != models)
      return badInput("hazard.geojson: a receptor point's result does not match the scene");
    for (std::size_t m = 0; m < models; ++m)
      for (const std::size_t a : point.models[m].arrays)
        glared.at(a)[m].push_back(scene.observers[point.observer].name);
    const std::array<double, 3> p = map.to_lon_lat(scene.observers[point.observer].position_m);
    point_features.push_back(
        {{"type", "Feature"},
         {"geometry", {{"type", "Point"}, {"coordinates", {p[0], p[1], p[2]}}}},
         {"properties", mapPointProperties(map, point)}});
  }
  json features = json::array();
  for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
    const ArrayPolygon& array = scene.arrays[a];
    json ring = json::array();
    for (const Vec3& vertex : array.vertices_m) {
      const std::array<double, 3> p = map.to_lon_lat(vertex);
      ring.push_back({p[0], p[1], p[2]});
    }
    ring.push_back(ring.front());  // RFC 7946: a linear ring is closed
    json properties = {{"kind", "array"}, {"name", array.name}};
    for (std::size_t m = 0; m < models; ++m) {
      const std::size_t count = glared[a][m].size();
      const std::string key = options.models[m].name() + "_";
      properties[key + "glares"] = std::move(glared[a][m]);
      properties[key + "receptor_points"] = count;
    }
    features.push_back({{"type", "Feature"},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", json::array({ring})}}},
                        {"properties", properties}});
  }
  for (json& feature : point_features) features.push_back(std::move(feature));
  return json{{"type", "FeatureCollection"},
              {"glarecam",
               {{"schema", kHazardGeoJsonSchema},
                {"year", options.year},
                {"max_distance_m", maxDistanceJson(options)},
                {"results", map.results},
                {"frame", sceneFrameJson(scene)}}},
              {"features", features}};
}

}  // namespace glarecam::hazard
