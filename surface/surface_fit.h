// Fitting a microfacet surface (brdf_model.h) to a sweep (docs/brdf.md, "Fitting the model"):
// the few parameters that shape the lobe (the two facet widths and the lobe's weight; the
// distribution, index, coating, second lobe and floor stay as given) by least squares on every
// row's ln Lmax and limit-ellipse axes, each computed from the model alone (lobe_contours.h)
// under the sweep's reference sun. Ceres, numeric central differences; σ from the covariance of
// the residuals at the optimum.
#pragma once

#include <optional>
#include <vector>

#include "core/error.h"
#include "surface/brdf_model.h"
#include "surface/lobe_contours.h"

namespace glarecam::surface {

struct SurfaceFitRow {
  double alpha_deg = 0;
  double limit_cd_m2 = 0;
  double lmax_cd_m2 = 0;
  std::optional<double> vertical_deg, horizontal_deg;  // none: no limit ellipse
};

struct SurfaceFitOptions {
  MicrofacetParameters start;  // the fixed parameters, and the widths and weight to start from
  LobeOptions lobe;            // E_ref and the sun's disc (a coarser disc quadrature is fine)
  // The residuals' scales: ln Lmax to 5 %, the axes to 0.2° (the camera route's typical σ of a
  // field sweep: docs/process.md).
  double lmax_scale = 0.05, axis_scale_deg = 0.2;
  int max_iterations = 50;
  Status validate() const;
};

struct SurfacePrediction {
  double alpha_deg = 0;
  double lmax_cd_m2 = 0;
  std::optional<double> vertical_deg, horizontal_deg;
};

struct SurfaceFit {
  MicrofacetParameters parameters;
  // Standard uncertainties of the fitted parameters (from the covariance; none when singular).
  std::optional<double> width_x_u_deg, width_y_u_deg, lobe_weight_u;
  double cost = 0;  // ½ Σ r² at the optimum
  int iterations = 0;
  std::vector<SurfacePrediction> fitted;  // the model at each row's α
};

// The model's Lmax and limit-ellipse axes at α under `lobe` (the limit: `limit_cd_m2`).
SurfacePrediction predict(const MicrofacetParameters& parameters, double alpha_deg,
                          double limit_cd_m2, const LobeOptions& lobe);

Result<SurfaceFit> fitSurface(const std::vector<SurfaceFitRow>& rows,
                              const SurfaceFitOptions& options);

}  // namespace glarecam::surface
