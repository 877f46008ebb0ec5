// Scenes and profiles with known answers for the hazard tests.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "hazard/profile_table.h"
#include "hazard/scene.h"
#include "hazard/vec3.h"

namespace glarecam::hazard::testing {

// A glare profile document (glarecam.glare-profile/1) with the same axes at every α, glaring
// over `ranges` (default 0–80°), Lmax 1e6 and limit 3e4 cd/m² everywhere.
nlohmann::json constantProfileJson(double vertical_deg, double horizontal_deg,
                                   std::vector<std::pair<double, double>> ranges = {{0, 80}});
ProfileTable constantProfile(double vertical_deg, double horizontal_deg,
                             std::vector<std::pair<double, double>> ranges = {{0, 80}});

// The same as a glarecam.glare-profile/2 referred to `reference_lx`, with a contour ladder of a
// log-quadratic lobe whose contour at the limit has exactly those axes at every α.
nlohmann::json ladderProfileJson(double vertical_deg, double horizontal_deg,
                                 double reference_lx = 100'000);
ProfileTable ladderProfile(double vertical_deg, double horizontal_deg,
                           double reference_lx = 100'000);

// A square array of side `side_m` centred on `centre_m` facing `normal` (unit), vertices
// counter-clockwise seen from the front.
std::vector<Vec3> squareVertices(Vec3 centre_m, Vec3 normal, double side_m);
ArrayPolygon squareArray(const std::string& name, Vec3 centre_m, Vec3 normal, double side_m);

// The unit vector towards `elevation_deg` above the horizon at `azimuth_deg` (from north).
Vec3 unitToward(double elevation_deg, double azimuth_deg);

// The Zürich site of hazard.md's example (UTC+1).
HazardSite zurichSite();

Scene sceneOf(HazardSite site, std::vector<ArrayPolygon> arrays, std::vector<Observer> observers);

}  // namespace glarecam::hazard::testing
