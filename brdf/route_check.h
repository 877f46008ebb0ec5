// `glarecam route-check` (docs/brdf.md, "The route check"): the method's open question (its
// outlook, item 3) asked of a known surface. One surface model (surface/surface_catalogue.h) is
// measured both ways: the simulated rig photographs it under the sun (capture/sim: the surface
// scene, a 12-bit sensor, an auto-bracket) and `process` analyses each stack; the simulated
// goniophotometer measures it as a lab does (rings of samples, stated noise, a point lamp) and
// the BRDF route analyses each file. Per α both routes cover, Lmax and the limit ellipse's two
// axes are compared in units of their combined standard uncertainty, z = (camera − brdf) /
// √(σ_camera² + σ_brdf²), beside the surface's own truth (surface/lobe_contours.h). Where the two
// cannot be compared the row says why instead of a number: α beyond the goniophotometer's range,
// a grid too coarse for the lobe (the BRDF route refuses it), no glare ellipse on either side, an
// ellipse cut by the camera's frame or by the picture's edge. A check that compares nothing does
// not agree.
//
// The camera's sky is dark (RouteCheckOptions::camera_background_cd_m2): the BRDF route measures
// the sun's reflection alone, and a field sky of 3000 cd/m² in the glass would move the limit
// contour by a tenth of the limit. The camera's Lmax is compared less that sky (exactly known
// here; 0.03 % of the smallest maximum), its contours at the limit are the reflection's at the
// limit less 10 cd/m² (an axis shorter by ~1e-4 of itself, far inside either σ). Outputs in the
// output directory: camera/stacks/, camera/ results/, goniophotometer/ (the pab-opto files and
// truth.json), brdf/results/, and route-check.csv and route-check.json, each atomically.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "brdf/simulated_goniophotometer.h"
#include "core/error.h"

namespace glarecam::brdf {

struct RouteCheckOptions {
  std::string surface = "standard";  // a catalogue name or a surface TOML file
  std::vector<double> alphas_deg = {5, 10, 15, 20, 25, 30, 35, 40, 45, 50, 55, 60, 65, 70, 75, 80};
  std::filesystem::path output_directory = "route-check";
  // The simulated camera: frame, field of view (16 px a degree: a 5° ellipse 80 px across; the
  // glare-reduced lobe's 21° whole), the noise seed of the first α (then one more per α).
  int width = 640, height = 512;
  double horizontal_fov_deg = 40;
  std::uint64_t seed = 1;
  double camera_background_cd_m2 = 10;  // a dark laboratory sky in the glass
  // The goniophotometer's sampling and noise (its alphas_deg are the check's, up to the range).
  GoniophotometerOptions goniophotometer;
  // Lab goniophotometers stop about here (the sample holder shades the beam beyond).
  double instrument_max_alpha_deg = 70;
  // The routes agree when every compared quantity's |z| is at most this; unset: the threshold
  // that makes "every |z| within it" a 3σ statement about the whole check (99.73 % for all N
  // comparisons together when the σ are right: Šidák's correction, familyThresholdZ()). A fixed
  // 3 on each of 40 comparisons would call 10 % of correct checks a disagreement.
  std::optional<double> agreement_z;
  bool show_progress = true;
  Status validate() const;
};

// One quantity at one α: each route's value and standard uncertainty, the surface's truth.
struct RouteQuantity {
  std::optional<double> camera, camera_sigma, brdf, brdf_sigma, truth;
  std::optional<double> z;  // when both routes have a value and a σ
};

struct RouteCheckRow {
  double alpha_deg = 0;
  RouteQuantity lmax_cd_m2, vertical_deg, horizontal_deg;  // the limit ellipse's full axes
  double limit_cd_m2 = 0;
  // Why a quantity has no z (empty when all three have one): "beyond the goniophotometer's range
  // (70°)", "grid too coarse: …", "no glare ellipse (Lmax below the limit)", ….
  std::string note;
  bool agrees(double agreement_z) const;  // every compared quantity within it
  bool compared() const;                  // any quantity has a z
};

// Two-sided 3σ: P(|z| ≤ 3) for a standard normal.
inline constexpr double kThreeSigmaConfidence = 0.9973002039367398;

// The |z| below which all of `comparisons` independent standard normal values lie with
// probability `confidence`: Φ⁻¹(1 − (1 − confidence^(1/N)) / 2). 3.0 for one, 4.0 for 40.
double familyThresholdZ(int comparisons, double confidence = kThreeSigmaConfidence);

struct RouteCheckSummary {
  std::string surface;
  std::vector<RouteCheckRow> rows;
  double worst_abs_z = 0;  // over every compared quantity
  int compared = 0;        // quantities with a z
  std::string worst;       // which: "Lmax at α 50°"
  double threshold_z = 3;  // the agreement threshold used
  bool agree = false;      // something compared, and every compared quantity within it
  std::filesystem::path csv, json;
};

Result<RouteCheckSummary> runRouteCheck(const RouteCheckOptions& options);

// route-check.csv's text, and the same as a Markdown table (docs/brdf.md quotes it).
std::string formatRouteCheckCsv(const RouteCheckSummary& summary);
std::string formatRouteCheckMarkdown(const RouteCheckSummary& summary);
nlohmann::json routeCheckJson(const RouteCheckSummary& summary, const RouteCheckOptions& options);

}  // namespace glarecam::brdf
