#include "pipeline/limit_curve.h"

#include <array>
#include <cmath>

namespace glarecam::pipeline {
namespace {

struct LimitPoint {
  double alpha_deg;
  double limit_cd_m2;
};

// docs/method.md, "Glare limit (threshold) curve" (the SPF paper's proposed curve).
constexpr std::array<LimitPoint, 4> kLimitCurve{{
    {50.0, 30'000.0},
    {60.0, 40'000.0},
    {70.0, 100'000.0},
    {80.0, 400'000.0},
}};

}  // namespace

std::optional<double> glareLimitCdM2(double alpha_deg) {
  if (!std::isfinite(alpha_deg) || alpha_deg < 0.0 || alpha_deg > kMaxLimitAlphaDeg)
    return std::nullopt;
  if (alpha_deg <= kLimitCurve.front().alpha_deg) return kLimitCurve.front().limit_cd_m2;
  for (std::size_t i = 1; i < kLimitCurve.size(); ++i) {
    const LimitPoint& lo = kLimitCurve[i - 1];
    const LimitPoint& hi = kLimitCurve[i];
    if (alpha_deg == hi.alpha_deg) return hi.limit_cd_m2;  // exact at the table's points
    if (alpha_deg < hi.alpha_deg) {
      const double t = (alpha_deg - lo.alpha_deg) / (hi.alpha_deg - lo.alpha_deg);
      return std::exp(std::log(lo.limit_cd_m2) +
                      t * (std::log(hi.limit_cd_m2) - std::log(lo.limit_cd_m2)));
    }
  }
  return kLimitCurve.back().limit_cd_m2;
}

}  // namespace glarecam::pipeline
