// The five-facet model: the facets' deflections against the closed forms at normal and grazing
// incidence.
#include "pipeline/facet_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/angles.h"

namespace glarecam::pipeline {
namespace {

TEST(FacetModel, MatchesTheClosedFormsAtNormalAndGrazingIncidence) {
  // At normal incidence both tilted facets deflect the ray by 2β; toward grazing the east-west
  // deflection vanishes (cos γ_ew → 1), the north-south one stays 2β.
  const FacetSpread normal = facetSpread(0.0, 2.5);
  EXPECT_NEAR(normal.gamma_ew_deg, 5.0, 1e-9);
  EXPECT_EQ(normal.gamma_ns_deg, 5.0);
  EXPECT_TRUE(normal.valid);
  const FacetSpread grazing = facetSpread(89.0, 2.5);
  EXPECT_LT(grazing.gamma_ew_deg, 0.1);
  EXPECT_FALSE(grazing.valid);  // elevation 1° < β
  // At 60° from the normal (elevation 30°): cos γ = cos²30 - sin²30 + 2 sin²30 cos²β.
  const double e = radians(30.0), b = radians(2.5);
  const double expected = std::acos(std::cos(e) * std::cos(e) - std::sin(e) * std::sin(e) +
                                    2 * std::sin(e) * std::sin(e) * std::cos(b) * std::cos(b));
  EXPECT_NEAR(facetSpread(60.0, 2.5).gamma_ew_deg, expected * 180 / std::numbers::pi, 1e-9);
}

}  // namespace
}  // namespace glarecam::pipeline
