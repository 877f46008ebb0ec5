// `glarecam model fit` (docs/brdf.md, "Fitting the model"): the microfacet surface fitted to a
// sweep of either route (sweep.csv, or contours.csv: its limit rungs and half maxima), reported
// beside the method's empirical fits on the same rows (R² of ln Lmax and of each axis), with the
// rows' residuals and the model's prediction over the whole α range (where the BRDF instrument
// stops at 70° and the camera route rarely reaches 5°).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/sweep_table.h"
#include "surface/sun_disc.h"
#include "surface/surface_fit.h"

namespace glarecam::brdf {

struct ModelFitOptions {
  surface::MicrofacetParameters start;  // the fixed parameters and the start
  double sun_half_angle_deg = surface::kSunHalfAngleDeg;
  // The α of the prediction table: 0, 5, ... 85.
  double predict_step_deg = 5, predict_max_deg = 85;
  Status validate() const;
};

struct ModelFitRow {
  surface::SurfaceFitRow data;
  surface::SurfacePrediction model;
};

struct ModelFitReport {
  std::string source;                   // the table read
  double reference_illuminance_lx = 0;  // E_ref the model is evaluated under
  bool unreferred = false;              // the table is: fitted as if at the default E_ref
  surface::SurfaceFit fit;
  std::vector<ModelFitRow> rows;
  // R² on the rows' ln Lmax, vertical and horizontal axes: the model's, and the paper's
  // empirical fits' (none where the fit could not be made).
  double model_r2_ln_lmax = 0;
  std::optional<double> model_r2_vertical, model_r2_horizontal;
  std::optional<double> cosine_r2, biquadratic_r2, logistic_vertical_r2, logistic_horizontal_r2;
  std::vector<surface::SurfacePrediction> predictions;
  std::vector<std::string> warnings;
};

// The rows of a sweep.csv or a contours.csv (by its header).
Result<std::vector<surface::SurfaceFitRow>> readFitRows(const std::filesystem::path& table,
                                                        std::optional<double>& reference_lx);

Result<ModelFitReport> fitModelToTable(const std::filesystem::path& table,
                                       const ModelFitOptions& options);

nlohmann::json toJson(const ModelFitReport& report);
// The fitted surface as a surface file (`--surface FILE.toml`, docs/brdf.md).
std::string surfaceToml(const surface::MicrofacetParameters& parameters,
                        const std::string& comment);

}  // namespace glarecam::brdf
