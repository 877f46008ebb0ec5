#include "tests/hazard/hazard_fixtures.h"

#include <cmath>
#include <stdexcept>

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

nlohmann::json ladderProfileJson(double vertical_deg, double horizontal_deg, double reference_lx) {
  nlohmann::json profile = constantProfileJson(vertical_deg, horizontal_deg);
  profile["schema"] = "glarecam.glare-profile/2";
  profile["illuminance"] = {{"status", "referred"}, {"reference_lx", reference_lx}};
  // A log-quadratic lobe (hazard.md step 7) of peak 1e6 cd/m², whose contour at the limit 3e4
  // has the given axes: axis(T) = axis · √(ln(Lmax/T) / ln(Lmax/limit)), on the ladder's rungs.
  constexpr double kLmax = 1e6, kLimit = 3e4;
  nlohmann::json ladder = nlohmann::json::array();
  for (int alpha = 0; alpha <= 80; ++alpha) {
    nlohmann::json contours = nlohmann::json::array();
    for (const double level : {1e4, 2.15e4, 4.64e4, 1e5, 2.15e5, 4.64e5}) {
      const double scale = std::sqrt(std::log(kLmax / level) / std::log(kLmax / kLimit));
      const double v = vertical_deg * scale, h = horizontal_deg * scale;
      contours.push_back({{"level_cd_m2", level},
                          {"kind", "ladder"},
                          {"vertical_deg", v},
                          {"horizontal_deg", h},
                          {"orientation_deg", 0},
                          {"solid_angle_sr", pipeline::circularBeamSpread(v, h).solid_angle_sr},
                          {"uncertainty",
                           {{"vertical_deg", 0},
                            {"horizontal_deg", 0},
                            {"orientation_deg", 0},
                            {"solid_angle_sr", 0}}}});
    }
    ladder.push_back({{"alpha_deg", alpha}, {"contours", contours}});
  }
  profile["ladder"] = ladder;
  return profile;
}

ProfileTable ladderProfile(double vertical_deg, double horizontal_deg, double reference_lx) {
  const Result<ProfileTable> table = ProfileTable::fromJson(
      ladderProfileJson(vertical_deg, horizontal_deg, reference_lx), "ladder-profile.json");
  if (!table) throw std::runtime_error(table.error().message);
  return *table;
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
