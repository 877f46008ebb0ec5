// A result document as small as `process` could write: Lmax, optionally α, the rest at its
// defaults (no limit, no ellipses, an inline calibration with K = 1500).
#pragma once

#include <optional>

#include "pipeline/result.h"

namespace glarecam::testing {

inline pipeline::StackResult minimalResult(double lmax_cd_m2,
                                           std::optional<double> alpha_deg = std::nullopt) {
  pipeline::StackResult result;
  result.stack = "20260621T080000Z-a40.00";
  result.alpha_deg = alpha_deg;
  if (alpha_deg) result.alpha_source = "manifest";
  result.width = 320;
  result.height = 256;
  result.calibration = {.origin = "inline", .id = "0123456789abcdef", .luminance_factor = 1500};
  result.luminance.max_cd_m2 = lmax_cd_m2;
  return result;
}

}  // namespace glarecam::testing
