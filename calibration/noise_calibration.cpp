#include "calibration/noise_calibration.h"

#include <fmt/format.h>

#include <cmath>

#include "calibration/radiometry.h"

namespace glarecam::calibration {
namespace {

// A pair whose ROI comes within this many temporal standard deviations of saturation loses
// variance to clipping: left out.
constexpr double kSaturationMarginSigmas = 4.0;
// Reweighting rounds of the fit (weights from the previous line; two settle it to 1e-4).
constexpr int kFitRounds = 3;

struct Line {
  double intercept = 0, slope = 0;
  double intercept_u = 0, slope_u = 0;
};

// Weighted least squares of variance on mean. The variance of a sample variance is
// 2 var² / (n - 1): weights 1 / var², var from the line of the round before.
Line fitTransferLine(const std::vector<TransferPoint>& points, double pixels) {
  Line line{.intercept = 0, .slope = 0};
  for (int round = 0; round < kFitRounds; ++round) {
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const TransferPoint& p : points) {
      const double predicted =
          round == 0 ? p.variance_dn2 : line.intercept + line.slope * p.mean_dn;
      const double w = 1.0 / std::max(predicted * predicted, 1e-12);
      sw += w;
      sx += w * p.mean_dn;
      sy += w * p.variance_dn2;
      sxx += w * p.mean_dn * p.mean_dn;
      sxy += w * p.mean_dn * p.variance_dn2;
    }
    const double det = sw * sxx - sx * sx;
    line.slope = (sw * sxy - sx * sy) / det;
    line.intercept = (sxx * sy - sx * sxy) / det;
    // Each weight is 1 / var²; the variance of a point is 2 var² / (n - 1) (a difference of two
    // frames over `pixels` pixels): the covariance of the fit is (2 / (n - 1)) (XᵀWX)⁻¹.
    const double scale = 2.0 / (pixels - 1);
    line.slope_u = std::sqrt(scale * sw / det);
    line.intercept_u = std::sqrt(scale * sxx / det);
  }
  return line;
}

}  // namespace

Result<NoiseCalibration> calibrateNoise(std::span<const InputFrame> frames,
                                        const SensorLevels& levels, const Roi& roi) {
  if (frames.empty()) return badInput("calibrate noise: no frames");
  const RawFrame& first = frames.front().frame;
  GLARECAM_CHECK(checkRoi(roi, first.width(), first.height(), "--roi"));
  NoiseCalibration noise;
  std::size_t levels_used = 0;  // exposures with at least one usable pair
  for (const ExposureGroup& group : groupByExposure(specsOf(frames))) {
    const std::size_t before = noise.points.size();
    const double gain = linearGain(group.gain_db);
    for (std::size_t i = 0; i + 1 < group.frames.size(); i += 2) {
      const RawFrame& a = frames[group.frames[i]].frame;
      const RawFrame& b = frames[group.frames[i + 1]].frame;
      const RegionStats sa = regionStats(a, roi), sb = regionStats(b, roi);
      const double variance = differenceStats(a, b, roi).variance_dn2 / 2;
      if (std::max(sa.max_dn, sb.max_dn) + kSaturationMarginSigmas * std::sqrt(variance) >=
          levels.saturation_dn) {
        ++noise.pairs_near_saturation;
        continue;
      }
      noise.points.push_back(
          {.exposure_us = group.exposure_us,
           .gain_db = group.gain_db,
           .mean_dn = ((sa.mean_dn + sb.mean_dn) / 2 - levels.black_level_dn) / gain,
           .variance_dn2 = variance / (gain * gain)});
    }
    levels_used += noise.points.size() > before;
  }
  if (levels_used < kMinTransferPoints) {
    return badInput(fmt::format(
        "calibrate noise: usable pairs of equal exposure at {} exposure(s) ({} pairs near "
        "saturation left out); needs pairs at {} or more exposures",
        levels_used, noise.pairs_near_saturation, kMinTransferPoints));
  }
  const Line line = fitTransferLine(noise.points, static_cast<double>(roi.pixelCount()));
  if (!(line.slope > 0)) {
    return badInput(
        "calibrate noise: the variance does not grow with the signal: the pairs are not of a "
        "steady source, or the exposures span too little signal");
  }
  if (!(line.intercept > 0)) {
    return badInput(fmt::format(
        "calibrate noise: read noise not resolved (fitted read variance {:.3g} DN²): add pairs "
        "at short exposures or with the lens capped",
        line.intercept));
  }
  noise.model = {.read_noise_dn = std::sqrt(line.intercept), .dn_per_electron = line.slope};
  noise.read_noise_u_dn = line.intercept_u / (2 * noise.model.read_noise_dn);
  noise.dn_per_electron_u = line.slope_u;
  return noise;
}

nlohmann::json noiseValues(const NoiseCalibration& noise) {
  nlohmann::json points = nlohmann::json::array();
  for (const TransferPoint& p : noise.points) {
    points.push_back({{"exposure_us", p.exposure_us},
                      {"gain_db", p.gain_db},
                      {"mean_dn", p.mean_dn},
                      {"variance_dn2", p.variance_dn2}});
  }
  return {{"noise",
           {{"read_noise_dn", noise.model.read_noise_dn},
            {"dn_per_electron", noise.model.dn_per_electron},
            {"read_noise_u_dn", noise.read_noise_u_dn},
            {"dn_per_electron_u", noise.dn_per_electron_u},
            {"photon_transfer", points}}}};
}

}  // namespace glarecam::calibration
