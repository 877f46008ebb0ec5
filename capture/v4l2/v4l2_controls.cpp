#include "capture/v4l2/v4l2_controls.h"

#include <linux/videodev2.h>

#include <algorithm>
#include <cmath>

namespace glarecam::capture {

static_assert(kExposureAutoManual == V4L2_EXPOSURE_MANUAL);

namespace {

Result<bool> hasControl(V4l2Device& device, V4l2Control control) {
  std::optional<V4l2ControlRange> range;
  GLARECAM_ASSIGN(range, device.queryControl(control));
  return range.has_value();
}

Result<std::optional<V4l2GainControl>> queryGain(V4l2Device& device) {
  for (const auto control : {V4l2Control::kAnalogueGain, V4l2Control::kGain}) {
    std::optional<V4l2ControlRange> range;
    GLARECAM_ASSIGN(range, device.queryControl(control));
    if (range) return V4l2GainControl{control, *range};
  }
  return std::nullopt;
}

// Linear gain codes need a positive unity code (see the header).
bool gainIsLinear(const V4l2GainControl& gain) { return gain.range.min > 0; }

std::int64_t valueOf(const std::vector<V4l2ControlValue>& values, V4l2Control control) {
  const auto found = std::ranges::find(values, control, &V4l2ControlValue::control);
  return found == values.end() ? 0 : found->value;
}

}  // namespace

Result<V4l2ControlSet> queryControlSet(V4l2Device& device) {
  std::optional<V4l2ControlRange> exposure;
  GLARECAM_ASSIGN(exposure, device.queryControl(V4l2Control::kExposureAbsolute));
  if (!exposure) {
    return hardwareError(
        "no exposure_absolute control (V4L2_CID_EXPOSURE_ABSOLUTE): "
        "the exposure cannot be set");
  }
  V4l2ControlSet controls;
  controls.exposure = *exposure;
  GLARECAM_ASSIGN(controls.has_exposure_auto, hasControl(device, V4l2Control::kExposureAuto));
  GLARECAM_ASSIGN(controls.has_auto_gain, hasControl(device, V4l2Control::kAutoGain));
  GLARECAM_ASSIGN(controls.gain, queryGain(device));
  return controls;
}

std::int64_t snapToControl(double target, const V4l2ControlRange& range) {
  const auto step = std::max<std::int64_t>(1, range.step);
  const double clamped =
      std::clamp(target, static_cast<double>(range.min), static_cast<double>(range.max));
  std::int64_t code =
      range.min + static_cast<std::int64_t>(std::llround(
                      (clamped - static_cast<double>(range.min)) / static_cast<double>(step))) *
                      step;
  if (code > range.max) code -= step;  // max is not on the grid: the grid point below it
  return std::max(code, range.min);
}

ExposureSetting exposureSetting(double exposure_us, const V4l2ControlRange& range) {
  auto code = snapToControl(exposure_us / kExposureAbsoluteUnitUs, range);
  if (code < 1) {  // 0 would be no exposure at all: the smallest positive grid point instead
    const auto step = std::max<std::int64_t>(1, range.step);
    const auto positive = range.min + (1 - range.min + step - 1) / step * step;
    if (positive <= range.max) code = positive;
  }
  return {code, exposureUsFromCode(code)};
}

double exposureUsFromCode(std::int64_t code) {
  return static_cast<double>(code) * kExposureAbsoluteUnitUs;
}

GainSetting gainSetting(double gain_db, const V4l2GainControl& gain) {
  if (!gainIsLinear(gain)) return {gain.range.min, 0.0};
  const double target = static_cast<double>(gain.range.min) * std::pow(10.0, gain_db / 20.0);
  const auto code = snapToControl(target, gain.range);
  return {code, gainDbFromCode(code, gain)};
}

double gainDbFromCode(std::int64_t code, const V4l2GainControl& gain) {
  if (!gainIsLinear(gain) || code <= 0) return 0.0;
  return 20.0 * std::log10(static_cast<double>(code) / static_cast<double>(gain.range.min));
}

CameraLimits limitsOf(const V4l2ControlSet& controls) {
  CameraLimits limits;
  limits.min_exposure_us = exposureSetting(0.0, controls.exposure).exposure_us;
  limits.max_exposure_us = exposureUsFromCode(
      snapToControl(static_cast<double>(controls.exposure.max), controls.exposure));
  limits.exposure_step_us = exposureUsFromCode(std::max<std::int64_t>(1, controls.exposure.step));
  if (controls.gain) {
    limits.max_gain_db = gainDbFromCode(
        snapToControl(static_cast<double>(controls.gain->range.max), controls.gain->range),
        *controls.gain);
  }
  return limits;
}

ControlWrite controlWrite(const V4l2ControlSet& controls, const ExposureRequest& request) {
  ControlWrite write;
  write.exposure = exposureSetting(request.exposure_us, controls.exposure);
  if (controls.has_exposure_auto) {
    write.values.push_back({V4l2Control::kExposureAuto, kExposureAutoManual});
  }
  if (controls.has_auto_gain) write.values.push_back({V4l2Control::kAutoGain, 0});
  write.values.push_back({V4l2Control::kExposureAbsolute, write.exposure.code});
  if (controls.gain) {
    write.gain = gainSetting(request.gain_db, *controls.gain);
    write.values.push_back({controls.gain->control, write.gain.code});
  }
  return write;
}

std::vector<V4l2Control> readBackControls(const V4l2ControlSet& controls) {
  std::vector<V4l2Control> wanted{V4l2Control::kExposureAbsolute};
  if (controls.gain) wanted.push_back(controls.gain->control);
  return wanted;
}

Result<AppliedControls> appliedControls(const V4l2ControlSet& controls,
                                        const std::vector<V4l2ControlValue>& read_back) {
  const auto exposure_code = valueOf(read_back, V4l2Control::kExposureAbsolute);
  if (exposure_code <= 0) {
    return hardwareError("exposure_absolute reads back as " + std::to_string(exposure_code));
  }
  AppliedControls applied{exposureUsFromCode(exposure_code), 0.0};
  if (controls.gain) {
    applied.gain_db = gainDbFromCode(valueOf(read_back, controls.gain->control), *controls.gain);
  }
  return applied;
}

SettleGate settleGate(std::uint32_t write_sequence, int settle_frames) {
  return {write_sequence + static_cast<std::uint32_t>(std::max(0, settle_frames))};
}

}  // namespace glarecam::capture
