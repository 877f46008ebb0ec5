#include "calibration/linearity_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace glarecam::calibration {
namespace {

std::vector<RampPoint> rampPoints(std::span<const InputFrame> frames,
                                  std::span<const ExposureGroup> groups, double black_level_dn,
                                  const Roi& roi) {
  std::vector<RampPoint> points;
  for (const ExposureGroup& group : groups) {
    double sum = 0;
    for (std::size_t i : group.frames) sum += regionStats(frames[i].frame, roi).mean_dn;
    points.push_back(
        {.exposure_us = group.exposure_us,
         .signal_dn = sum / static_cast<double>(group.frames.size()) - black_level_dn});
  }
  return points;
}

// Least squares through the origin on the points inside the fit band.
std::optional<double> fitSlope(const std::vector<RampPoint>& points) {
  double largest = 0;
  for (const RampPoint& p : points) largest = std::max(largest, p.signal_dn);
  double sxy = 0, sxx = 0;
  std::size_t used = 0;
  for (const RampPoint& p : points) {
    if (p.signal_dn < kLinearFitLowFraction * largest ||
        p.signal_dn > kLinearFitHighFraction * largest)
      continue;
    sxy += p.exposure_us * p.signal_dn;
    sxx += p.exposure_us * p.exposure_us;
    ++used;
  }
  if (used < 2) return std::nullopt;
  return sxy / sxx;
}

}  // namespace

Status checkLinearityTolerance(double tolerance) {
  if (!(tolerance > 0 && tolerance < 1))
    return badInput(
        fmt::format("calibrate linearity: tolerance {:g} must be in (0, 1)", tolerance));
  return {};
}

Result<LinearityCalibration> calibrateLinearity(std::span<const InputFrame> frames,
                                                double black_level_dn, const Roi& roi,
                                                double tolerance) {
  if (frames.empty()) return badInput("calibrate linearity: no frames");
  const RawFrame& first = frames.front().frame;
  GLARECAM_CHECK(checkRoi(roi, first.width(), first.height(), "--roi"));
  GLARECAM_CHECK(checkLinearityTolerance(tolerance));
  LinearityCalibration result;
  result.tolerance = tolerance;
  const std::vector<ExposureGroup> groups = groupByExposure(specsOf(frames));
  GLARECAM_CHECK(checkOneGain(groups, "linearity"));
  result.points = rampPoints(frames, groups, black_level_dn, roi);
  if (result.points.size() < kMinRampPoints) {
    return badInput(fmt::format(
        "calibrate linearity: {} exposure(s); a ramp needs at least {} different exposures",
        result.points.size(), kMinRampPoints));
  }
  const auto slope = fitSlope(result.points);
  if (!slope || !(*slope > 0)) {
    return badInput(fmt::format(
        "calibrate linearity: fewer than 2 exposures give between {:g} % and {:g} % of the "
        "largest signal: spread the ramp more evenly",
        100 * kLinearFitLowFraction, 100 * kLinearFitHighFraction));
  }
  result.slope_dn_per_us = *slope;
  for (RampPoint& p : result.points) p.deviation = p.signal_dn / (*slope * p.exposure_us) - 1;

  // The usable range: from the first point above the noise floor up to the last point before
  // the deviation first exceeds the tolerance (interpolated to where it crosses).
  const RampPoint* last_good = nullptr;
  double largest = 0;
  for (const RampPoint& p : result.points) largest = std::max(largest, p.signal_dn);
  for (const RampPoint& p : result.points) {
    if (p.signal_dn < kLinearFitLowFraction * largest) continue;
    if (std::abs(p.deviation) > tolerance) {
      result.bend_found = last_good != nullptr;
      if (last_good) {
        const double f = (tolerance - std::abs(last_good->deviation)) /
                         (std::abs(p.deviation) - std::abs(last_good->deviation));
        result.linear_to_dn =
            black_level_dn + last_good->signal_dn + f * (p.signal_dn - last_good->signal_dn);
      }
      break;
    }
    if (!last_good) result.linear_from_dn = black_level_dn + p.signal_dn;
    last_good = &p;
    result.max_deviation = std::max(result.max_deviation, std::abs(p.deviation));
  }
  if (!last_good) return badInput("calibrate linearity: no point of the ramp is linear");
  if (!result.bend_found) result.linear_to_dn = black_level_dn + last_good->signal_dn;
  result.saturation_dn = result.linear_to_dn;
  return result;
}

nlohmann::json linearityValues(const LinearityCalibration& linearity) {
  nlohmann::json points = nlohmann::json::array();
  for (const RampPoint& p : linearity.points) {
    points.push_back(
        {{"exposure_us", p.exposure_us}, {"signal_dn", p.signal_dn}, {"deviation", p.deviation}});
  }
  return {{"saturation_dn", linearity.saturation_dn},
          {"linearity",
           {{"tolerance", linearity.tolerance},
            {"linear_range_dn", {linearity.linear_from_dn, linearity.linear_to_dn}},
            {"max_deviation", linearity.max_deviation},
            {"bend_found", linearity.bend_found},
            {"slope_dn_per_us", linearity.slope_dn_per_us},
            {"ramp", points}}}};
}

}  // namespace glarecam::calibration
