// Auto-bracketing decisions, as pure logic on frame statistics (the bracketer drives a camera
// with them; tests drive them with the `sim:` camera):
//  1. meter: from a first frame, shorten (peak clipped) or lengthen (peak too dark) until the
//     brightest pixel sits inside the usable range, within the camera's exposure limits;
//  2. plan: the signal rates of that frame give the bracket (bracketing.h: the peak unsaturated
//     with margin in the shortest frame, the background at good SNR in the longest, steps of at
//     most a decade, at least six frames as in the paper);
//  3. check: if the peak is still clipped in the shortest captured frame, re-plan shorter.
// Every decision is recorded (AutoBracketLog) and goes into the manifest.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "capture/bracketing.h"
#include "capture/camera.h"
#include "core/error.h"
#include "core/image.h"

namespace glarecam::capture {

// A frame's levels in DN above black: a robust peak (ignoring the few brightest pixels, which
// may be hot pixels) and the background (5th percentile, the darkest part of the scene).
struct FrameLevels {
  double peak_dn = 0;
  double background_dn = 0;
  bool peak_clipped = false;  // the robust peak reached the saturation level
};

FrameLevels measureFrameLevels(const RawFrame& frame, double black_level_dn, double saturation_dn);

struct AutoBracketOptions {
  BracketOptions bracket;
  double first_metering_exposure_us = 1000.0;  // 1 ms: mid-range of machine-vision exposures
  int max_metering_frames = 8;       // per quantity: enough to cross 10 µs … 2 s in decades
  int max_rebrackets = 3;            // bounded re-bracketing when the peak is still clipped
  double dark_peak_fraction = 0.05;  // a metering peak below 5 % of range is too dark to trust
  // The background is measured once it is above 2 % of the range (about 80 DN at 12 bits, 40×
  // a typical read noise): its rate then sets the longest exposure to within a few percent.
  double min_background_fraction = 0.02;
  Status validate() const;
};

// One metering frame: the exposure it was taken at and its levels.
struct MeteringFrame {
  double exposure_us = 0;
  FrameLevels levels;
};

// The next exposure for metering the peak, or nullopt when `frame` is usable: its peak is
// unclipped and bright enough, or the camera's limits leave nothing better.
std::optional<double> nextPeakMetering(const MeteringFrame& frame, double usable_range_dn,
                                       const CameraLimits& limits,
                                       const AutoBracketOptions& options);
// The same for the background, which a frame metered for the peak usually leaves in the noise.
std::optional<double> nextBackgroundMetering(const MeteringFrame& frame, double usable_range_dn,
                                             const CameraLimits& limits,
                                             const AutoBracketOptions& options);

// Signal rates in DN/µs. A clipped peak gives only a lower bound: the range over the exposure.
double peakRate(const MeteringFrame& frame, double usable_range_dn);
double backgroundRate(const MeteringFrame& frame);
// After the shortest frame of a bracket came back clipped: assume the peak a decade above the
// bound that frame gives.
double clippedPeakRate(double shortest_exposure_us, double usable_range_dn);

// The bracket for these rates within the camera's limits.
Result<BracketPlan> planForRates(double peak_dn_per_us, double background_dn_per_us,
                                 double usable_range_dn, const CameraLimits& limits,
                                 const AutoBracketOptions& options);

// What happened, for the manifest's capture.auto_bracket block.
struct AutoBracketLog {
  std::vector<MeteringFrame> metering;
  int rebrackets = 0;
  bool peak_clipped = false;             // still clipped after the last attempt
  bool background_underexposed = false;  // the longest allowed exposure leaves it dark
  nlohmann::json toJson() const;
};

}  // namespace glarecam::capture
