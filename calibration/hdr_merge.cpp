#include "calibration/hdr_merge.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

#include "core/parallel.h"

namespace glarecam::calibration {
namespace {

// Per-frame constants of the kernel, in float: the loops below run on SIMD lanes.
struct FrameConstants {
  const RawFrame* frame;
  float scale;             // cd/m² per DN
  float saturated_cd_m2;   // luminance at the saturation DN (lower bound when clipped)
  float dark_cd_m2;        // luminance at the under-exposure threshold
  float exposure_weight;   // 1 / scale: the pilot's weight (inverse variance when shot-limited)
  float shot_coefficient;  // var(L_i) = shot_coefficient * L + read_coefficient
  float read_coefficient;
};

// Frames sorted from the longest effective exposure (smallest scale) to the shortest.
std::vector<FrameConstants> frameConstants(const MergeInput& input) {
  std::vector<FrameConstants> constants;
  const double full_range_dn = input.saturation_dn - input.black_level_dn;
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    const FrameRadiometry& r = input.radiometry[i];
    constants.push_back({&input.frames[i], static_cast<float>(r.scale_cd_m2_per_dn),
                         static_cast<float>(full_range_dn * r.scale_cd_m2_per_dn),
                         static_cast<float>(r.min_signal_dn * r.scale_cd_m2_per_dn),
                         static_cast<float>(1.0 / r.scale_cd_m2_per_dn),
                         static_cast<float>(r.scale_cd_m2_per_dn * r.dn_per_electron),
                         static_cast<float>(r.scale_cd_m2_per_dn * r.scale_cd_m2_per_dn *
                                            r.read_noise_dn * r.read_noise_dn)});
  }
  std::stable_sort(constants.begin(), constants.end(),
                   [](const auto& a, const auto& b) { return a.scale < b.scale; });
  return constants;
}

// The row loop is compiled twice on x86-64, for the baseline and for AVX2 (a feature test; an
// "arch=" clone would match one CPU model only), and the loader picks the best the CPU has.
// Sanitizer builds compile one plain kernel (ifunc resolvers run before the sanitizer runtime
// starts); the -O0 merge tests of the normal build run the clone the CPU selects.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
#define GLARECAM_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define GLARECAM_SIMD_CLONES
#endif

// Eight pixels at a time, in GCC's portable vector extensions (SSE2, AVX2 and NEON alike):
// each frame pixel is read once, every accumulator lives in registers, only outputs are stored.
constexpr int kLanes = 8;
using FloatLanes = float __attribute__((vector_size(kLanes * sizeof(float))));
using IntLanes = std::int32_t __attribute__((vector_size(kLanes * sizeof(std::int32_t))));
using WordLanes = std::uint16_t __attribute__((vector_size(kLanes * sizeof(std::uint16_t))));

// Always inlined: a 32-byte vector passed or returned by value through a real call would follow
// a different ABI in the baseline and the AVX2 clone (wrong numbers at -O0 otherwise).
template <typename Lanes, typename T>
[[gnu::always_inline]] inline Lanes loadLanes(const T* source) {
  Lanes lanes;
  std::memcpy(&lanes, source, sizeof lanes);
  return lanes;
}

template <typename Lanes, typename T>
[[gnu::always_inline]] inline void storeLanes(T* target, const Lanes& lanes) {
  std::memcpy(target, &lanes, sizeof lanes);
}

// Where one row's eight pixels come from and go to.
struct LanePointers {
  const std::uint16_t* const* frames;  // one row pointer per frame
  const float* inverse_flat;
  float* luminance;
  float* relative;
  float* valid;  // counts, flags and weight sums as floats, finished once per row: lane-wise
  float* bound;  // float-to-byte conversion and sqrt do not vectorise inside the lanes
  float* weight_sum;
};

struct KernelConstants {
  const FrameConstants* frames;  // from the longest effective exposure to the shortest
  int frame_count;
  float black, saturation, upper_bound;
};

// Frames are met from the longest effective exposure to the shortest: the first valid estimate
// (the one with the most signal) becomes the pixel's reference luminance, at which every
// frame's noise variance is evaluated, and each valid estimate is added with its inverse
// variance as weight. Saturated frames raise the lower bound to their saturation luminance.
// One pass over the frames: each valid estimate added with its weight. `valid_in(frame, value,
// estimate)` decides which frame pixels count, `weight_of(frame, valid)` weighs them. The
// callables must be always inlined too: a real call passing vectors would cross the AVX2
// clone's ABI.
struct LaneSums {
  FloatLanes weight_sum{}, weighted_sum{}, count{}, lower{};
};

template <typename Validity, typename Weight>
[[gnu::always_inline]] inline LaneSums sumFrames(const KernelConstants& k, const LanePointers& p,
                                                 int offset, Validity valid_in, Weight weight_of) {
  const FloatLanes zero{}, one = zero + 1.0f;
  LaneSums sums;
  for (int i = 0; i < k.frame_count; ++i) {
    const FrameConstants& f = k.frames[i];
    const FloatLanes value =
        __builtin_convertvector(loadLanes<WordLanes>(p.frames[i] + offset), FloatLanes);
    const FloatLanes estimate = (value - k.black) * f.scale;
    const IntLanes valid = valid_in(f, value, estimate);
    const FloatLanes weight = weight_of(f, valid);
    sums.weight_sum += weight;
    sums.weighted_sum += weight * estimate;
    sums.count += valid ? one : zero;
    const IntLanes saturated = value >= k.saturation;
    sums.lower =
        (saturated & (sums.lower < f.saturated_cd_m2)) ? zero + f.saturated_cd_m2 : sums.lower;
  }
  return sums;
}

// Two passes over the frames, values reloaded from L1:
//  1. pilot: a frame pixel counts when its own reading is below saturation and above the dark
//     threshold, weighted by its exposure (1 / scale: the inverse variance where shot noise
//     dominates, and independent of the readings, so unbiased and free of divisions);
//  2. final: a frame counts when the *pilot* predicts it within range: at least its dark
//     threshold and at least kSaturationMarginSigmas of its noise below its saturation. A frame
//     judged by its own reading keeps the readings noise pushed down and drops those it pushed
//     up, and reads low just below saturation (high just above the dark threshold); judged by
//     the pilot it is not truncated. Weights: inverse variances from the noise model at the
//     pilot.
// Pixels the pilot could not measure, or that no frame passes in pass 2, keep pass 1's answer.
[[gnu::always_inline]] inline void mergeLanes(const KernelConstants& k, const LanePointers& p,
                                              int offset) {
  constexpr float kSaturationMarginSigmas = 3.0f;
  const FloatLanes zero{}, one = zero + 1.0f;
  const LaneSums pilot_sums = sumFrames(
      k, p, offset,
      [&](const FrameConstants& f, FloatLanes value, FloatLanes estimate)
          __attribute__((always_inline))
              ->IntLanes { return (value < k.saturation) & (estimate >= f.dark_cd_m2); },
      [&](const FrameConstants& f, IntLanes valid)
          __attribute__((always_inline)) { return valid ? zero + f.exposure_weight : zero; });
  const IntLanes pilot_measured = pilot_sums.count > zero;
  const FloatLanes pilot = pilot_sums.weighted_sum / (pilot_measured ? pilot_sums.weight_sum : one);
  // The smallest normal float keeps 0/0 out of lanes with no pilot and no read noise.
  const auto variance = [&](const FrameConstants& f) __attribute__((always_inline)) {
    return f.shot_coefficient * pilot + f.read_coefficient + std::numeric_limits<float>::min();
  };
  const LaneSums sums = sumFrames(
      k, p, offset,
      [&](const FrameConstants& f, FloatLanes value, FloatLanes) __attribute__((always_inline))
          ->IntLanes {
            const FloatLanes headroom = f.saturated_cd_m2 - pilot;
            const IntLanes below_saturation =
                (headroom > zero) &
                (headroom * headroom >
                 kSaturationMarginSigmas * kSaturationMarginSigmas * variance(f));
            return pilot_measured & below_saturation & (pilot >= f.dark_cd_m2) &
                   (value < k.saturation);
          },
      [&](const FrameConstants& f, IntLanes valid)
          __attribute__((always_inline)) { return valid ? one / variance(f) : zero; });

  const IntLanes refined = sums.count > zero;
  const FloatLanes weight_sum = refined ? sums.weight_sum : pilot_sums.weight_sum;
  const FloatLanes count = refined ? sums.count : pilot_sums.count;
  const IntLanes measured = count > zero;
  const IntLanes clipped = pilot_sums.lower > zero;
  const FloatLanes mean = refined ? sums.weighted_sum / (refined ? sums.weight_sum : one) : pilot;
  const FloatLanes unmeasured = clipped ? pilot_sums.lower : zero + k.upper_bound;
  const FloatLanes nan = zero + std::numeric_limits<float>::quiet_NaN();
  storeLanes(p.luminance + offset,
             (measured ? mean : unmeasured) * loadLanes<FloatLanes>(p.inverse_flat + offset));
  storeLanes(p.relative + offset, measured ? one / mean : nan);  // / sqrt(weight_sum) per row
  storeLanes(p.weight_sum + offset, weight_sum);
  storeLanes(p.valid + offset, count);
  // PixelBound: 0 measured, 1 lower bound (saturated), 2 upper bound (dark).
  storeLanes(p.bound + offset, measured ? zero : (clipped ? one : one + one));
}

// Zero-padded copies of every frame's row tail, allocated once per worker.
struct TailScratch {
  explicit TailScratch(int frame_count)
      : pixels(static_cast<std::size_t>(frame_count) * kLanes),
        rows(static_cast<std::size_t>(frame_count)) {}
  std::vector<std::uint16_t> pixels;
  std::vector<const std::uint16_t*> rows;
};

// The last width % 8 pixels of a row, through zero-padded copies.
void mergeTail(const KernelConstants& k, const LanePointers& p, int whole, int rest,
               TailScratch& scratch) {
  std::fill(scratch.pixels.begin(), scratch.pixels.end(), std::uint16_t{0});
  for (int i = 0; i < k.frame_count; ++i) {
    std::uint16_t* tail = scratch.pixels.data() + static_cast<std::size_t>(i) * kLanes;
    std::copy_n(p.frames[i] + whole, rest, tail);
    scratch.rows[static_cast<std::size_t>(i)] = tail;
  }
  float flat[kLanes] = {}, luminance[kLanes], relative[kLanes], valid[kLanes], bound[kLanes],
        weight_sum[kLanes];
  std::copy_n(p.inverse_flat + whole, rest, flat);
  mergeLanes(k, {scratch.rows.data(), flat, luminance, relative, valid, bound, weight_sum}, 0);
  std::copy_n(luminance, rest, p.luminance + whole);
  std::copy_n(relative, rest, p.relative + whole);
  std::copy_n(valid, rest, p.valid + whole);
  std::copy_n(bound, rest, p.bound + whole);
  std::copy_n(weight_sum, rest, p.weight_sum + whole);
}

// A row: whole groups of eight in place, the rest through zero-padded copies (a zero DN is
// under-exposed, so padding never disturbs anything and is never stored). Then the counts and
// flags are narrowed to bytes.
GLARECAM_SIMD_CLONES void mergeRow(const KernelConstants& k, const LanePointers& p, int width,
                                   std::uint8_t* __restrict valid, std::uint8_t* __restrict bound,
                                   TailScratch& scratch) {
  const int whole = width - width % kLanes;
  for (int x = 0; x < whole; x += kLanes) mergeLanes(k, p, x);
  if (whole < width) mergeTail(k, p, whole, width - whole, scratch);
  for (int x = 0; x < width; ++x) {
    p.relative[x] /= std::sqrt(p.weight_sum[x]);  // sigma / L = 1 / (sqrt(sum w) L)
    valid[x] = static_cast<std::uint8_t>(p.valid[x]);
    bound[x] = static_cast<std::uint8_t>(p.bound[x]);
  }
}

class MergeKernel {
 public:
  MergeKernel(const MergeInput& input, MergedImage& output)
      : output_(output), frames_(frameConstants(input)), flat_(input.flat_field) {
    constants_ = {frames_.data(), static_cast<int>(frames_.size()),
                  static_cast<float>(input.black_level_dn), static_cast<float>(input.saturation_dn),
                  upperBound(frames_)};
  }

  void runRows(int begin, int end) const {
    const int width = output_.luminance_cd_m2.width();
    std::vector<const std::uint16_t*> rows(frames_.size());
    std::vector<float> inverse_flat(static_cast<std::size_t>(width), 1.0f);
    std::vector<float> valid(static_cast<std::size_t>(width)), bound(valid.size()),
        weight_sum(valid.size());
    TailScratch tail(static_cast<int>(frames_.size()));
    for (int y = begin; y < end; ++y) {
      for (std::size_t i = 0; i < frames_.size(); ++i) rows[i] = frames_[i].frame->row(y).data();
      if (flat_) {
        auto flat = flat_->row(y);
        for (std::size_t x = 0; x < flat.size(); ++x) inverse_flat[x] = 1.0f / flat[x];
      }
      mergeRow(constants_,
               {rows.data(), inverse_flat.data(), output_.luminance_cd_m2.row(y).data(),
                output_.relative_uncertainty.row(y).data(), valid.data(), bound.data(),
                weight_sum.data()},
               width, output_.valid_frames.row(y).data(), output_.bound.row(y).data(), tail);
    }
  }

 private:
  // The darkest luminance the longest frame can still detect: the bound of all-dark pixels.
  static float upperBound(const std::vector<FrameConstants>& frames) {
    float bound = std::numeric_limits<float>::max();
    for (const auto& f : frames) bound = std::min(bound, f.dark_cd_m2);
    return bound;
  }

  MergedImage& output_;
  std::vector<FrameConstants> frames_;
  const FloatImage* flat_;
  KernelConstants constants_{};
};

template <typename T>
void ensureSize(Image<T>& image, int width, int height) {
  if (!image.sameSize(width, height)) image = Image<T>(width, height);
}

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
    if (!isRepresentable(input.radiometry[i])) {
      return badInput("merge: frame " + std::to_string(i) +
                      " has radiometric constants outside the range the merge computes in");
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
