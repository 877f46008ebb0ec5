// The libcamera backend's pure logic, free of libcamera so it is unit-tested without a camera:
//  - BracketMatcher: which bracket step a completed frame fills, decided by the exposure and gain
//    in the frame's metadata and never by queue order (a sensor applies controls a few frames
//    late, so the first frames after a change still carry the old exposure). Frames that fill no
//    step are discarded and counted against the step they were queued for, up to a bound.
//  - gain conversions: glarecam speaks dB, libcamera's AnalogueGain is a linear factor;
//  - the runtime version check: only libcamera versions we tested are accepted;
//  - raw layouts libcamera delivers (8-bit, 16-bit little-endian containers, MIPI CSI-2 packed
//    10/12-bit) parsed from libcamera's format names and unpacked to uint16 frames.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "capture/camera.h"
#include "core/error.h"
#include "core/image.h"

namespace glarecam::capture::libcam {

// ---- gain ----------------------------------------------------------------------------------
// Amplitude decibels: linear = 10^(dB/20). gainLinearToDb needs gain_linear > 0.
double gainDbToLinear(double gain_db);
double gainLinearToDb(double gain_linear);

// ---- version -------------------------------------------------------------------------------
struct LibcameraVersion {
  int major = 0;
  int minor = 0;
  int patch = 0;
  bool operator==(const LibcameraVersion&) const = default;
  std::string toString() const;  // "0.0.3"
};

// Versions this backend was run against. Debian bookworm's libcamera0.0.3 reports "v0.0.3".
inline constexpr std::array kTestedLibcameraVersions{LibcameraVersion{0, 0, 3}};

// Parses what CameraManager::version() reports: "0.0.3", "v0.0.3", "v0.0.3+65-1a2b3c4d" (a git
// build on top of the 0.0.3 tag), "0.0.3-6". Anything else: std::nullopt.
std::optional<LibcameraVersion> parseLibcameraVersion(std::string_view reported);
// Ok when `reported` parses to a tested version; otherwise a hardware error naming the reported
// version and the tested list.
Status checkLibcameraVersion(std::string_view reported);

// ---- matching frames to bracket steps ------------------------------------------------------
// A frame's exposure matches a step when |applied − requested| ≤ max(exposure_rounding_us,
// exposure_relative × requested): sensors round exposures to whole lines, which the absolute term
// covers, and the relative term covers long exposures. Its gain matches when it is within
// gain_tolerance_db of the requested gain or when the frame reports no gain. A frame that matches
// several unfilled steps fills the nearest one (in log ratio), the step it was queued for first.
struct MatchRule {
  double exposure_rounding_us = 1.0;
  double exposure_relative = 0.01;
  // Analogue gain codes are quantised: with a gain of 256 / (256 − code) (IMX219), one code at
  // 16× is about 0.5 dB, so 1 dB accepts the nearest code and still tells 6 dB steps apart.
  double gain_tolerance_db = 1.0;
  bool exposureMatches(double requested_us, double applied_us) const;
  bool gainMatches(double requested_db, std::optional<double> applied_db) const;
};

// The metadata of one completed frame, as the backend read it.
struct FrameMeta {
  std::optional<double> exposure_us;  // libcamera ExposureTime; a frame without it is an error
  std::optional<double> gain_db;      // from AnalogueGain, when the pipeline reports it
  std::uint32_t sequence = 0;         // the sensor's frame counter, for messages
};

// Tracks one bracket: which steps are filled, how many requests are in flight per step and how
// many frames each step discarded. The backend queues a request with the controls of
// nextStep(), reports each completion with the step it was queued for, and stops when
// complete(). A step that discards more than max_retries_per_step frames fails the bracket.
class BracketMatcher {
 public:
  BracketMatcher(std::vector<ExposureRequest> steps, MatchRule rule, int max_retries_per_step);

  std::size_t size() const { return steps_.size(); }
  const ExposureRequest& step(std::size_t index) const { return steps_[index]; }
  bool complete() const;
  bool filled(std::size_t index) const { return state_[index].filled; }
  int retries(std::size_t index) const { return state_[index].retries; }

  // The first unfilled step with no request in flight: what to queue next, if anything.
  std::optional<std::size_t> nextStep() const;
  void onQueued(std::size_t queued_for);
  // A frame completed for a request queued for `queued_for`: the step it fills, or std::nullopt
  // when it is stale (discarded and counted). Fails when the metadata has no exposure or the
  // charged step ran out of retries.
  Result<std::optional<std::size_t>> onFrame(std::size_t queued_for, const FrameMeta& meta);
  // A request queued for `queued_for` was cancelled or its buffer failed: counted as a retry.
  Status onFailure(std::size_t queued_for, std::string_view why);

 private:
  struct StepState {
    bool filled = false;
    int in_flight = 0;
    int retries = 0;
  };
  std::optional<std::size_t> bestMatch(std::size_t queued_for, const FrameMeta& meta) const;
  Status chargeRetry(std::size_t queued_for, const std::string& what);
  std::string describeStep(std::size_t index) const;

  std::vector<ExposureRequest> steps_;
  std::vector<StepState> state_;
  MatchRule rule_;
  int max_retries_per_step_;
};

// ---- raw layouts ---------------------------------------------------------------------------
enum class Packing {
  k8Bit,            // one byte per pixel
  kLittleEndian16,  // one little-endian uint16 per pixel, value in the low depth_bits bits
  kCsi2Packed,      // MIPI CSI-2: 10-bit 4 pixels in 5 bytes, 12-bit 2 pixels in 3 bytes
};

struct RawLayout {
  Packing packing = Packing::kLittleEndian16;
  int depth_bits = 16;
  std::string bayer_order;  // "RGGB", "GRBG", "GBRG", "BGGR"; empty for mono
  bool mono() const { return bayer_order.empty(); }
  // What SensorFormat records: the GenICam name of the unpacked values ("Mono12", "BayerRG10").
  std::string genicamName() const;
  // Higher is better: deeper first, mono before Bayer at equal depth.
  int preference() const { return depth_bits * 2 + (mono() ? 1 : 0); }
};

// From a libcamera PixelFormat name: "R8", "R10", "R10_CSI2P", "SRGGB12", "SBGGR12_CSI2P",
// "SGRBG16". Layouts this backend cannot unpack (IPU3 packing, 14-bit packed, YUV, RGB):
// std::nullopt.
std::optional<RawLayout> parseRawLayout(std::string_view libcamera_name);

// Bytes one row of `width` pixels occupies before padding.
std::size_t packedRowBytes(const RawLayout& layout, int width);

// Unpacks a frame of `height` rows, `stride_bytes` apart, into uint16 values (0..2^depth − 1).
// Fails when the buffer is too small for the rows or the stride is shorter than a row.
Result<RawFrame> unpackRaw(std::span<const std::uint8_t> bytes, int width, int height,
                           std::size_t stride_bytes, const RawLayout& layout);

}  // namespace glarecam::capture::libcam
