#include "pipeline/facet_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/angles.h"

namespace glarecam::pipeline {

namespace {}

FacetSpread facetSpread(double alpha_deg, double beta_deg) {
  // The paper measures the sun's angle from the module plane: s = (0, cos e, sin e).
  const double elevation = radians(90.0 - alpha_deg);
  const double beta = radians(beta_deg);
  const double cos_e = std::cos(elevation), sin_e = std::sin(elevation), cos_b = std::cos(beta);
  const double cos_gamma_ew = cos_e * cos_e - sin_e * sin_e + 2.0 * sin_e * sin_e * cos_b * cos_b;
  return {.alpha_deg = alpha_deg,
          .gamma_ew_deg = degrees(std::acos(std::clamp(cos_gamma_ew, -1.0, 1.0))),
          .gamma_ns_deg = 2.0 * beta_deg,
          .valid = 90.0 - alpha_deg >= beta_deg};
}

}  // namespace glarecam::pipeline
