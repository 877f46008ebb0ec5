// How an ExposureRequest becomes V4L2 control values, and which frames to trust afterwards.
// Exposure: V4L2_CID_EXPOSURE_ABSOLUTE, "in 100 µs units" (V4L2 spec, camera control reference),
// rounded to the nearest code on the control's [min, max] grid of `step`; the applied µs is
// reported back. Auto exposure and auto gain are switched off in the same write.
// Gain: V4L2_CID_ANALOGUE_GAIN when present, else V4L2_CID_GAIN; the spec gives them no unit. We
// assume (1) 0 dB is the control's minimum code, the sensor's lowest gain, at which the camera is
// calibrated, and (2) codes are linear in gain above it: gain_db = 20·log10(code / min). Sensors
// with a non-linear code (imx219: 256 − 256/gain) or min = 0 (many UVC cameras) break (2); for
// those only 0 dB is exact, and a min of 0 offers 0 dB only. Bracket with exposure, not gain.
// Settling: a control written while streaming reaches the pixels a few frames later.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "capture/camera.h"
#include "capture/v4l2/v4l2_device.h"
#include "core/error.h"

namespace glarecam::capture {

// V4L2 spec: V4L2_CID_EXPOSURE_ABSOLUTE "in 100 µs units".
inline constexpr double kExposureAbsoluteUnitUs = 100.0;
// V4L2_EXPOSURE_MANUAL, the menu value of V4L2_CID_EXPOSURE_AUTO (<linux/v4l2-controls.h>).
inline constexpr std::int64_t kExposureAutoManual = 1;

// Frames to drop after a control write, counted from the frame in flight at the write (the one
// after the last dequeued). Sensors latch exposure at a frame start and apply it two frames
// after the write (libcamera's default "exposure delay" of 2 frames, src/ipa/rpi/cam_helper/
// cam_helper.cpp, also gain delay 2 for most sensors); our write is not synchronised to the
// frame start, so one frame more. UVC firmware varies: V4l2Options::settle_frames overrides.
inline constexpr int kDefaultSettleFrames = 3;

struct V4l2GainControl {
  V4l2Control control = V4l2Control::kAnalogueGain;
  V4l2ControlRange range;
};

// The controls a device offers for exposure and gain.
struct V4l2ControlSet {
  V4l2ControlRange exposure;  // V4L2_CID_EXPOSURE_ABSOLUTE: required
  bool has_exposure_auto = false;
  bool has_auto_gain = false;
  std::optional<V4l2GainControl> gain;  // analogue preferred over digital; none: fixed gain
};

// Queries the device; fails when it has no V4L2_CID_EXPOSURE_ABSOLUTE.
Result<V4l2ControlSet> queryControlSet(V4l2Device& device);

// The code nearest `target` on the grid min + k·step within [min, max].
std::int64_t snapToControl(double target, const V4l2ControlRange& range);

struct ExposureSetting {
  std::int64_t code = 0;   // V4L2_CID_EXPOSURE_ABSOLUTE value (100 µs units)
  double exposure_us = 0;  // what that code means
};
ExposureSetting exposureSetting(double exposure_us, const V4l2ControlRange& range);
double exposureUsFromCode(std::int64_t code);

struct GainSetting {
  std::int64_t code = 0;
  double gain_db = 0;
};
GainSetting gainSetting(double gain_db, const V4l2GainControl& gain);
double gainDbFromCode(std::int64_t code, const V4l2GainControl& gain);

CameraLimits limitsOf(const V4l2ControlSet& controls);

// One request's write, in order: exposure auto off, auto gain off, exposure, gain.
struct ControlWrite {
  std::vector<V4l2ControlValue> values;
  ExposureSetting exposure;
  GainSetting gain;  // 0 dB when the device has no gain control
};
ControlWrite controlWrite(const V4l2ControlSet& controls, const ExposureRequest& request);

// The controls to read back after a write, and the applied values they hold.
std::vector<V4l2Control> readBackControls(const V4l2ControlSet& controls);
struct AppliedControls {
  double exposure_us = 0;
  double gain_db = 0;
};
Result<AppliedControls> appliedControls(const V4l2ControlSet& controls,
                                        const std::vector<V4l2ControlValue>& read_back);

// Frames with sequence < write_sequence + settle_frames were (partly) exposed with the old
// controls. write_sequence is the sequence of the frame in flight when the controls were written.
struct SettleGate {
  std::uint32_t first_settled_sequence = 0;
  bool settled(std::uint32_t sequence) const { return sequence >= first_settled_sequence; }
};
SettleGate settleGate(std::uint32_t write_sequence, int settle_frames);

}  // namespace glarecam::capture
