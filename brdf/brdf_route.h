// `glarecam brdf`: the method's second route (its section 3.3; docs/brdf.md). Each angle of
// incidence of the goniophotometer files becomes the luminance picture the camera route would
// have photographed under the reference sun (brdf_luminance.h), analysed by the same glare
// analysis (limit ellipse, FWHM, ladder), and written as the camera route writes a processed
// stack: OUT/results/<id>/ with result.json (route "brdf", its `brdf` block: the file, grid,
// noise and the method's 2-D Gaussian approximation), luminance.exr, quality.exr and
// luminance.png; then OUT/sweep.csv and OUT/contours.csv, so that `fit`, `datasheet` and
// `hazard` take them unchanged.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "brdf/brdf_luminance.h"
#include "brdf/brdf_measurement.h"
#include "core/error.h"
#include "pipeline/contour_table.h"
#include "pipeline/result.h"
#include "pipeline/sweep_table.h"

namespace glarecam::brdf {

struct BrdfRouteOptions {
  std::filesystem::path output_directory = "brdf";
  LuminanceImageOptions image;            // E_ref, the sun's disc, the picture's size
  std::optional<double> threshold_cd_m2;  // a constant limit instead of the α curve
  bool ladder = true;
  bool float32 = false;  // the images at full float32 precision
  bool show_progress = true;
  Status validate() const;
};

struct BrdfAngle {
  std::string file;                        // the measurement's file
  std::filesystem::path result_directory;  // OUT/results/<id>
  pipeline::StackResult result;
  std::vector<std::string> warnings;  // the peak off the specular direction
};

struct BrdfRouteSummary {
  std::vector<BrdfAngle> angles;  // by α
  pipeline::SweepTable table;
  pipeline::ContourTable contours;
  std::filesystem::path sweep_csv, contours_csv;
};

// One measurement through the route: its result and picture in `result_directory`. `sampling`:
// checkSampling()'s of the measurement when the caller has it (runBrdfRoute checks every file
// first), else it is checked here.
Result<BrdfAngle> processMeasurement(const BrdfMeasurement& measurement,
                                     const std::filesystem::path& result_directory,
                                     const BrdfRouteOptions& options,
                                     const SamplingCheck* sampling = nullptr);

// Every file's measurements (a file the readers refuse stops the run: exit 2 naming it and the
// line), in order of α; OUT/sweep.csv and OUT/contours.csv written atomically at the end.
Result<BrdfRouteSummary> runBrdfRoute(const std::vector<std::filesystem::path>& files,
                                      const BrdfRouteOptions& options);

// The result block of the BRDF route (result.json's `brdf`).
nlohmann::json brdfBlock(const BrdfMeasurement& measurement, const SamplingCheck& sampling,
                         const BrdfLuminance& luminance, const LuminanceImageOptions& image,
                         std::optional<double> limit_cd_m2);

}  // namespace glarecam::brdf
