#include "calibration/flat_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "calibration/frame_statistics.h"
#include "calibration/radiometry.h"

namespace glarecam::calibration {
namespace {

Status checkFrame(const RawFrame& frame, const std::string& name, const SensorLevels& levels) {
  std::size_t saturated = 0;
  double sum = 0;
  for (std::size_t i = 0; i < frame.pixelCount(); ++i) {
    saturated += frame.data()[i] >= levels.saturation_dn;
    sum += frame.data()[i];
  }
  if (saturated > 0) {
    return badInput(
        fmt::format("{}: {} pixels at or above saturation_dn {:g}: a flat frame must not saturate; "
                    "shorten the exposure",
                    name, saturated, levels.saturation_dn));
  }
  const double signal = sum / static_cast<double>(frame.pixelCount()) - levels.black_level_dn;
  const double range = levels.saturation_dn - levels.black_level_dn;
  if (signal < kMinFlatSignalFraction * range) {
    return badInput(fmt::format(
        "{}: mean signal {:.0f} DN above black is under {:g} % of the range ({:.0f} DN): too "
        "dark for a flat; lengthen the exposure",
        name, signal, 100 * kMinFlatSignalFraction, range));
  }
  return {};
}

}  // namespace

Result<FlatCalibration> calibrateFlat(std::span<const InputFrame> frames,
                                      const SensorLevels& levels, double principal_x,
                                      double principal_y) {
  if (frames.empty()) return badInput("calibrate flat: no frames");
  const int width = frames.front().frame.width(), height = frames.front().frame.height();
  if (principal_x < 0 || principal_y < 0 || principal_x > width - 1 || principal_y > height - 1) {
    return badInput(
        fmt::format("calibrate flat: principal point ({:g}, {:g}) is outside the "
                    "{}x{} frames",
                    principal_x, principal_y, width, height));
  }
  // Sum of (DN - black) / exposure-and-gain: frames at different settings add up in one unit.
  std::vector<double> sum(frames.front().frame.pixelCount(), 0.0);
  double signal_sum = 0;
  for (const InputFrame& frame : frames) {
    GLARECAM_CHECK(checkFrame(frame.frame, frame.name, levels));
    const double scale = 1.0 / (frame.spec.exposure_us * linearGain(frame.spec.gain_db));
    const std::uint16_t* pixels = frame.frame.data();
    double frame_sum = 0;
    for (std::size_t i = 0; i < sum.size(); ++i) {
      const double signal = pixels[i] - levels.black_level_dn;
      sum[i] += signal * scale;
      frame_sum += signal;
    }
    signal_sum += frame_sum / static_cast<double>(sum.size());
  }
  FlatCalibration flat;
  flat.frames = frames.size();
  flat.mean_signal_dn = signal_sum / static_cast<double>(frames.size());
  flat.principal_x = principal_x;
  flat.principal_y = principal_y;
  flat.flat_field = FloatImage(width, height);
  for (std::size_t i = 0; i < sum.size(); ++i)
    flat.flat_field.data()[i] = static_cast<float>(sum[i]);
  const double centre =
      windowMean(flat.flat_field, principal_x, principal_y, kFlatNormalisationWindowPx);
  if (!(centre > 0)) return badInput("calibrate flat: no signal at the principal point");
  float* field = flat.flat_field.data();
  std::transform(field, field + sum.size(), field,
                 [centre](float v) { return static_cast<float>(v / centre); });
  const auto [low, high] = std::minmax_element(field, field + sum.size());
  flat.min_value = *low;
  flat.max_value = *high;
  if (flat.min_value <= 0) {
    return badInput(fmt::format(
        "calibrate flat: the field reaches {:.3g} (no light at some pixels): the source does "
        "not cover the whole image",
        flat.min_value));
  }
  return flat;
}

nlohmann::json flatValues(const FlatCalibration& flat, const std::string& flat_file) {
  return {{"flat_field", flat_file},
          {"flat",
           {{"frames", flat.frames},
            {"mean_signal_dn", flat.mean_signal_dn},
            {"normalised_at", {flat.principal_x, flat.principal_y}},
            {"min", flat.min_value},
            {"max", flat.max_value}}}};
}

}  // namespace glarecam::calibration
