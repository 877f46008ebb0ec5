// The paper's five-facet geometric model of beam spread (docs/method.md, "The geometric model"):
// one facet in the module plane and four tilted by beta toward the cardinal directions. It gives
// the angle between the specular ray and the ray reflected by an east-west tilted facet (gamma_ew,
// shrinking toward grazing incidence) and by a north-south tilted facet (gamma_ns = 2 beta).
// A reference curve only: it explains the ellipse's shape, not its growth at flat angles.
#pragma once

namespace glarecam::pipeline {

struct FacetSpread {
  double alpha_deg = 0;     // angle of incidence from the module normal (glarecam's α)
  double gamma_ew_deg = 0;  // east-west tilted facet: the horizontal half-spread
  double gamma_ns_deg = 0;  // north-south tilted facet: the vertical half-spread
  // The model holds while the sun's elevation above the module plane (90° - α) is at least β
  // (the paper's "α ≥ β" with its α measured from the plane).
  bool valid = false;
};

// Facets tilted further than this would face away from the sky.
inline constexpr double kMaxFacetTiltDeg = 45.0;

// alpha_deg in [0, 90], beta_deg in (0, kMaxFacetTiltDeg]; callers validate.
FacetSpread facetSpread(double alpha_deg, double beta_deg);

}  // namespace glarecam::pipeline
