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
      : best(width), weight_sum(width), weighted_sum(width), valid_count(width), lower_bound(width) {}
  std::vector<float> best, weight_sum, weighted_sum, valid_count, lower_bound;
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
    float* __restrict best = row.best.data();
    float* __restrict lower = row.lower_bound.data();
    std::fill_n(best, width, 0.0f);
    std::fill_n(lower, width, 0.0f);
    for (const FrameConstants& f : frames_) {
      const std::uint16_t* __restrict dn = f.frame->row(y).data();
      for (std::size_t x = 0; x < width; ++x) {
        const float value = dn[x];
        const float signal = value - black_;
        const bool saturated = value >= saturation_;
        const bool valid = !saturated & (signal >= f.min_signal_dn);
        best[x] = valid ? signal * f.scale : best[x];
        lower[x] = std::max(lower[x], saturated ? f.saturated_cd_m2 : 0.0f);
      }
    }
  }

  // Pass 2: inverse-variance weighted sum of the valid estimates.
  void accumulate(int y, RowAccumulator& row) const {
    const std::size_t width = row.best.size();
    const float* __restrict best = row.best.data();
    float* __restrict weight_sum = row.weight_sum.data();
    float* __restrict weighted_sum = row.weighted_sum.data();
    float* __restrict count = row.valid_count.data();
    std::fill_n(weight_sum, width, 0.0f);
    std::fill_n(weighted_sum, width, 0.0f);
    std::fill_n(count, width, 0.0f);
    for (const FrameConstants& f : frames_) {
      const std::uint16_t* __restrict dn = f.frame->row(y).data();
      for (std::size_t x = 0; x < width; ++x) {
        const float value = dn[x];
        const float signal = value - black_;
        const bool valid = (value < saturation_) & (signal >= f.min_signal_dn);
        const float weight = valid ? 1.0f / (f.shot_coefficient * best[x] + f.read_coefficient) : 0.0f;
        weight_sum[x] += weight;
        weighted_sum[x] += weight * (signal * f.scale);
        count[x] += valid ? 1.0f : 0.0f;
      }
    }
  }

  // Pass 3: luminance, uncertainty and flags of the row, flat field applied once.
  void finish(int y, const RowAccumulator& row) const {
    const std::size_t width = row.best.size();
    float* __restrict luminance = output_.luminance_cd_m2.row(y).data();
    float* __restrict relative = output_.relative_uncertainty.row(y).data();
    std::uint8_t* __restrict valid = output_.valid_frames.row(y).data();
    std::uint8_t* __restrict bound = output_.bound.row(y).data();
    const float* __restrict flat = flat_ ? flat_->row(y).data() : nullptr;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t x = 0; x < width; ++x) {
      const bool measured = row.valid_count[x] > 0.0f;
      const bool saturated = row.lower_bound[x] > 0.0f;
      const float mean = row.weighted_sum[x] / row.weight_sum[x];
      const float unflat = measured ? mean : (saturated ? row.lower_bound[x] : upper_bound_);
      luminance[x] = flat ? unflat / flat[x] : unflat;
      relative[x] = measured ? 1.0f / (std::sqrt(row.weight_sum[x]) * mean) : nan;
      valid[x] = static_cast<std::uint8_t>(row.valid_count[x]);
      bound[x] = static_cast<std::uint8_t>(measured ? PixelBound::kMeasured
                                                    : (saturated ? PixelBound::kLowerBound : PixelBound::kUpperBound));
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
