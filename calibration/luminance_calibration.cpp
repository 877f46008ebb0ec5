#include "calibration/luminance_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "calibration/hdr_merge.h"
#include "calibration/radiometry.h"

namespace glarecam::calibration {

Status LuminanceReference::validate() const {
  if (readings_cd_m2.empty())
    return badInput("calibrate luminance: give the meter's reading with --reference CD_M2");
  for (double reading : readings_cd_m2) {
    if (!(reading > 0) || !std::isfinite(reading))
      return badInput(
          fmt::format("calibrate luminance: --reference {:g} must be a positive "
                      "luminance in cd/m²",
                      reading));
  }
  if (!(meter_accuracy_percent >= 0) || meter_accuracy_percent >= 100)
    return badInput("calibrate luminance: --meter-accuracy must be in [0, 100) %");
  return {};
}

namespace {

// Refuses a region where the merge has only a bound: the reference saturated every frame (or
// none saw it).
Status checkMeasured(const MergedImage& merged, const Roi& roi) {
  long long lower = 0, upper = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const auto bound = static_cast<PixelBound>(merged.bound.at(x, y));
      lower += bound == PixelBound::kLowerBound;
      upper += bound == PixelBound::kUpperBound;
    }
  }
  if (lower > 0) {
    return badInput(fmt::format(
        "calibrate luminance: the reference is saturated in every frame at {} of the region's "
        "{} pixels: add a shorter exposure",
        lower, roi.pixelCount()));
  }
  if (upper > 0) {
    return badInput(fmt::format(
        "calibrate luminance: the reference is too dark in every frame at {} of the region's {} "
        "pixels: add a longer exposure",
        upper, roi.pixelCount()));
  }
  return {};
}

double meanOver(const FloatImage& image, const Roi& roi) {
  double sum = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y)
    for (int x = roi.x; x < roi.x + roi.width; ++x) sum += image.at(x, y);
  return sum / static_cast<double>(roi.pixelCount());
}

// The spread (sample standard deviation) of the cells' means, relative to their mean.
double nonUniformity(const FloatImage& luminance, const Roi& roi) {
  const int cells = std::min({kUniformityCells, roi.width, roi.height});
  std::vector<double> means;
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const Roi cell{.x = roi.x + i * roi.width / cells,
                     .y = roi.y + j * roi.height / cells,
                     .width = (i + 1) * roi.width / cells - i * roi.width / cells,
                     .height = (j + 1) * roi.height / cells - j * roi.height / cells};
      means.push_back(meanOver(luminance, cell));
    }
  }
  if (means.size() < 2) return 0;
  const double mean = std::accumulate(means.begin(), means.end(), 0.0) / means.size();
  double sq = 0;
  for (double m : means) sq += (m - mean) * (m - mean);
  return std::sqrt(sq / static_cast<double>(means.size() - 1)) / mean;
}

// The merge's relative uncertainty of the region's mean (pixel noise independent).
double noiseOfMean(const MergedImage& merged, const Roi& roi) {
  double variance = 0, sum = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const double l = merged.luminance_cd_m2.at(x, y);
      const double u = merged.relative_uncertainty.at(x, y) * l;
      variance += u * u;
      sum += l;
    }
  }
  return std::sqrt(variance) / sum;
}

LuminanceUncertainty readingUncertainty(const LuminanceReference& reference, double& mean) {
  const std::vector<double>& r = reference.readings_cd_m2;
  mean = std::accumulate(r.begin(), r.end(), 0.0) / static_cast<double>(r.size());
  LuminanceUncertainty u;
  u.meter = reference.meter_accuracy_percent / 100.0 / std::sqrt(3.0);
  if (r.size() > 1) {
    double sq = 0;
    for (double v : r) sq += (v - mean) * (v - mean);
    const double sd = std::sqrt(sq / static_cast<double>(r.size() - 1));
    u.readings = sd / std::sqrt(static_cast<double>(r.size())) / mean;
  }
  return u;
}

}  // namespace

double LuminanceUncertainty::combined() const {
  return std::sqrt(meter * meter + readings * readings + non_uniformity * non_uniformity +
                   noise * noise);
}

Result<LuminanceCalibration> calibrateLuminance(std::vector<InputFrame> frames,
                                                const Calibration& calibration,
                                                const FloatImage* flat_field, const Roi& roi,
                                                const LuminanceReference& reference) {
  GLARECAM_CHECK(reference.validate());
  if (frames.empty()) return badInput("calibrate luminance: no frames");
  GLARECAM_CHECK(
      checkRoi(roi, frames.front().frame.width(), frames.front().frame.height(), "--roi"));
  Calibration unit = calibration;
  unit.luminance_factor = 1.0;
  const std::vector<FrameRadiometry> radiometry = frameRadiometry(specsOf(frames), unit);
  // The merge takes the pixels as one block: moved there, each frame is still held once.
  std::vector<RawFrame> pixels;
  std::vector<int> bit_depths;
  for (InputFrame& frame : frames) {
    pixels.push_back(std::move(frame.frame));
    bit_depths.push_back(frame.bit_depth);
  }
  MergedImage merged;
  GLARECAM_ASSIGN(merged, merge({.frames = pixels,
                                 .radiometry = radiometry,
                                 .black_level_dn = unit.black_level_dn,
                                 .saturation_dn = unit.saturation_dn,
                                 .flat_field = flat_field,
                                 .bit_depths = bit_depths}));
  GLARECAM_CHECK(checkMeasured(merged, roi));
  LuminanceCalibration result;
  result.roi = roi;
  result.relative = readingUncertainty(reference, result.reference_cd_m2);
  result.relative_mean = meanOver(merged.luminance_cd_m2, roi);
  result.relative.non_uniformity = nonUniformity(merged.luminance_cd_m2, roi);
  result.relative.noise = noiseOfMean(merged, roi);
  result.luminance_factor = result.reference_cd_m2 / result.relative_mean;
  result.luminance_factor_u = result.luminance_factor * result.relative.combined();
  return result;
}

nlohmann::json luminanceValues(const LuminanceCalibration& luminance,
                               std::optional<double> reference_f_number) {
  nlohmann::json values = {
      {"luminance_factor", luminance.luminance_factor},
      {"luminance_factor_u", luminance.luminance_factor_u},
      {"luminance",
       {{"reference_cd_m2", luminance.reference_cd_m2},
        {"roi", {luminance.roi.x, luminance.roi.y, luminance.roi.width, luminance.roi.height}},
        {"relative_uncertainty",
         {{"meter", luminance.relative.meter},
          {"readings", luminance.relative.readings},
          {"non_uniformity", luminance.relative.non_uniformity},
          {"noise", luminance.relative.noise},
          {"combined", luminance.relative.combined()}}}}}};
  if (reference_f_number) values["reference_f_number"] = *reference_f_number;
  return values;
}

}  // namespace glarecam::calibration
