#include "calibration/hdr_merge.h"

#include <algorithm>
#include <cmath>
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
  float min_signal_dn;     // under-exposure threshold above black
  float saturated_cd_m2;   // luminance at the saturation DN (lower bound when clipped)
  float shot_coefficient;  // var(L_i) = shot_coefficient * L + read_coefficient
  float read_coefficient;
};

// Frames sorted from the shortest effective exposure (largest scale) to the longest, so the
// last valid estimate seen for a pixel comes from the frame with the most signal.
std::vector<FrameConstants> frameConstants(const MergeInput& input) {
  std::vector<FrameConstants> constants;
  const double full_range_dn = input.saturation_dn - input.black_level_dn;
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    const FrameRadiometry& r = input.radiometry[i];
    constants.push_back({&input.frames[i], static_cast<float>(r.scale_cd_m2_per_dn), static_cast<float>(r.min_signal_dn),
                         static_cast<float>(full_range_dn * r.scale_cd_m2_per_dn),
                         static_cast<float>(r.scale_cd_m2_per_dn * r.dn_per_electron),
                         static_cast<float>(r.scale_cd_m2_per_dn * r.scale_cd_m2_per_dn * r.read_noise_dn * r.read_noise_dn)});
  }
  std::stable_sort(constants.begin(), constants.end(), [](const auto& a, const auto& b) { return a.scale > b.scale; });
  return constants;
}

// Row buffers of one worker: allocated once per band, reused for every row.
struct RowAccumulator {
  explicit RowAccumulator(int width)
      : best(width), weight_sum(width), weighted_sum(width), valid_count(width), lower_bound(width),
        inverse_flat(width, 1.0f) {}
  std::vector<float> best, weight_sum, weighted_sum, valid_count, lower_bound;
  mutable std::vector<float> inverse_flat;  // 1 / flat field of the row (all ones without one)
};

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
    RowAccumulator row(output_.luminance_cd_m2.width());
    for (int y = begin; y < end; ++y) {
      estimateReference(y, row);
      accumulate(y, row);
      finish(y, row);
    }
  }

 private:
  // The darkest luminance the longest frame can still detect: the bound of all-dark pixels.
  static float upperBound(const std::vector<FrameConstants>& frames) {
    float bound = std::numeric_limits<float>::max();
    for (const auto& f : frames) bound = std::min(bound, f.min_signal_dn * f.scale);
    return bound;
  }

  // Pass 1: the reference luminance of each pixel (longest valid frame) and the lower bound.
  void estimateReference(int y, RowAccumulator& row) const {
    const std::size_t width = row.best.size();
    std::fill_n(row.best.data(), width, 0.0f);
    std::fill_n(row.lower_bound.data(), width, 0.0f);
    for (const FrameConstants& f : frames_) {
      referenceRow(f.frame->row(y).data(), row.best.data(), row.lower_bound.data(), width, black_, saturation_,
                   f.min_signal_dn, f.scale, f.saturated_cd_m2);
    }
  }

  // The loops below take every constant by value so that the compiler keeps them in registers
  // and vectorises (with -fno-trapping-math the selects become blends).
  static void referenceRow(const std::uint16_t* __restrict dn, float* __restrict best, float* __restrict lower,
                           std::size_t width, float black, float saturation, float min_signal, float scale,
                           float saturated_cd_m2) {
    for (std::size_t x = 0; x < width; ++x) {
      const float value = dn[x];
      const float signal = value - black;
      const bool saturated = value >= saturation;
      const bool valid = (value < saturation) & (signal >= min_signal);
      best[x] = valid ? signal * scale : best[x];
      lower[x] = std::max(lower[x], saturated ? saturated_cd_m2 : 0.0f);
    }
  }

  // Pass 2: inverse-variance weighted sum of the valid estimates.
  void accumulate(int y, RowAccumulator& row) const {
    const std::size_t width = row.best.size();
    std::fill_n(row.weight_sum.data(), width, 0.0f);
    std::fill_n(row.weighted_sum.data(), width, 0.0f);
    std::fill_n(row.valid_count.data(), width, 0.0f);
    for (const FrameConstants& f : frames_) {
      accumulateRow(f.frame->row(y).data(), row.best.data(), row.weight_sum.data(), row.weighted_sum.data(),
                    row.valid_count.data(), width, black_, saturation_, f);
    }
  }

  static void accumulateRow(const std::uint16_t* __restrict dn, const float* __restrict best,
                            float* __restrict weight_sum, float* __restrict weighted_sum, float* __restrict count,
                            std::size_t width, float black, float saturation, FrameConstants f) {
    const float min_signal = f.min_signal_dn, scale = f.scale, shot = f.shot_coefficient;
    // The smallest normal float keeps 0/0 out of pixels with no reference and no read noise.
    const float read = f.read_coefficient + std::numeric_limits<float>::min();
    for (std::size_t x = 0; x < width; ++x) {
      const float value = dn[x];
      const float signal = value - black;
      const float valid = ((value < saturation) & (signal >= min_signal)) ? 1.0f : 0.0f;
      const float weight = valid / (shot * best[x] + read);  // inverse variance, or 0
      weight_sum[x] += weight;
      weighted_sum[x] += weight * (signal * scale);
      count[x] += valid;
    }
  }

  // Pass 3: luminance, uncertainty and flags of the row, flat field applied once.
  void finish(int y, const RowAccumulator& row) const {
    const float* inverse_flat = row.inverse_flat.data();
    if (flat_) {
      auto flat = flat_->row(y);
      for (std::size_t x = 0; x < flat.size(); ++x) row.inverse_flat[x] = 1.0f / flat[x];
    }
    finishRow(row, inverse_flat, upper_bound_, output_.luminance_cd_m2.row(y).data(),
              output_.relative_uncertainty.row(y).data(), output_.valid_frames.row(y).data(),
              output_.bound.row(y).data());
  }

  static void finishRow(const RowAccumulator& row, const float* __restrict inverse_flat, float upper_bound,
                        float* __restrict luminance, float* __restrict relative, std::uint8_t* __restrict valid,
                        std::uint8_t* __restrict bound) {
    const float* __restrict weight_sum = row.weight_sum.data();
    const float* __restrict weighted_sum = row.weighted_sum.data();
    const float* __restrict count = row.valid_count.data();
    const float* __restrict lower = row.lower_bound.data();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::size_t width = row.best.size();
    for (std::size_t x = 0; x < width; ++x) {
      const bool measured = count[x] > 0.0f;
      const bool saturated = lower[x] > 0.0f;
      const float mean = weighted_sum[x] / weight_sum[x];
      const float unmeasured = saturated ? lower[x] : upper_bound;
      luminance[x] = (measured ? mean : unmeasured) * inverse_flat[x];
      relative[x] = measured ? 1.0f / (std::sqrt(weight_sum[x]) * mean) : nan;
      valid[x] = static_cast<std::uint8_t>(count[x]);
      // PixelBound: 0 measured, 1 lower bound (saturated), 2 upper bound (dark).
      const std::uint8_t unmeasured_flag = saturated ? 1 : 2;
      bound[x] = measured ? 0 : unmeasured_flag;
    }
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
  if (input.frames.size() != input.radiometry.size()) return fail(ErrorCode::kInternal, "merge: one radiometry per frame needed");
  if (input.frames.size() > std::numeric_limits<std::uint8_t>::max()) return badInput("merge: more than 255 frames");
  if (!(input.black_level_dn >= 0 && input.black_level_dn < input.saturation_dn && std::isfinite(input.saturation_dn))) {
    return badInput("merge: black level must be below saturation");
  }
  const RawFrame& first = input.frames.front();
  for (std::size_t i = 0; i < input.frames.size(); ++i) {
    if (!input.frames[i].sameSize(first.width(), first.height()) || input.frames[i].empty()) {
      return badInput("merge: frame " + std::to_string(i) + " differs in size from frame 0");
    }
    const FrameRadiometry& r = input.radiometry[i];
    if (!finitePositive(r.scale_cd_m2_per_dn) || !finitePositive(r.dn_per_electron) || !finitePositive(r.min_signal_dn) ||
        !(std::isfinite(r.read_noise_dn) && r.read_noise_dn >= 0)) {
      return badInput("merge: frame " + std::to_string(i) + " has non-finite or non-positive radiometric constants");
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
