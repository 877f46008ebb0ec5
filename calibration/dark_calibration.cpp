#include "calibration/dark_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "calibration/frame_statistics.h"

namespace glarecam::calibration {
namespace {

std::vector<const RawFrame*> framesOf(std::span<const InputFrame> frames,
                                      const ExposureGroup& group) {
  std::vector<const RawFrame*> selected;
  for (std::size_t i : group.frames) selected.push_back(&frames[i].frame);
  return selected;
}

// The temporal noise of one frame, from the differences of consecutive frames: the fixed
// pattern cancels, and var(a - b) = 2 var(noise).
std::optional<double> temporalNoise(std::span<const InputFrame> frames,
                                    const ExposureGroup& group) {
  if (group.frames.size() < 2) return std::nullopt;
  const RawFrame& first = frames[group.frames.front()].frame;
  const Roi all{.x = 0, .y = 0, .width = first.width(), .height = first.height()};
  double variance = 0;
  for (std::size_t i = 1; i < group.frames.size(); ++i)
    variance +=
        differenceStats(frames[group.frames[i - 1]].frame, frames[group.frames[i]].frame, all)
            .variance_dn2 /
        2;
  return std::sqrt(variance / static_cast<double>(group.frames.size() - 1));
}

// Every frame is dark: its values spread little across the image, and its median is not far
// above the darkest frame's (light leaking around a cap raises the median, a lit scene spreads).
Status checkNoLight(std::span<const InputFrame> frames) {
  std::vector<RobustSpread> spreads;
  for (const InputFrame& frame : frames) {
    const RawFrame* one = &frame.frame;
    spreads.push_back(robustSpread(meanFrame(std::span(&one, 1))));
  }
  const double darkest = std::ranges::min(spreads, {}, &RobustSpread::median).median;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (spreads[i].sigma > kMaxDarkSpreadDn || spreads[i].median > darkest + kLightLeakDn) {
      return badInput(fmt::format(
          "{}: not a dark frame (median {:.0f} DN, spread {:.0f} DN across the image; the "
          "darkest frame's median is {:.0f} DN): cap the lens or close the shutter",
          frames[i].name, spreads[i].median, spreads[i].sigma, darkest));
    }
  }
  return {};
}

// The least-squares slope of the levels' medians over exposure, in DN/µs (0 with one exposure).
double darkCurrent(const std::vector<DarkLevel>& levels) {
  if (levels.size() < 2) return 0;
  double mean_t = 0, mean_dn = 0;
  for (const DarkLevel& level : levels) {
    mean_t += level.exposure_us / static_cast<double>(levels.size());
    mean_dn += level.median_dn / static_cast<double>(levels.size());
  }
  double covariance = 0, variance = 0;
  for (const DarkLevel& level : levels) {
    covariance += (level.exposure_us - mean_t) * (level.median_dn - mean_dn);
    variance += (level.exposure_us - mean_t) * (level.exposure_us - mean_t);
  }
  return variance > 0 ? covariance / variance : 0;
}

}  // namespace

Result<DarkCalibration> calibrateDark(std::span<const InputFrame> frames) {
  if (frames.size() < kMinDarkFrames) {
    return badInput(fmt::format("calibrate dark: {} frame(s); needs at least {} dark frames",
                                frames.size(), kMinDarkFrames));
  }
  GLARECAM_CHECK(checkNoLight(frames));
  const std::vector<ExposureGroup> groups = groupByExposure(specsOf(frames));
  GLARECAM_CHECK(checkOneGain(groups, "dark"));
  DarkCalibration dark;
  for (const ExposureGroup& group : groups) {
    FloatImage mean = meanFrame(framesOf(frames, group));
    dark.levels.push_back({.exposure_us = group.exposure_us,
                           .frames = group.frames.size(),
                           .median_dn = robustSpread(mean).median,
                           .temporal_noise_dn = temporalNoise(frames, group)});
    dark.dark_frame_dn = std::move(mean);  // the longest exposure's (the last group) stays
  }
  dark.black_level_dn = dark.levels.front().median_dn;

  dark.dark_frame_exposure_us = groups.back().exposure_us;
  dark.dark_frame_gain_db = groups.back().gain_db;
  dark.dark_current_dn_per_us = darkCurrent(dark.levels);
  const RobustSpread spread = robustSpread(dark.dark_frame_dn);
  if (const auto noise = dark.levels.back().temporal_noise_dn) {
    dark.dark_frame_noise_dn = *noise / std::sqrt(static_cast<double>(dark.levels.back().frames));
    dark.fixed_pattern_dn = std::sqrt(std::max(
        0.0, spread.sigma * spread.sigma - dark.dark_frame_noise_dn * dark.dark_frame_noise_dn));
  }
  dark.hot_threshold_dn = spread.median + std::max(kHotPixelSigmas * spread.sigma, kMinHotExcessDn);
  dark.hot_pixels = ByteImage(dark.dark_frame_dn.width(), dark.dark_frame_dn.height());
  for (std::size_t i = 0; i < dark.dark_frame_dn.pixelCount(); ++i) {
    const bool hot = dark.dark_frame_dn.data()[i] > dark.hot_threshold_dn;
    dark.hot_pixels.data()[i] = hot ? 255 : 0;
    dark.hot_pixel_count += hot;
  }
  return dark;
}

std::optional<std::string> darkFrameNoiseWarning(const DarkCalibration& dark) {
  const DarkLevel& longest = dark.levels.back();
  if (!longest.temporal_noise_dn || !(dark.dark_frame_noise_dn > dark.fixed_pattern_dn))
    return std::nullopt;
  // Frames for the dark frame's noise to fall to the fixed pattern: (sigma_t / fixed pattern)².
  const double needed =
      dark.fixed_pattern_dn > 0
          ? std::ceil(std::pow(*longest.temporal_noise_dn / dark.fixed_pattern_dn, 2))
          : std::numeric_limits<double>::infinity();
  return fmt::format(
      "the dark frame's own noise ({:.2f} DN: {:.2f} DN over the square root of {} frames) exceeds "
      "the fixed pattern it removes ({:.2f} DN): subtracting it adds noise to every stack; {}",
      dark.dark_frame_noise_dn, *longest.temporal_noise_dn, longest.frames, dark.fixed_pattern_dn,
      std::isfinite(needed) && needed <= kMaxUsefulDarkFrames
          ? fmt::format("capture {:.0f} or more frames at the longest exposure", needed)
          : std::string("the fixed pattern is too small to be worth removing (subtracting the dark "
                        "frame only adds noise); its hot pixels are masked all the same"));
}

nlohmann::json darkValues(const DarkCalibration& dark, const std::string& dark_frame_file,
                          const std::string& hot_pixels_file) {
  nlohmann::json levels = nlohmann::json::array();
  for (const DarkLevel& level : dark.levels) {
    nlohmann::json entry = {{"exposure_us", level.exposure_us},
                            {"frames", level.frames},
                            {"median_dn", level.median_dn}};
    if (level.temporal_noise_dn) entry["temporal_noise_dn"] = *level.temporal_noise_dn;
    levels.push_back(std::move(entry));
  }
  return {{"black_level_dn", dark.black_level_dn},
          {"dark_frame", dark_frame_file},
          {"dark_frame_exposure_us", dark.dark_frame_exposure_us},
          {"dark_frame_gain_db", dark.dark_frame_gain_db},
          {"dark_current_dn_per_us", dark.dark_current_dn_per_us},
          {"hot_pixels", hot_pixels_file},
          {"dark",
           {{"hot_pixel_count", dark.hot_pixel_count},
            {"fixed_pattern_dn", dark.fixed_pattern_dn},
            {"dark_frame_noise_dn", dark.dark_frame_noise_dn},
            {"hot_threshold_dn", dark.hot_threshold_dn},
            {"levels", levels}}}};
}

}  // namespace glarecam::calibration
