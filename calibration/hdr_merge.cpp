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
  float saturation_dn;     // values at or above are saturated (the calibration's, or the frame
                           // container's maximum when that is lower: 255 for 8-bit frames)
  float saturated_cd_m2;   // luminance at the saturation DN (lower bound when clipped)
  float dark_cd_m2;        // luminance at the under-exposure threshold
  float exposure_weight;   // 1 / shot_coefficient: the pilot's weight
  float shot_coefficient;  // var(L_i) = shot_coefficient * L + read_coefficient
  float read_coefficient;
  float dark_offset_dn;  // added to the dark frame's pixel (0 with the black level)
};

// Frames sorted from the longest effective exposure (smallest scale) to the shortest.
std::vector<FrameConstants> frameConstants(const MergeInput& input) {
  std::vector<FrameConstants> constants;
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    const FrameRadiometry& r = input.radiometry[i];
    const double saturation_dn = frameSaturationDn(input, i);
    const double shot_coefficient = r.scale_cd_m2_per_dn * r.dn_per_electron;
    constants.push_back(
        {&input.frames[i], static_cast<float>(r.scale_cd_m2_per_dn),
         static_cast<float>(saturation_dn),
         static_cast<float>((saturation_dn - input.black_level_dn) * r.scale_cd_m2_per_dn),
         static_cast<float>(r.min_signal_dn * r.scale_cd_m2_per_dn),
         static_cast<float>(1.0 / shot_coefficient), static_cast<float>(shot_coefficient),
         static_cast<float>(r.scale_cd_m2_per_dn * r.scale_cd_m2_per_dn * r.read_noise_dn *
                            r.read_noise_dn),
         static_cast<float>(input.dark_frame_dn ? input.dark_offsets_dn[i] : 0.0)});
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
  const float* black;                  // per pixel: the dark frame's row, or the black level
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
  float upper_bound;
};

// One frame's eight pixels: raw values, and their luminance estimates.
struct FrameLanes {
  FloatLanes value, estimate;
};

[[gnu::always_inline]] inline FrameLanes loadFrame(const FrameConstants& f,
                                                   const std::uint16_t* row, FloatLanes black) {
  const FloatLanes value = __builtin_convertvector(loadLanes<WordLanes>(row), FloatLanes);
  return {value, (value - (black + f.dark_offset_dn)) * f.scale};
}

// A frame pixel judged by its own reading: below the frame's saturation, above its dark threshold.
[[gnu::always_inline]] inline IntLanes validByReading(const FrameConstants& f,
                                                      const FrameLanes& x) {
  return (x.value < f.saturation_dn) & (x.estimate >= f.dark_cd_m2);
}

// Sums of a weighted mean. With weights w_i = t_i / var_i (t_i a taper in [0, 1]) the mean's
// variance is sum(t_i² / var_i) / (sum w_i)²: `tapered_sum` holds sum(t_i w_i).
struct LaneSums {
  FloatLanes weight_sum{}, weighted_sum{}, count{}, tapered_sum{};
  [[gnu::always_inline]] void add(IntLanes valid, FloatLanes weight, FloatLanes estimate) {
    const FloatLanes zero{};
    const FloatLanes w = valid ? weight : zero;
    weight_sum += w;
    weighted_sum += w * estimate;
    tapered_sum += w;
    count += valid ? zero + 1.0f : zero;
  }
  [[gnu::always_inline]] void add(IntLanes valid, FloatLanes weight, FloatLanes estimate,
                                  FloatLanes taper) {
    const FloatLanes zero{};
    const FloatLanes w = valid ? weight * taper : zero;
    weight_sum += w;
    weighted_sum += w * estimate;
    tapered_sum += w * taper;
    count += valid ? zero + 1.0f : zero;
  }
  // (sum w)² / sum(t w): the weight of an optimal mean with the same variance.
  [[gnu::always_inline]] FloatLanes effectiveWeight(IntLanes measured) const {
    const FloatLanes one = FloatLanes{} + 1.0f;
    return measured ? weight_sum * weight_sum / tapered_sum : one;
  }
};

// A frame's weight tapers from 0 at kSaturationMarginSigmas of its noise below its saturation to
// full at kTaperEndSigmas, smoothly (smoothstep in the squared headroom, no square root per
// pixel). The pilot that decides is mostly the frame's own reading, so near a hard cut a frame
// that read high was dropped and one that read low kept: in a frame's band the median pixel read
// 0.34 % low (issue 23; the mean barely moved), and the reported noise swung by ±8 %. Spread over
// 3..12 sigma the median stays within 0.11 % and the noise within 4 %; a wider band would cost
// the frame's information where it is good, and judging a frame by the others' pilot instead
// moves the bias onto them (+0.3 % on the mean, measured).
constexpr float kSaturationMarginSigmas = 3.0f;
constexpr float kTaperEndSigmas = 12.0f;
// Below this taper (headroom within 0.13 sigma of the 3 sigma start) a frame is not counted.
constexpr float kMinCountedTaper = 1e-4f;

// Every lane's mask set.
[[gnu::always_inline]] inline bool allLanes(IntLanes mask) {
  bool all = true;
  for (int i = 0; i < kLanes; ++i) all &= mask[i] != 0;
  return all;
}

// Where a lane is in the band: 0 at its start, 1 at its end (unclamped).
[[gnu::always_inline]] inline FloatLanes taperPosition(FloatLanes headroom_sq_sigmas) {
  constexpr float kStart = kSaturationMarginSigmas * kSaturationMarginSigmas;
  constexpr float kSpan = kTaperEndSigmas * kTaperEndSigmas - kStart;
  return (headroom_sq_sigmas - kStart) * (1.0f / kSpan);
}

[[gnu::always_inline]] inline FloatLanes saturationTaper(FloatLanes headroom_sq_sigmas) {
  const FloatLanes zero{}, one = zero + 1.0f;
  FloatLanes u = taperPosition(headroom_sq_sigmas);
  u = u < zero ? zero : u;
  u = u > one ? one : u;
  return u * u * (3.0f - 2.0f * u);
}

// Two passes over the frames, values reloaded from L1:
//  1. pilot: a frame pixel counts when its own reading is valid, weighted by 1 / shot
//     coefficient (its inverse variance where shot noise dominates; independent of the
//     readings, so unbiased, and free of divisions);
//  2. final: a frame counts when the *pilot* predicts it within range: at least its dark
//     threshold and more than kSaturationMarginSigmas of its noise below its saturation, its
//     weight tapering to full at kTaperEndSigmas. A frame judged by its own reading keeps the
//     readings noise pushed down and drops those it pushed up, and reads low just below
//     saturation (high just above the dark threshold); judged by the pilot it is not truncated.
//     Weights: inverse variances at the pilot, times the taper; the reported uncertainty is that
//     of this weighted mean.
// A pixel no frame passes in pass 2 (its best frame sits within 3 sigma of saturation) falls
// back to the own-reading rule with the same inverse-variance weights.
[[gnu::always_inline]] inline void mergeLanes(const KernelConstants& k, const LanePointers& p,
                                              int offset) {
  const FloatLanes zero{}, one = zero + 1.0f;
  const FloatLanes black = loadLanes<FloatLanes>(p.black + offset);
  LaneSums pilot_sums;
  FloatLanes lower = zero;
  for (int i = 0; i < k.frame_count; ++i) {
    const FrameConstants& f = k.frames[i];
    const FrameLanes x = loadFrame(f, p.frames[i] + offset, black);
    pilot_sums.add(validByReading(f, x), zero + f.exposure_weight, x.estimate);
    const IntLanes saturated = x.value >= f.saturation_dn;
    lower = (saturated & (lower < f.saturated_cd_m2)) ? zero + f.saturated_cd_m2 : lower;
  }
  const IntLanes pilot_measured = pilot_sums.count > zero;
  const FloatLanes pilot = pilot_sums.weighted_sum / (pilot_measured ? pilot_sums.weight_sum : one);

  LaneSums final_sums, fallback_sums;
  for (int i = 0; i < k.frame_count; ++i) {
    const FrameConstants& f = k.frames[i];
    const FrameLanes x = loadFrame(f, p.frames[i] + offset, black);
    // The smallest normal float keeps 0/0 out of lanes with no pilot and no read noise.
    const FloatLanes variance =
        f.shot_coefficient * pilot + f.read_coefficient + std::numeric_limits<float>::min();
    const FloatLanes weight = one / variance;
    const FloatLanes headroom = f.saturated_cd_m2 - pilot;
    const FloatLanes headroom_sq_sigmas = headroom * headroom / variance;
    fallback_sums.add(validByReading(f, x), weight, x.estimate);
    const IntLanes below_saturation = x.value < f.saturation_dn;
    // Most of an image lies past the band in most frames: full weight, no taper to compute (the
    // same test that clamps the taper to exactly 1, so the sums are bit for bit the same).
    if (allLanes((headroom > zero) & (taperPosition(headroom_sq_sigmas) >= one))) {
      final_sums.add(pilot_measured & (pilot >= f.dark_cd_m2) & below_saturation, weight,
                     x.estimate);
      continue;
    }
    // A frame whose taper all but vanishes does not count: alone it would make the pixel
    // "measured" by a weight whose square underflows float (its uncertainty then read 0).
    const FloatLanes taper = saturationTaper(headroom_sq_sigmas);
    const IntLanes predicted_in_range =
        pilot_measured & (pilot >= f.dark_cd_m2) & (headroom > zero) & (taper > kMinCountedTaper);
    final_sums.add(predicted_in_range & below_saturation, weight, x.estimate, taper);
  }

  const IntLanes refined = final_sums.count > zero;
  const LaneSums chosen{refined ? final_sums.weight_sum : fallback_sums.weight_sum,
                        refined ? final_sums.weighted_sum : fallback_sums.weighted_sum,
                        refined ? final_sums.count : fallback_sums.count,
                        refined ? final_sums.tapered_sum : fallback_sums.tapered_sum};
  const IntLanes measured = chosen.count > zero;
  const IntLanes clipped = lower > zero;
  const FloatLanes mean = chosen.weighted_sum / (measured ? chosen.weight_sum : one);
  const FloatLanes unmeasured = clipped ? lower : zero + k.upper_bound;
  const FloatLanes nan = zero + std::numeric_limits<float>::quiet_NaN();
  storeLanes(p.luminance + offset,
             (measured ? mean : unmeasured) * loadLanes<FloatLanes>(p.inverse_flat + offset));
  storeLanes(p.relative + offset, measured ? one / mean : nan);  // / sqrt(weight_sum) per row
  storeLanes(p.weight_sum + offset, chosen.effectiveWeight(measured));
  storeLanes(p.valid + offset, chosen.count);
  // PixelBound: 0 measured, 1 lower bound (saturated), 2 upper bound (dark).
  storeLanes(p.bound + offset, measured ? zero : (clipped ? one : one + one));
}

// Zero-padded copies of every frame's row tail, allocated once per worker.
struct TailScratch {
  TailScratch(int frame_count, float black_level_dn)
      : pixels(static_cast<std::size_t>(frame_count) * kLanes),
        rows(static_cast<std::size_t>(frame_count)),
        padding_black_dn(black_level_dn) {}
  std::vector<std::uint16_t> pixels;
  std::vector<const std::uint16_t*> rows;
  float padding_black_dn;  // a zero DN below it is under-exposed in every frame
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
  float black[kLanes], flat[kLanes] = {}, luminance[kLanes], relative[kLanes], valid[kLanes],
                       bound[kLanes], weight_sum[kLanes];
  std::fill_n(black, kLanes, scratch.padding_black_dn);
  std::copy_n(p.black + whole, rest, black);
  std::copy_n(p.inverse_flat + whole, rest, flat);
  mergeLanes(k, {scratch.rows.data(), black, flat, luminance, relative, valid, bound, weight_sum},
             0);
  std::copy_n(luminance, rest, p.luminance + whole);
  std::copy_n(relative, rest, p.relative + whole);
  std::copy_n(valid, rest, p.valid + whole);
  std::copy_n(bound, rest, p.bound + whole);
  std::copy_n(weight_sum, rest, p.weight_sum + whole);
}

// A row: whole groups of eight in place, the rest through zero-padded copies (a zero DN below
// the black level is under-exposed, so padding never disturbs anything and is never stored). Then
// the counts and flags are narrowed to bytes.
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
      : output_(output),
        frames_(frameConstants(input)),
        flat_(input.flat_field),
        dark_(input.dark_frame_dn),
        black_level_dn_(static_cast<float>(input.black_level_dn)) {
    constants_ = {frames_.data(), static_cast<int>(frames_.size()), upperBound(frames_)};
  }

  void runRows(int begin, int end) const {
    const int width = output_.luminance_cd_m2.width();
    std::vector<const std::uint16_t*> rows(frames_.size());
    std::vector<float> inverse_flat(static_cast<std::size_t>(width), 1.0f);
    const std::vector<float> black_level(static_cast<std::size_t>(width), black_level_dn_);
    std::vector<float> valid(static_cast<std::size_t>(width)), bound(valid.size()),
        weight_sum(valid.size());
    TailScratch tail(static_cast<int>(frames_.size()), black_level_dn_);
    for (int y = begin; y < end; ++y) {
      const float* black = dark_ ? dark_->row(y).data() : black_level.data();
      for (std::size_t i = 0; i < frames_.size(); ++i) rows[i] = frames_[i].frame->row(y).data();
      if (flat_) {
        auto flat = flat_->row(y);
        for (std::size_t x = 0; x < flat.size(); ++x) inverse_flat[x] = 1.0f / flat[x];
      }
      mergeRow(constants_,
               {rows.data(), black, inverse_flat.data(), output_.luminance_cd_m2.row(y).data(),
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
  const FloatImage* dark_;
  float black_level_dn_;
  KernelConstants constants_{};
};

// The kernel writes every pixel of every output row, so new outputs need no fill.
template <typename T>
void ensureSize(Image<T>& image, int width, int height) {
  if (!image.sameSize(width, height)) image = Image<T>::uninitialized(width, height);
}

// Masked pixels take the median of their unmasked 8-neighbours (hot pixels are isolated: a
// cluster of them has no value, NaN). Only unmasked pixels are read, so the order is free.
void fillMaskedPixels(const ByteImage& mask, MergedImage& output) {
  const int width = mask.width(), height = mask.height();
  std::vector<float> neighbours;
  for (int y = 0; y < height; ++y) {
    const auto row = mask.row(y);
    for (int x = 0; x < width; ++x) {
      if (row[static_cast<std::size_t>(x)] == 0) continue;
      neighbours.clear();
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height || mask.at(nx, ny) != 0) continue;
          const float v = output.luminance_cd_m2.at(nx, ny);
          if (std::isfinite(v)) neighbours.push_back(v);
        }
      }
      float value = std::numeric_limits<float>::quiet_NaN();
      if (!neighbours.empty()) {
        const auto middle = neighbours.begin() + static_cast<std::ptrdiff_t>(neighbours.size() / 2);
        std::nth_element(neighbours.begin(), middle, neighbours.end());
        value = *middle;
      }
      output.luminance_cd_m2.at(x, y) = value;
      output.relative_uncertainty.at(x, y) = std::numeric_limits<float>::quiet_NaN();
      output.valid_frames.at(x, y) = 0;
      output.bound.at(x, y) = static_cast<std::uint8_t>(PixelBound::kMasked);
    }
  }
}

}  // namespace

double blackDn(const MergeInput& input, std::size_t frame, std::size_t pixel) {
  if (!input.dark_frame_dn) return input.black_level_dn;
  return input.dark_frame_dn->data()[pixel] + input.dark_offsets_dn[frame];
}

std::vector<double> darkOffsetsDn(std::span<const FrameSpec> frames,
                                  const Calibration& calibration) {
  std::vector<double> offsets;
  for (const FrameSpec& frame : frames) {
    offsets.push_back(calibration.dark_frame_exposure_us
                          ? calibration.dark_current_dn_per_us *
                                (frame.exposure_us - *calibration.dark_frame_exposure_us)
                          : 0.0);
  }
  return offsets;
}

double frameSaturationDn(const MergeInput& input, std::size_t frame) {
  const int bits = frame < input.bit_depths.size() ? input.bit_depths[frame] : 16;
  return std::min(input.saturation_dn, static_cast<double>((1 << bits) - 1));
}

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
  if (!input.bit_depths.empty() && input.bit_depths.size() != input.frames.size()) {
    return fail(ErrorCode::kInternal, "merge: one bit depth per frame needed");
  }
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    if (frameSaturationDn(input, i) <= input.black_level_dn) {
      return badInput("merge: frame " + std::to_string(i) +
                      " cannot hold values above the black level " +
                      std::to_string(input.black_level_dn) + " DN (" +
                      std::to_string(input.bit_depths[i]) + "-bit frame)");
    }
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
  if (input.dark_frame_dn) {
    if (!input.dark_frame_dn->sameSize(first.width(), first.height()))
      return badInput("merge: dark frame differs in size from the frames");
    if (input.dark_offsets_dn.size() != input.frames.size())
      return fail(ErrorCode::kInternal, "merge: one dark offset per frame needed");
  }
  if (input.masked_pixels && !input.masked_pixels->sameSize(first.width(), first.height())) {
    return badInput("merge: hot-pixel map differs in size from the frames");
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
  parallelRows(height, options.threads ? options.threads : availableThreads(),
               [&](int begin, int end) { kernel.runRows(begin, end); });
  if (input.masked_pixels) fillMaskedPixels(*input.masked_pixels, output);
  return {};
}

Result<MergedImage> merge(const MergeInput& input, const MergeOptions& options) {
  MergedImage output;
  GLARECAM_CHECK(mergeInto(input, options, output));
  return output;
}

}  // namespace glarecam::calibration
