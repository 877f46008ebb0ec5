// `glarecam calibrate luminance`: the absolute scale K (cd/m² per DN/µs at the reference
// f-number). A stack of a reference surface whose luminance a meter measured is merged with
// K = 1, so each pixel holds L / K; the mean over the region the meter saw gives
// K = L_ref / mean. The standard uncertainty of K combines, in quadrature (GUM, uncorrelated):
// the meter's accuracy (a ± bound read as a rectangular distribution), the scatter of several
// readings, the surface's non-uniformity over the region (where in it the meter's spot fell is
// unknown), and the merge's own noise. The same measurement on an in-scene reference patch of a
// field stack checks an existing K for drift.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "calibration/frame_statistics.h"
#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

// Spot luminance meters of the class used for this (Konica Minolta LS-150/160) state ±2 % for
// illuminant A.
inline constexpr double kDefaultMeterAccuracyPercent = 2.0;
// The region is split into this many cells a side; the spread of their means is the
// non-uniformity (cells average the pixel noise away).
inline constexpr int kUniformityCells = 4;

struct LuminanceReference {
  std::vector<double> readings_cd_m2;  // one or more meter readings of the surface
  double meter_accuracy_percent = kDefaultMeterAccuracyPercent;
  Status validate() const;  // readings positive and finite, accuracy in [0, 100) %
};

struct LuminanceUncertainty {  // relative standard uncertainties
  double meter = 0, readings = 0, non_uniformity = 0, noise = 0;
  double combined() const;
};

struct LuminanceCalibration {
  double luminance_factor = 0;    // K
  double luminance_factor_u = 0;  // its standard uncertainty (absolute)
  LuminanceUncertainty relative;
  double reference_cd_m2 = 0;  // mean of the readings
  double relative_mean = 0;    // the region's mean with K = 1
  Roi roi;
};

// `calibration` gives black level, saturation, noise, reference f-number and flat field (its
// luminance_factor is ignored); `flat_field` may be null. The frames are moved in: the merge
// takes their pixels as one block.
Result<LuminanceCalibration> calibrateLuminance(std::vector<InputFrame> frames,
                                                const Calibration& calibration,
                                                const FloatImage* flat_field, const Roi& roi,
                                                const LuminanceReference& reference);

nlohmann::json luminanceValues(const LuminanceCalibration& luminance,
                               std::optional<double> reference_f_number);

}  // namespace glarecam::calibration
