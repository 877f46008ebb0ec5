#include "capture/auto_bracket.h"

#include <algorithm>
#include <cmath>

namespace glarecam::capture {
namespace {

// The robust peak skips this fraction of the brightest pixels (and at least one): a handful of
// hot pixels must not shorten the bracket, while a real glare peak covers far more pixels.
constexpr double kPeakIgnoredFraction = 1e-5;
constexpr double kBackgroundPercentile = 0.05;  // as the simulator's metering
// Factors between metering frames: a decade when clipped (a clipped peak says nothing about
// how bright it is); at most 100× longer at once when dark.
constexpr double kClippedMeteringFactor = 0.1;
constexpr double kMaxLengthenFactor = 100.0;
// A clipped shortest frame bounds the peak's rate from below only; assume it is a decade above.
constexpr double kClippedPeakRateFactor = 10.0;

BracketOptions withinLimits(const BracketOptions& options, const CameraLimits& limits) {
  BracketOptions bounded = options;
  bounded.min_exposure_us = std::max(options.min_exposure_us, limits.min_exposure_us);
  bounded.max_exposure_us = std::min(options.max_exposure_us, limits.max_exposure_us);
  bounded.exposure_step_us = std::max(options.exposure_step_us, limits.exposure_step_us);
  if (bounded.max_exposure_us < bounded.min_exposure_us)
    bounded.max_exposure_us = bounded.min_exposure_us;
  return bounded;
}

nlohmann::json levelsJson(const FrameLevels& levels) {
  return {{"peak_dn", levels.peak_dn},
          {"background_dn", levels.background_dn},
          {"peak_clipped", levels.peak_clipped}};
}

}  // namespace

FrameLevels measureFrameLevels(const RawFrame& frame, double black_level_dn, double saturation_dn) {
  std::vector<std::size_t> histogram(std::size_t{1} << 16, 0);
  const std::uint16_t* values = frame.data();
  for (std::size_t i = 0; i < frame.pixelCount(); ++i) ++histogram[values[i]];
  const auto ignored = std::max<std::size_t>(
      1, static_cast<std::size_t>(kPeakIgnoredFraction * static_cast<double>(frame.pixelCount())));
  const auto background_rank =
      static_cast<std::size_t>(kBackgroundPercentile * static_cast<double>(frame.pixelCount()));
  std::size_t peak_value = 0, background_value = 0, seen = 0;
  for (std::size_t value = histogram.size(); value-- > 0;) {
    seen += histogram[value];
    if (seen > ignored) {
      peak_value = value;
      break;
    }
  }
  seen = 0;
  for (std::size_t value = 0; value < histogram.size(); ++value) {
    seen += histogram[value];
    if (seen > background_rank) {
      background_value = value;
      break;
    }
  }
  FrameLevels levels;
  levels.peak_dn = std::max(0.0, static_cast<double>(peak_value) - black_level_dn);
  levels.background_dn = std::max(0.0, static_cast<double>(background_value) - black_level_dn);
  levels.peak_clipped = static_cast<double>(peak_value) >= saturation_dn;
  return levels;
}

Status AutoBracketOptions::validate() const {
  GLARECAM_CHECK(bracket.validate());
  if (!(first_metering_exposure_us > 0) || max_metering_frames < 1 || max_rebrackets < 0 ||
      !(dark_peak_fraction > 0 && dark_peak_fraction < bracket.peak_fraction) ||
      !(min_background_fraction > 0 && min_background_fraction < bracket.background_fraction)) {
    return badInput("auto-bracket: metering options out of range");
  }
  return {};
}

namespace {

// Moves `exposure_us` by `factor` within the limits; nullopt when a limit leaves no change.
std::optional<double> steppedExposure(double exposure_us, double factor, const CameraLimits& limits,
                                      const AutoBracketOptions& options) {
  const BracketOptions bounds = withinLimits(options.bracket, limits);
  const double next =
      std::clamp(exposure_us * factor, bounds.min_exposure_us, bounds.max_exposure_us);
  if (std::abs(next - exposure_us) < bounds.exposure_step_us) return std::nullopt;
  return next;
}

// The factor that brings `level_dn` to `target_dn`, at most kMaxLengthenFactor at once.
double lengthenFactor(double level_dn, double target_dn) {
  return std::min(kMaxLengthenFactor, target_dn / std::max(level_dn, 1.0));
}

}  // namespace

std::optional<double> nextPeakMetering(const MeteringFrame& frame, double usable_range_dn,
                                       const CameraLimits& limits,
                                       const AutoBracketOptions& options) {
  if (frame.levels.peak_clipped) {
    return steppedExposure(frame.exposure_us, kClippedMeteringFactor, limits, options);
  }
  if (frame.levels.peak_dn < options.dark_peak_fraction * usable_range_dn) {
    const double target = options.bracket.peak_fraction * usable_range_dn;
    return steppedExposure(frame.exposure_us, lengthenFactor(frame.levels.peak_dn, target), limits,
                           options);
  }
  return std::nullopt;
}

std::optional<double> nextBackgroundMetering(const MeteringFrame& frame, double usable_range_dn,
                                             const CameraLimits& limits,
                                             const AutoBracketOptions& options) {
  if (frame.levels.background_dn >= options.min_background_fraction * usable_range_dn) {
    return std::nullopt;
  }
  const double target = options.bracket.background_fraction * usable_range_dn;
  return steppedExposure(frame.exposure_us, lengthenFactor(frame.levels.background_dn, target),
                         limits, options);
}

double peakRate(const MeteringFrame& frame, double usable_range_dn) {
  const double peak_dn =
      frame.levels.peak_clipped ? usable_range_dn : std::max(frame.levels.peak_dn, 1.0);
  return peak_dn / frame.exposure_us;
}

double backgroundRate(const MeteringFrame& frame) {
  // A background below one DN is bounded by that.
  return std::max(frame.levels.background_dn, 1.0) / frame.exposure_us;
}

double clippedPeakRate(double shortest_exposure_us, double usable_range_dn) {
  return kClippedPeakRateFactor * usable_range_dn / shortest_exposure_us;
}

Result<BracketPlan> planForRates(double peak_dn_per_us, double background_dn_per_us,
                                 double usable_range_dn, const CameraLimits& limits,
                                 const AutoBracketOptions& options) {
  return planBracket(peak_dn_per_us, std::min(background_dn_per_us, peak_dn_per_us),
                     usable_range_dn, withinLimits(options.bracket, limits));
}

nlohmann::json AutoBracketLog::toJson() const {
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& step : metering) {
    auto entry = levelsJson(step.levels);
    entry["exposure_us"] = step.exposure_us;
    frames.push_back(std::move(entry));
  }
  return {{"metering", std::move(frames)},
          {"rebrackets", rebrackets},
          {"peak_clipped", peak_clipped},
          {"background_underexposed", background_underexposed}};
}

}  // namespace glarecam::capture
