#include "brdf/brdf_route.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "brdf/brdf_file.h"
#include "core/angles.h"
#include "core/atomic_file.h"
#include "core/progress.h"
#include "core/sha256.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/limit_curve.h"
#include "pipeline/luminance_stats.h"
#include "pipeline/process_stack.h"
#include "pipeline/sweep.h"

namespace glarecam::brdf {

namespace fs = std::filesystem;

Status BrdfRouteOptions::validate() const {
  GLARECAM_CHECK(image.validate());
  if (threshold_cd_m2 && !(std::isfinite(*threshold_cd_m2) && *threshold_cd_m2 > 0))
    return badInput("--threshold: must be a positive luminance in cd/m²");
  return {};
}

namespace {

nlohmann::json gaussianAxes(const GaussianLobe& g, double peak_cd_m2, double level_cd_m2) {
  if (!(level_cd_m2 < peak_cd_m2)) return nullptr;
  const double fraction = level_cd_m2 / peak_cd_m2;
  return {{"level_cd_m2", level_cd_m2},
          {"vertical_deg", g.verticalAxisDeg(fraction)},
          {"horizontal_deg", g.horizontalAxisDeg(fraction)}};
}

// The id of one measurement: the file's stem, with θ_i when the file holds several.
std::string measurementId(const BrdfMeasurement& m, bool several) {
  const std::string stem = fs::path(m.file).stem().string();
  return several ? fmt::format("{}-{:g}deg", stem, m.incident_theta_deg) : stem;
}

pipeline::CalibrationIdentity fileIdentity(const BrdfMeasurement& m, double scale_u) {
  pipeline::CalibrationIdentity identity;
  identity.origin = "brdf";
  const fs::path file = fs::absolute(m.file).lexically_normal();
  identity.file = file.string();
  if (auto digest = sha256OfFile(file)) identity.sha256 = std::move(*digest);
  // No camera, no K: the values are f_r · E_ref · cos α themselves (id empty: nothing to mix).
  // Its uncertainty is the grid's: linear interpolation of ln f_r between samples under-reads the
  // lobe's top alike over it, as an error of K would scale it (brdf_luminance.h).
  identity.luminance_factor = 1;
  identity.luminance_factor_u = scale_u;
  return identity;
}

}  // namespace

nlohmann::json brdfBlock(const BrdfMeasurement& m, const SamplingCheck& sampling,
                         const BrdfLuminance& luminance, const LuminanceImageOptions& image,
                         std::optional<double> limit_cd_m2) {
  const GaussianLobe& g = sampling.lobe;
  // The Gaussian's peak luminance under the same sun, without the disc (the approximation is
  // the method's, of the cone before any convolution).
  const double scale = image.reference_illuminance_lx * std::cos(radians(m.incident_theta_deg));
  const double peak_cd_m2 = g.peak_brdf_sr * scale;
  return {{"file", fs::absolute(m.file).lexically_normal().string()},
          {"format", toString(m.format)},
          {"sample_name",
           m.sample_name.empty() ? nlohmann::json(nullptr) : nlohmann::json(m.sample_name)},
          {"incident_theta_deg", m.incident_theta_deg},
          {"incident_phi_deg", m.incident_phi_deg},
          {"samples", m.samples.size()},
          {"peak_brdf_sr", m.samples[sampling.peak_index].brdf_sr},
          {"peak_offset_deg", sampling.peak_offset_deg},
          {"spacing_deg", sampling.spacing_deg},
          {"samples_across_fwhm", sampling.samples_across_fwhm},
          {"relative_noise", luminance.relative_noise},
          {"noise", luminance.noise_origin},
          {"grid_relative_uncertainty", luminance.grid_relative_uncertainty},
          {"contour_grid_relative_uncertainty", luminance.contour_grid_relative_uncertainty},
          {"noise_correlation_px", luminance.noise_correlation},
          {"coarsest_spacing_deg", sampling.coarsest_spacing_deg},
          {"covered_deg", luminance.covered_deg},
          {"pixel_deg", luminance.pixel_deg},
          {"sun_half_angle_deg", image.sun_half_angle_deg},
          {"gaussian",
           {{"peak_cd_m2", peak_cd_m2},
            {"sigma_vertical_deg", g.sigma_vertical_deg},
            {"sigma_horizontal_deg", g.sigma_horizontal_deg},
            {"orientation_deg", g.orientation_deg},
            {"samples", g.samples},
            {"limit", limit_cd_m2 ? gaussianAxes(g, peak_cd_m2, *limit_cd_m2) : nullptr},
            {"fwhm", gaussianAxes(g, peak_cd_m2, peak_cd_m2 / 2)}}}};
}

Result<BrdfAngle> processMeasurement(const BrdfMeasurement& m, const fs::path& result_directory,
                                     const BrdfRouteOptions& options,
                                     const SamplingCheck* checked) {
  GLARECAM_CHECK(options.validate());
  BrdfAngle angle;
  angle.file = m.file;
  angle.result_directory = result_directory;
  SamplingCheck sampling;
  if (checked) {
    sampling = *checked;
  } else {
    GLARECAM_ASSIGN(sampling, checkSampling(m));
  }
  angle.warnings = sampling.warnings;
  BrdfLuminance luminance;
  GLARECAM_ASSIGN(luminance, luminanceUnderSun(m, sampling, options.image));
  const pipeline::LuminanceStats stats = pipeline::luminanceStats(luminance.image);
  const std::optional<double> limit = options.threshold_cd_m2
                                          ? options.threshold_cd_m2
                                          : pipeline::glareLimitCdM2(m.incident_theta_deg);
  const calibration::CameraModel camera(luminance.intrinsics);
  const pipeline::GlareAnalysis glare = pipeline::analyseGlare(
      luminance.image, camera, stats.max,
      {.limit_cd_m2 = limit,
       .thresholds_cd_m2 = {},
       .scale_relative_uncertainty = luminance.contour_grid_relative_uncertainty,
       .ladder = options.ladder});
  pipeline::ResultIlluminance illuminance;
  // The picture is computed under the reference sun itself: E = E_ref exactly.
  illuminance.source = SourceIlluminance{
      .illuminance_lx = options.image.reference_illuminance_lx,
      .origin = IlluminanceOrigin::kGiven,
      .instrument = "the reference sun of the BRDF route (L = f_r · E_ref · cos α)"};
  illuminance.reference_lx = options.image.reference_illuminance_lx;
  nlohmann::json camera_block = {{"backend", "brdf"},
                                 {"model", fmt::format("{} file", toString(m.format))},
                                 {"serial", nullptr}};
  angle.result = pipeline::makeResult(
      {.stack_id = result_directory.filename().string(),
       .route = pipeline::Route::kBrdf,
       .brdf = brdfBlock(m, sampling, luminance, options.image, limit),
       .alpha_deg = m.incident_theta_deg,
       .alpha_source = "measurement",
       .camera = camera_block,
       .module = m.sample_name.empty() ? std::nullopt : std::optional(m.sample_name),
       .width = luminance.image.luminance_cd_m2.width(),
       .height = luminance.image.luminance_cd_m2.height(),
       .calibration = fileIdentity(m, luminance.grid_relative_uncertainty),
       .illuminance = illuminance,
       .stats = stats,
       .limit_cd_m2 = limit,
       .constant_limit = options.threshold_cd_m2.has_value(),
       .glare = glare,
       .ladder = options.ladder});
  Progress quiet("", pipeline::kResultFileSteps, false);
  GLARECAM_CHECK(pipeline::writeResultFiles(result_directory, luminance.image, camera, glare,
                                            stats.max, angle.result, options.float32, quiet));
  return angle;
}

Result<BrdfRouteSummary> runBrdfRoute(const std::vector<fs::path>& files,
                                      const BrdfRouteOptions& options) {
  GLARECAM_CHECK(options.validate());
  if (files.empty()) return badInput("brdf: no files");
  std::vector<BrdfMeasurement> measurements;
  std::vector<bool> several;
  for (const fs::path& file : files) {
    std::vector<BrdfMeasurement> read;
    GLARECAM_ASSIGN(read, readBrdfFile(file));
    for (BrdfMeasurement& m : read) {
      several.push_back(read.size() > 1);
      measurements.push_back(std::move(m));
    }
  }
  // Check every grid before the minutes of pictures: a refused file stops the run at once.
  std::vector<SamplingCheck> checks;
  for (const BrdfMeasurement& m : measurements) {
    SamplingCheck check;
    GLARECAM_ASSIGN(check, checkSampling(m));
    checks.push_back(std::move(check));
  }
  GLARECAM_CHECK(ensureDirectory(options.output_directory));
  std::vector<std::size_t> order(measurements.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::ranges::stable_sort(order, {},
                           [&](std::size_t i) { return measurements[i].incident_theta_deg; });
  BrdfRouteSummary summary;
  std::set<std::string> ids;
  Progress progress("brdf", static_cast<int>(measurements.size()), options.show_progress);
  for (std::size_t i : order) {
    const BrdfMeasurement& m = measurements[i];
    std::string id = measurementId(m, several[i]);
    for (int n = 2; ids.contains(id); ++n)
      id = fmt::format("{}-{}", measurementId(m, several[i]), n);
    ids.insert(id);
    BrdfAngle angle;
    GLARECAM_ASSIGN(angle, processMeasurement(
                               m, options.output_directory / pipeline::kSweepResultsDirectory / id,
                               options, &checks[i]));
    for (const std::string& warning : angle.warnings) spdlog::warn("{}", warning);
    auto row = pipeline::sweepRowFromResult(angle.result, angle.result_directory.string());
    if (!row) return badInput(fmt::format("{}: {}", m.file, row.error().message));
    summary.table.rows.push_back(std::move(*row));
    for (pipeline::ContourRow& c : pipeline::contourRowsFromResult(angle.result))
      summary.contours.rows.push_back(std::move(c));
    progress.advance(fmt::format("α {:g}°", m.incident_theta_deg));
    summary.angles.push_back(std::move(angle));
  }
  progress.finish();
  // The same α twice (two files of one angle, a file given twice): both rows are kept, as a
  // sweep keeps repeated stacks, and said.
  for (std::size_t i = 1; i < summary.angles.size(); ++i) {
    const double a = *summary.angles[i - 1].result.alpha_deg,
                 b = *summary.angles[i].result.alpha_deg;
    if (a == b)
      spdlog::warn("brdf: α {:g}° twice ({} and {}): both rows are in sweep.csv", b,
                   summary.angles[i - 1].file, summary.angles[i].file);
  }
  // Results of an earlier run into the same directory that this one did not write.
  std::error_code ec;
  const fs::path results = options.output_directory / pipeline::kSweepResultsDirectory;
  for (const auto& entry : fs::directory_iterator(results, ec)) {
    if (!entry.is_directory(ec) || ids.contains(entry.path().filename().string())) continue;
    spdlog::warn("brdf: {} is an earlier run's result, not in this sweep.csv",
                 entry.path().string());
  }
  summary.table.notes.push_back(fmt::format(
      "route brdf: {} angles of incidence from {} files, under E_ref {:g} klx{}",
      measurements.size(), files.size(), options.image.reference_illuminance_lx / 1000,
      options.image.sun_half_angle_deg > 0 ? " (the sun's disc)" : " (a point source)"));
  summary.sweep_csv = options.output_directory / pipeline::kSweepTableFileName;
  GLARECAM_CHECK(writeFileAtomic(summary.sweep_csv, pipeline::formatSweepTable(summary.table)));
  summary.contours_csv = options.output_directory / pipeline::kContourTableFileName;
  GLARECAM_CHECK(
      writeFileAtomic(summary.contours_csv, pipeline::formatContourTable(summary.contours)));
  return summary;
}

}  // namespace glarecam::brdf
