#include "calibration/hdr_merge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <string>

#include "core/parallel.h"

namespace glarecam::calibration {
namespace {

// Per-frame constants of the kernel, in float: the loops below run on SIMD lanes.
struct FrameConstants {
  const RawFrame* frame;
  float scale;             // cd/m² per DN
  float min_signal_dn;     // under-exposure threshold above black
  float saturated_cd_m2;   // luminance at the saturation DN (lower bound when clipped)
  float shot_coefficient;  // var(L_i) = shot_coefficient * L + read_coefficient
  float read_coefficient;
};

// Frames sorted from the longest effective exposure (smallest scale) to the shortest, so the
// first valid estimate met for a pixel comes from the frame with the most signal.
std::vector<FrameConstants> frameConstants(const MergeInput& input) {
  std::vector<FrameConstants> constants;
  const double full_range_dn = input.saturation_dn - input.black_level_dn;
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    const FrameRadiometry& r = input.radiometry[i];
    constants.push_back({&input.frames[i], static_cast<float>(r.scale_cd_m2_per_dn),
                         static_cast<float>(r.min_signal_dn),
                         static_cast<float>(full_range_dn * r.scale_cd_m2_per_dn),
                         static_cast<float>(r.scale_cd_m2_per_dn * r.dn_per_electron),
                         static_cast<float>(r.scale_cd_m2_per_dn * r.scale_cd_m2_per_dn *
                                            r.read_noise_dn * r.read_noise_dn)});
  }
  std::stable_sort(constants.begin(), constants.end(),
                   [](const auto& a, const auto& b) { return a.scale < b.scale; });
  return constants;
}

// The per-pixel loops are compiled twice on x86-64, for the baseline and for AVX2 (a feature
// test; an "arch=" clone would match one CPU model only), and the loader picks the best the
// CPU has. Sanitizer builds skip it.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
#define GLARECAM_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define GLARECAM_SIMD_CLONES
#endif

// Pixels handled per step: the six float buffers of a segment (24 KiB) stay in L1.
constexpr int kSegmentPixels = 1024;

// Buffers of one worker for one segment of a row, allocated once per band.
struct SegmentBuffers {
  std::array<float, kSegmentPixels> reference, weight_sum, weighted_sum, valid_count, lower_bound,
      inverse_flat;
};

// One frame's contribution, frames taken from the longest exposure to the shortest. The
// first valid estimate met (the longest valid frame, the one with the most signal) becomes the
// pixel's reference luminance, at which every frame's noise variance is evaluated; each valid
// estimate is added with its inverse variance as weight. Saturated pixels raise the lower
// bound to the frame's saturation luminance.
GLARECAM_SIMD_CLONES void accumulateSegment(
    const std::uint16_t* __restrict dn, float* __restrict reference, float* __restrict weight_sum,
    float* __restrict weighted_sum, float* __restrict valid_count, float* __restrict lower,
    int count, float black, float saturation, const FrameConstants& frame) {
  const float min_signal = frame.min_signal_dn, scale = frame.scale, shot = frame.shot_coefficient;
  const float saturated_cd_m2 = frame.saturated_cd_m2;
  // The smallest normal float keeps 0/0 out of pixels with no reference and no read noise.
  const float read = frame.read_coefficient + std::numeric_limits<float>::min();
  for (int x = 0; x < count; ++x) {
    const float value = dn[x];
    const float signal = value - black;
    const float estimate = signal * scale;
    const bool saturated = value >= saturation;
    const bool valid = (value < saturation) & (signal >= min_signal);
    // Written as arithmetic, not a select: GCC turns "r[x] = c ? v : r[x]" into a masked store,
    // which is microcoded and slow on AMD cores.
    const float take = (valid & (reference[x] == 0.0f)) ? 1.0f : 0.0f;
    const float ref = reference[x] + take * (estimate - reference[x]);
    reference[x] = ref;
    const float weight = (valid ? 1.0f : 0.0f) / (shot * ref + read);  // inverse variance, or 0
    weight_sum[x] += weight;
    weighted_sum[x] += weight * estimate;
    valid_count[x] += valid ? 1.0f : 0.0f;
    lower[x] = std::max(lower[x], saturated ? saturated_cd_m2 : 0.0f);
  }
}

// Pass 3: luminance, relative uncertainty and flags, flat field applied once.
GLARECAM_SIMD_CLONES void finishSegment(const SegmentBuffers& b, int count, float upper_bound,
                                        float* __restrict luminance, float* __restrict relative,
                                        std::uint8_t* __restrict valid,
                                        std::uint8_t* __restrict bound) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int x = 0; x < count; ++x) {
    const bool measured = b.valid_count[x] > 0.0f;
    const bool saturated = b.lower_bound[x] > 0.0f;
    const float mean = b.weighted_sum[x] / b.weight_sum[x];
    const float unmeasured = saturated ? b.lower_bound[x] : upper_bound;
    luminance[x] = (measured ? mean : unmeasured) * b.inverse_flat[x];
    relative[x] = measured ? 1.0f / (std::sqrt(b.weight_sum[x]) * mean) : nan;
    valid[x] = static_cast<std::uint8_t>(b.valid_count[x]);
    // PixelBound: 0 measured, 1 lower bound (saturated), 2 upper bound (dark).
    const std::uint8_t unmeasured_flag = saturated ? 1 : 2;
    bound[x] = measured ? 0 : unmeasured_flag;
  }
}

class MergeKernel {
 public:
  MergeKernel(const MergeInput& input, MergedImage& output)
      : output_(output),
        frames_(frameConstants(input)),
        flat_(input.flat_field),
        black_(static_cast<float>(input.black_level_dn)),
        saturation_(static_cast<float>(input.saturation_dn)),
        upper_bound_(upperBound(frames_)) {}

  void runRows(int begin, int end) const {
    auto buffers = std::make_unique<SegmentBuffers>();
    const int width = output_.luminance_cd_m2.width();
    for (int y = begin; y < end; ++y) {
      for (int x0 = 0; x0 < width; x0 += kSegmentPixels)
        runSegment(y, x0, std::min(kSegmentPixels, width - x0), *buffers);
    }
  }

 private:
  // The darkest luminance the longest frame can still detect: the bound of all-dark pixels.
  static float upperBound(const std::vector<FrameConstants>& frames) {
    float bound = std::numeric_limits<float>::max();
    for (const auto& f : frames) bound = std::min(bound, f.min_signal_dn * f.scale);
    return bound;
  }

  void runSegment(int y, int x0, int count, SegmentBuffers& b) const {
    const auto n = static_cast<std::size_t>(count);
    std::fill_n(b.reference.begin(), n, 0.0f);
    std::fill_n(b.lower_bound.begin(), n, 0.0f);
    std::fill_n(b.weight_sum.begin(), n, 0.0f);
    std::fill_n(b.weighted_sum.begin(), n, 0.0f);
    std::fill_n(b.valid_count.begin(), n, 0.0f);
    for (const FrameConstants& f : frames_) {
      accumulateSegment(f.frame->row(y).data() + x0, b.reference.data(), b.weight_sum.data(),
                        b.weighted_sum.data(), b.valid_count.data(), b.lower_bound.data(), count,
                        black_, saturation_, f);
    }
    const float* flat = flat_ ? flat_->row(y).data() + x0 : nullptr;
    for (int x = 0; x < count; ++x)
      b.inverse_flat[static_cast<std::size_t>(x)] = flat ? 1.0f / flat[x] : 1.0f;
    finishSegment(b, count, upper_bound_, output_.luminance_cd_m2.row(y).data() + x0,
                  output_.relative_uncertainty.row(y).data() + x0,
                  output_.valid_frames.row(y).data() + x0, output_.bound.row(y).data() + x0);
  }

  MergedImage& output_;
  std::vector<FrameConstants> frames_;
  const FloatImage* flat_;
  float black_;
  float saturation_;
  float upper_bound_;
};

template <typename T>
void ensureSize(Image<T>& image, int width, int height) {
  if (!image.sameSize(width, height)) image = Image<T>(width, height);
}

bool finitePositive(double value) { return std::isfinite(value) && value > 0; }

}  // namespace

Status validate(const MergeInput& input) {
  if (input.frames.empty()) return badInput("merge: no frames");
  if (input.frames.size() != input.radiometry.size())
    return fail(ErrorCode::kInternal, "merge: one radiometry per frame needed");
  if (input.frames.size() > std::numeric_limits<std::uint8_t>::max())
    return badInput("merge: more than 255 frames");
  if (!(input.black_level_dn >= 0 && input.black_level_dn < input.saturation_dn &&
        std::isfinite(input.saturation_dn))) {
    return badInput("merge: black level must be below saturation");
  }
  const RawFrame& first = input.frames.front();
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    if (!input.frames[i].sameSize(first.width(), first.height()) || input.frames[i].empty()) {
      return badInput("merge: frame " + std::to_string(i) + " differs in size from frame 0");
    }
    const FrameRadiometry& r = input.radiometry[i];
    if (!finitePositive(r.scale_cd_m2_per_dn) || !finitePositive(r.dn_per_electron) ||
        !finitePositive(r.min_signal_dn) ||
        !(std::isfinite(r.read_noise_dn) && r.read_noise_dn >= 0)) {
      return badInput("merge: frame " + std::to_string(i) +
                      " has non-finite or non-positive radiometric constants");
    }
  }
  if (input.flat_field && !input.flat_field->sameSize(first.width(), first.height())) {
    return badInput("merge: flat field differs in size from the frames");
  }
  return {};
}

Status mergeInto(const MergeInput& input, const MergeOptions& options, MergedImage& output) {
  GLARECAM_CHECK(validate(input));
  const int width = input.frames.front().width();
  const int height = input.frames.front().height();
  ensureSize(output.luminance_cd_m2, width, height);
  ensureSize(output.relative_uncertainty, width, height);
  ensureSize(output.valid_frames, width, height);
  ensureSize(output.bound, width, height);
  const MergeKernel kernel(input, output);
  parallelRows(height, options.threads ? options.threads : defaultThreadCount(),
               [&](int begin, int end) { kernel.runRows(begin, end); });
  return {};
}

Result<MergedImage> merge(const MergeInput& input, const MergeOptions& options) {
  MergedImage output;
  GLARECAM_CHECK(mergeInto(input, options, output));
  return output;
}

}  // namespace glarecam::calibration
