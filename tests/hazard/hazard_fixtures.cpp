#include "tests/hazard/hazard_fixtures.h"

#include <cmath>

#include "pipeline/glare_profile.h"
#include "sun/incidence_angle.h"

namespace glarecam::hazard::testing {

nlohmann::json constantProfileJson(double vertical_deg, double horizontal_deg,
                                   std::vector<std::pair<double, double>> ranges) {
  nlohmann::json rows = nlohmann::json::array();
  const pipeline::CircularBeamSpread beam =
      pipeline::circularBeamSpread(vertical_deg, horizontal_deg);
  for (int alpha = 0; alpha <= 80; ++alpha) {
    rows.push_back({{"alpha_deg", alpha},
                    {"lmax_cd_m2", 1e6},
                    {"limit_cd_m2", 3e4},
                    {"glares", true},
                    {"vertical_deg", vertical_deg},
                    {"horizontal_deg", horizontal_deg},
                    {"circular_beam",
                     {{"beta_mrad", beam.beta_mrad},
                      {"slope_error_mrad", beam.slope_error_mrad},
                      {"solid_angle_sr", beam.solid_angle_sr}}},
                    {"extrapolated", false}});
  }
  nlohmann::json glare_ranges = nlohmann::json::array();
  for (const auto& [from, to] : ranges) glare_ranges.push_back({from, to});
  return {{"schema", "glarecam.glare-profile/1"},
          {"module", "test module"},
          {"glare_ranges_deg", glare_ranges},
          {"profile", rows}};
}

ProfileTable constantProfile(double vertical_deg, double horizontal_deg,
                             std::vector<std::pair<double, double>> ranges) {
  return *ProfileTable::fromJson(constantProfileJson(vertical_deg, horizontal_deg, ranges),
                                 "profile.json");
}

std::vector<Vec3> squareVertices(Vec3 centre_m, Vec3 normal, double side_m) {
  const Vec3 helper = std::abs(normal.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
  const Vec3 u = normalised(cross(helper, normal));
  const Vec3 w = cross(normal, u);  // u × w = n
  const double h = side_m / 2;
  return {centre_m + (-h) * u + (-h) * w, centre_m + h * u + (-h) * w, centre_m + h * u + h * w,
          centre_m + (-h) * u + h * w};
}

ArrayPolygon squareArray(const std::string& name, Vec3 centre_m, Vec3 normal, double side_m) {
  return *makeArrayPolygon(name, squareVertices(centre_m, normal, side_m), "scene.json",
                           "arrays[0].vertices_m");
}

HazardSite zurichSite() {
  HazardSite site;
  site.location.latitude_deg = 47.37;
  site.location.longitude_deg = 8.54;
  site.location.altitude_m = 410;
  site.location.pressure_hpa = sun::standardPressureHpa(410);
  site.utc_offset_h = 1.0;
  return site;
}

Scene sceneOf(HazardSite site, std::vector<ArrayPolygon> arrays, std::vector<Observer> observers) {
  Scene scene;
  scene.path = "scene.json";
  scene.site = site;
  scene.arrays = std::move(arrays);
  scene.observers = std::move(observers);
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    scene.observers[o].receptor = o;
    scene.receptors.push_back(
        {.kind = ReceptorKind::kObserver, .name = scene.observers[o].name, .first = o, .count = 1});
  }
  return scene;
}

Vec3 unitToward(double elevation_deg, double azimuth_deg) {
  const auto [east, north, up] = sun::eastNorthUp({elevation_deg, azimuth_deg});
  return {east, north, up};
}

}  // namespace glarecam::hazard::testing
