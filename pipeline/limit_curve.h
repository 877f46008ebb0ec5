// The glare limit (threshold) curve of docs/method.md: the luminance above which a PV module
// is said to glare at angle of incidence alpha (from the module normal). 30 000 cd/m² up to
// 50°, then 40 000 at 60°, 100 000 at 70° and 400 000 at 80°, log-linear in between; undefined
// above 80° and for angles outside [0°, 90°].
#pragma once

#include <optional>

namespace glarecam::pipeline {

// The simpler constant-threshold mode of the method (and the curve's value up to 50°).
inline constexpr double kConstantGlareLimitCdM2 = 30'000.0;
// The method is defined up to this angle of incidence.
inline constexpr double kMaxLimitAlphaDeg = 80.0;

std::optional<double> glareLimitCdM2(double alpha_deg);

// Which limit a measurement used: the α curve, or one constant (`--threshold`).
struct GlareLimit {
  std::optional<double> constant_cd_m2;  // none: the α curve
  std::optional<double> at(double alpha_deg) const {
    return constant_cd_m2 ? constant_cd_m2 : glareLimitCdM2(alpha_deg);
  }
  const char* mode() const { return constant_cd_m2 ? "constant" : "alpha_curve"; }
  bool operator==(const GlareLimit&) const = default;
};

}  // namespace glarecam::pipeline
