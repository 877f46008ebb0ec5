#include "brdf/route_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "brdf/brdf_file.h"
#include "brdf/brdf_route.h"
#include "capture/sim/simulated_stack.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/json.h"
#include "core/progress.h"
#include "core/source_illuminance.h"
#include "pipeline/limit_curve.h"
#include "pipeline/process_stack.h"
#include "pipeline/sweep.h"
#include "pipeline/sweep_table.h"
#include "surface/lobe_contours.h"
#include "surface/surface_catalogue.h"

namespace glarecam::brdf {
namespace fs = std::filesystem;
namespace {

constexpr int kMinSide = 64, kMaxSide = 4096;

// The values of one route's sweep row.
void fillRoute(const pipeline::SweepRow& row, bool camera, RouteCheckRow& out) {
  const auto put = [&](RouteQuantity& q, std::optional<double> value, std::optional<double> sigma) {
    (camera ? q.camera : q.brdf) = value;
    (camera ? q.camera_sigma : q.brdf_sigma) = sigma;
  };
  put(out.lmax_cd_m2, row.lmax_cd_m2, row.lmax_uncertainty_cd_m2);
  put(out.vertical_deg, row.vertical_deg, row.vertical_uncertainty_deg);
  put(out.horizontal_deg, row.horizontal_deg, row.horizontal_uncertainty_deg);
}

void addNote(std::string& note, const std::string& text) {
  note += (note.empty() ? "" : "; ") + text;
}

void compare(RouteQuantity& q) {
  if (!q.camera || !q.brdf || !q.camera_sigma || !q.brdf_sigma) return;
  const double sigma = std::hypot(*q.camera_sigma, *q.brdf_sigma);
  if (sigma > 0) q.z = (*q.camera - *q.brdf) / sigma;
}

// One route's row at one α, and whether its limit ellipse runs off its picture (then its axes
// are not the contour's).
struct RouteRow {
  pipeline::SweepRow row;
  bool truncated = false;
};

bool limitTruncated(const pipeline::StackResult& result) {
  return result.limit.ellipse && result.limit.ellipse->truncated;
}

// The camera route at one α: a stack of the simulated rig looking at the surface, processed.
Result<RouteRow> cameraRoute(const RouteCheckOptions& options, double alpha_deg, std::uint64_t seed,
                             const std::string& id) {
  capture::SimulationOptions sim;
  sim.surface = options.surface;
  sim.alpha_deg = alpha_deg;
  sim.width = options.width;
  sim.height = options.height;
  sim.horizontal_fov_deg = options.horizontal_fov_deg;
  sim.background_cd_m2 = options.camera_background_cd_m2;
  sim.seed = seed;
  capture::SimulatedStack stack;
  GLARECAM_ASSIGN(stack, capture::simulateStack(sim));
  const fs::path stack_directory = options.output_directory / "camera" / "stacks" / id;
  GLARECAM_CHECK(capture::writeSimulatedStack(stack_directory, stack));
  pipeline::ProcessOptions process;
  process.output_directory =
      options.output_directory / "camera" / pipeline::kSweepResultsDirectory / id;
  process.show_progress = false;
  pipeline::ProcessSummary processed;
  GLARECAM_ASSIGN(processed, pipeline::processStack(stack_directory, process));
  RouteRow out;
  out.truncated = limitTruncated(processed.result);
  GLARECAM_ASSIGN(out.row,
                  pipeline::sweepRowFromResult(processed.result, stack_directory.string()));
  return out;
}

// The BRDF route at one α: the goniophotometer's file written and analysed; a grid the route
// refuses is the row's note, not an error.
Result<std::optional<RouteRow>> brdfRoute(const surface::BrdfModel& model,
                                          const RouteCheckOptions& options, double alpha_deg,
                                          const std::string& id, std::string& note) {
  const fs::path file = options.output_directory / "goniophotometer" / (id + ".dat");
  const BrdfMeasurement m =
      simulateMeasurement(model, alpha_deg, options.goniophotometer, file.string());
  GLARECAM_CHECK(writeFileAtomic(file, formatPabOpto(m)));
  const auto sampling = checkSampling(m);
  if (!sampling) {
    if (sampling.error().code != ErrorCode::kBadInput) return std::unexpected(sampling.error());
    addNote(note, "BRDF route refuses the grid: " + sampling.error().message);
    return std::optional<RouteRow>{};
  }
  BrdfRouteOptions route;
  route.output_directory = options.output_directory / "brdf";
  route.show_progress = false;
  BrdfAngle angle;
  GLARECAM_ASSIGN(
      angle, processMeasurement(m, route.output_directory / pipeline::kSweepResultsDirectory / id,
                                route, &*sampling));
  for (const std::string& warning : angle.warnings) addNote(note, warning);
  RouteRow out;
  out.truncated = limitTruncated(angle.result);
  GLARECAM_ASSIGN(out.row, pipeline::sweepRowFromResult(angle.result, file.string()));
  return std::optional<RouteRow>(std::move(out));
}

// The names a route check writes into its directory.
constexpr std::array<const char*, 5> kOutputNames = {"camera", "goniophotometer", "brdf",
                                                     "route-check.csv", "route-check.json"};

// The output directory: made when missing; one that holds anything but a route check's own
// outputs is refused (a check writes five names into it and removes the last one's first, so it
// never mixes two runs, and never touches what it did not make).
Status prepareOutputDirectory(const fs::path& directory) {
  const std::string name = directory.string();
  std::error_code ec;
  if (fs::exists(directory, ec)) {
    if (!fs::is_directory(directory, ec))
      return badInput(fmt::format("route-check: --out {}: not a directory", name));
    for (const auto& entry : fs::directory_iterator(directory, ec)) {
      const std::string file = entry.path().filename().string();
      if (std::ranges::find(kOutputNames, file) == kOutputNames.end())
        return badInput(fmt::format(
            "route-check: --out {} holds {}, which no route check wrote: give a new or a route "
            "check's own directory",
            name, file));
    }
    if (ec) return badInput(fmt::format("route-check: --out {}: {}", name, ec.message()));
    for (const char* file : kOutputNames) {
      fs::remove_all(directory / file, ec);
      if (ec)
        return ioError(fmt::format("route-check: cannot remove the earlier {}: {}",
                                   (directory / file).string(), ec.message()));
    }
  }
  GLARECAM_CHECK(ensureDirectory(directory));
  for (const char* sub : {"camera", "goniophotometer", "brdf"})
    GLARECAM_CHECK(ensureDirectory(directory / sub));
  return {};
}

}  // namespace

Status RouteCheckOptions::validate() const {
  if (alphas_deg.empty()) return badInput("route-check: --alpha names no angle");
  for (double alpha : alphas_deg)
    if (!(alpha > 0 && alpha <= pipeline::kMaxLimitAlphaDeg))
      return badInput(
          fmt::format("route-check: --alpha {:g} is outside (0, {:g}]° (the limit curve's range)",
                      alpha, pipeline::kMaxLimitAlphaDeg));
  if (!std::ranges::is_sorted(alphas_deg) ||
      std::ranges::adjacent_find(alphas_deg) != alphas_deg.end())
    return badInput("route-check: --alpha must ascend without repeats");
  if (!(horizontal_fov_deg >= 5 && horizontal_fov_deg <= 120))
    return badInput("route-check: --fov must be between 5 and 120 degrees");
  if (width < kMinSide || height < kMinSide || width > kMaxSide || height > kMaxSide)
    return badInput(
        fmt::format("route-check: --size must be between {0}x{0} and {1}x{1}", kMinSide, kMaxSide));
  if (!(instrument_max_alpha_deg > 0 && instrument_max_alpha_deg < 90))
    return badInput("route-check: --instrument-max-alpha must be in (0, 90)°");
  if (agreement_z && !(*agreement_z > 0 && std::isfinite(*agreement_z)))
    return badInput("route-check: --agreement must be a positive number of σ");
  if (!(camera_background_cd_m2 > 0 && std::isfinite(camera_background_cd_m2)))
    return badInput("route-check: the camera's background must be a positive luminance");
  GoniophotometerOptions instrument = goniophotometer;
  instrument.alphas_deg = {std::min(alphas_deg.front(), instrument_max_alpha_deg)};
  return instrument.validate();
}

double familyThresholdZ(int comparisons, double confidence) {
  const double each = std::pow(confidence, 1.0 / std::max(1, comparisons));
  // P(|z| > t) = erfc(t / √2) = 1 − each, by bisection (erfc falls monotonically).
  double lo = 0, hi = 10;
  for (int k = 0; k < 100; ++k) {
    const double mid = (lo + hi) / 2;
    (std::erfc(mid / std::sqrt(2.0)) > 1 - each ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

bool RouteCheckRow::compared() const { return lmax_cd_m2.z || vertical_deg.z || horizontal_deg.z; }

bool RouteCheckRow::agrees(double agreement_z) const {
  for (const RouteQuantity* q : {&lmax_cd_m2, &vertical_deg, &horizontal_deg})
    if (q->z && !(std::abs(*q->z) <= agreement_z)) return false;
  return true;
}

Result<RouteCheckSummary> runRouteCheck(const RouteCheckOptions& options) {
  GLARECAM_CHECK(options.validate());
  std::unique_ptr<surface::BrdfModel> model;
  GLARECAM_ASSIGN(model, surface::surfaceModel(options.surface));
  GLARECAM_CHECK(prepareOutputDirectory(options.output_directory));
  RouteCheckSummary summary;
  summary.surface = options.surface;
  const int steps = static_cast<int>(options.alphas_deg.size());
  Progress progress("route-check", 2 * steps, options.show_progress);
  surface::LobeOptions truth_options;  // the reference sun's disc at E_ref
  truth_options.illuminance_lx = kDefaultReferenceIlluminanceLx;
  for (int i = 0; i < steps; ++i) {
    const double alpha = options.alphas_deg[static_cast<std::size_t>(i)];
    const std::string id = fmt::format("alpha-{:05.2f}", alpha);
    RouteCheckRow row;
    row.alpha_deg = alpha;
    row.limit_cd_m2 = pipeline::glareLimitCdM2(alpha).value_or(pipeline::kConstantGlareLimitCdM2);
    // The surface's own spot: the truth both routes are measured against.
    const surface::LobeContours peak = surface::lobePeak(*model, alpha, truth_options);
    const surface::ContourAxes axes =
        surface::contourAxes(*model, peak, row.limit_cd_m2, truth_options);
    row.lmax_cd_m2.truth = peak.peak_cd_m2;
    row.vertical_deg.truth = axes.vertical_deg;
    row.horizontal_deg.truth = axes.horizontal_deg;

    RouteRow camera;
    GLARECAM_ASSIGN(camera, cameraRoute(options, alpha, options.seed + i, id));
    // The camera sees the sun's reflection over the sky's B, the goniophotometer the reflection
    // alone: B, known exactly here, comes off the camera's maximum.
    camera.row.lmax_cd_m2 -= options.camera_background_cd_m2;
    fillRoute(camera.row, true, row);
    progress.advance(fmt::format("α {:g}°: camera", alpha));

    if (alpha > options.instrument_max_alpha_deg) {
      addNote(row.note, fmt::format("beyond the goniophotometer's range ({:g}°)",
                                    options.instrument_max_alpha_deg));
    } else {
      std::optional<RouteRow> brdf;
      GLARECAM_ASSIGN(brdf, brdfRoute(*model, options, alpha, id, row.note));
      if (brdf) fillRoute(brdf->row, false, row);
      if (brdf && brdf->truncated) {
        addNote(row.note,
                "the BRDF picture cuts the limit ellipse (its samples stop): axes not compared");
        row.vertical_deg.brdf = row.horizontal_deg.brdf = std::nullopt;
      }
    }
    if (camera.truncated) {
      addNote(row.note,
              "the camera's frame cuts the limit ellipse (--size, --fov): axes not compared");
      row.vertical_deg.camera = row.horizontal_deg.camera = std::nullopt;
    }
    progress.advance(fmt::format("α {:g}°: goniophotometer", alpha));

    for (RouteQuantity* q : {&row.lmax_cd_m2, &row.vertical_deg, &row.horizontal_deg}) compare(*q);
    const bool camera_ellipse = row.vertical_deg.camera && row.horizontal_deg.camera;
    const bool brdf_ellipse = row.vertical_deg.brdf && row.horizontal_deg.brdf;
    if (row.lmax_cd_m2.brdf && camera_ellipse != brdf_ellipse)
      addNote(row.note, fmt::format("a glare ellipse on the {} route only (Lmax near the limit)",
                                    camera_ellipse ? "camera" : "BRDF"));
    else if (row.lmax_cd_m2.brdf && !camera_ellipse)
      addNote(row.note, "no glare ellipse on either route (Lmax below the limit)");
    for (const RouteQuantity* q : {&row.lmax_cd_m2, &row.vertical_deg, &row.horizontal_deg}) {
      if (!q->z) continue;
      ++summary.compared;
      summary.worst_abs_z = std::max(summary.worst_abs_z, std::abs(*q->z));
    }
    summary.rows.push_back(std::move(row));
  }
  progress.finish();
  summary.threshold_z = options.agreement_z.value_or(familyThresholdZ(summary.compared));
  summary.agree = summary.compared > 0;  // nothing compared is no agreement
  for (const RouteCheckRow& row : summary.rows) {
    summary.agree = summary.agree && row.agrees(summary.threshold_z);
    for (const auto& [name, q] :
         {std::pair{"Lmax", &row.lmax_cd_m2}, std::pair{"vertical", &row.vertical_deg},
          std::pair{"horizontal", &row.horizontal_deg}})
      if (q->z && std::abs(*q->z) == summary.worst_abs_z && summary.worst.empty())
        summary.worst = fmt::format("{} at α {:g}°", name, row.alpha_deg);
  }
  summary.csv = options.output_directory / "route-check.csv";
  summary.json = options.output_directory / "route-check.json";
  GLARECAM_CHECK(writeFileAtomic(summary.csv, formatRouteCheckCsv(summary)));
  GLARECAM_CHECK(writeJsonFile(summary.json, routeCheckJson(summary, options)));
  return summary;
}

namespace {

std::string csvNumber(const std::optional<double>& value) {
  return value ? fmt::format("{:.6g}", *value) : std::string();
}

nlohmann::json quantityJson(const RouteQuantity& q) {
  const auto value = [](const std::optional<double>& v) -> nlohmann::json {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  return {{"camera", value(q.camera)}, {"camera_sigma", value(q.camera_sigma)},
          {"brdf", value(q.brdf)},     {"brdf_sigma", value(q.brdf_sigma)},
          {"truth", value(q.truth)},   {"z", value(q.z)}};
}

// A value to the second significant digit of its σ ("612.3k ± 1.1k", "29.58k ± 0.01k" for
// luminances in thousands; "5.512 ± 0.003" for angles), "–" when absent.
std::string shown(const std::optional<double>& value, const std::optional<double>& sigma,
                  bool luminance, bool show_sigma = true) {
  if (!value) return "–";
  const double unit = luminance ? 1e3 : 1.0;
  const char* suffix = luminance ? "k" : "";
  int decimals = luminance ? 1 : 3;
  if (sigma && *sigma > 0)
    decimals = std::clamp(1 - static_cast<int>(std::floor(std::log10(*sigma / unit))), 0, 6);
  if (!sigma || !show_sigma) return fmt::format("{:.{}f}{}", *value / unit, decimals, suffix);
  return fmt::format("{:.{}f}{} ± {:.{}f}{}", *value / unit, decimals, suffix, *sigma / unit,
                     decimals, suffix);
}

}  // namespace

std::string formatRouteCheckCsv(const RouteCheckSummary& summary) {
  std::string text = "# glarecam route-check: surface " + summary.surface +
                     "; z = (camera - brdf) / combined standard uncertainty\n"
                     "alpha_deg,limit_cd_m2";
  for (const char* name : {"lmax_cd_m2", "vertical_deg", "horizontal_deg"})
    for (const char* column : {"camera", "camera_sigma", "brdf", "brdf_sigma", "truth", "z"})
      text += fmt::format(",{}_{}", name, column);
  text += ",note\n";
  for (const RouteCheckRow& row : summary.rows) {
    text += fmt::format("{:g},{:.6g}", row.alpha_deg, row.limit_cd_m2);
    for (const RouteQuantity* q : {&row.lmax_cd_m2, &row.vertical_deg, &row.horizontal_deg})
      for (const auto* v :
           {&q->camera, &q->camera_sigma, &q->brdf, &q->brdf_sigma, &q->truth, &q->z})
        text += fmt::format(",{}", csvNumber(*v));
    text += fmt::format(",{}\n", quoteCsvField(row.note));
  }
  return text;
}

std::string formatRouteCheckMarkdown(const RouteCheckSummary& summary) {
  std::string text =
      "| α (°) | Lmax camera (cd/m²) | Lmax BRDF | Lmax truth | z | vertical camera (°) | "
      "vertical BRDF | truth | z | horizontal camera (°) | horizontal BRDF | truth | z | note |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  const auto z = [](const RouteQuantity& q) {
    return q.z ? fmt::format("{:+.1f}", *q.z) : std::string("–");
  };
  for (const RouteCheckRow& row : summary.rows) {
    text += fmt::format("| {:g} ", row.alpha_deg);
    for (const RouteQuantity* q : {&row.lmax_cd_m2, &row.vertical_deg, &row.horizontal_deg}) {
      const bool luminance = q == &row.lmax_cd_m2;
      text += fmt::format(
          "| {} | {} | {} | {} ", shown(q->camera, q->camera_sigma, luminance),
          shown(q->brdf, q->brdf_sigma, luminance),
          shown(q->truth, q->camera_sigma ? q->camera_sigma : q->brdf_sigma, luminance, false),
          z(*q));
    }
    text += "| " + row.note + " |\n";
  }
  return text;
}

nlohmann::json routeCheckJson(const RouteCheckSummary& summary, const RouteCheckOptions& options) {
  nlohmann::json rows = nlohmann::json::array();
  for (const RouteCheckRow& row : summary.rows)
    rows.push_back({{"alpha_deg", row.alpha_deg},
                    {"limit_cd_m2", row.limit_cd_m2},
                    {"lmax_cd_m2", quantityJson(row.lmax_cd_m2)},
                    {"vertical_deg", quantityJson(row.vertical_deg)},
                    {"horizontal_deg", quantityJson(row.horizontal_deg)},
                    {"agrees", row.compared() ? nlohmann::json(row.agrees(summary.threshold_z))
                                              : nlohmann::json(nullptr)},
                    {"note", row.note}});
  return {{"schema", "glarecam.route-check/1"},
          {"surface", summary.surface},
          {"threshold_z", summary.threshold_z},
          {"threshold", options.agreement_z ? "given" : "3σ for the whole check (Šidák)"},
          {"camera",
           {{"width", options.width},
            {"height", options.height},
            {"horizontal_fov_deg", options.horizontal_fov_deg},
            {"background_cd_m2", options.camera_background_cd_m2},
            {"seed", options.seed}}},
          {"goniophotometer",
           {{"fine_step_deg", options.goniophotometer.fine_step_deg},
            {"fine_radius_deg", options.goniophotometer.fine_radius_deg},
            {"relative_noise", options.goniophotometer.relative_noise},
            {"max_alpha_deg", options.instrument_max_alpha_deg}}},
          {"compared", summary.compared},
          {"worst_abs_z", summary.worst_abs_z},
          {"worst", summary.worst},
          {"agree", summary.agree},
          {"rows", rows}};
}

}  // namespace glarecam::brdf
