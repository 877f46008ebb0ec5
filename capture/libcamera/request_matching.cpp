#include "capture/libcamera/request_matching.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

namespace glarecam::capture::libcam {

double gainDbToLinear(double gain_db) { return std::pow(10.0, gain_db / 20.0); }
double gainLinearToDb(double gain_linear) { return 20.0 * std::log10(gain_linear); }

// ---- version -------------------------------------------------------------------------------

std::string LibcameraVersion::toString() const {
  return fmt::format("{}.{}.{}", major, minor, patch);
}

namespace {

// Reads one decimal component; advances `text` past it.
std::optional<int> takeNumber(std::string_view& text) {
  if (text.empty() || text.front() < '0' || text.front() > '9') return std::nullopt;
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end == text.data()) return std::nullopt;
  text.remove_prefix(static_cast<std::size_t>(end - text.data()));
  return value;
}

bool takeChar(std::string_view& text, char c) {
  if (text.empty() || text.front() != c) return false;
  text.remove_prefix(1);
  return true;
}

std::string testedList() {
  std::string list;
  for (const LibcameraVersion& version : kTestedLibcameraVersions) {
    list += (list.empty() ? "" : ", ") + version.toString();
  }
  return list;
}

}  // namespace

std::optional<LibcameraVersion> parseLibcameraVersion(std::string_view reported) {
  takeChar(reported, 'v');
  const auto major = takeNumber(reported);
  if (!major || !takeChar(reported, '.')) return std::nullopt;
  const auto minor = takeNumber(reported);
  if (!minor || !takeChar(reported, '.')) return std::nullopt;
  const auto patch = takeNumber(reported);
  if (!patch) return std::nullopt;
  // What may follow the patch number: a git suffix ("+65-1a2b3c4d") or a packaging revision.
  if (!reported.empty() && reported.front() != '+' && reported.front() != '-') return std::nullopt;
  return LibcameraVersion{*major, *minor, *patch};
}

Status checkLibcameraVersion(std::string_view reported) {
  const auto version = parseLibcameraVersion(reported);
  if (!version) {
    return hardwareError(fmt::format("libcamera reports an unreadable version \"{}\" (tested: {})",
                                     reported, testedList()));
  }
  if (std::ranges::find(kTestedLibcameraVersions, *version) == kTestedLibcameraVersions.end()) {
    return hardwareError(
        fmt::format("libcamera {} is not a tested version (tested: {})", reported, testedList()));
  }
  return {};
}

// ---- matching ------------------------------------------------------------------------------

bool MatchRule::exposureMatches(double requested_us, double applied_us) const {
  const double tolerance_us = std::max(exposure_rounding_us, exposure_relative * requested_us);
  return std::abs(applied_us - requested_us) <= tolerance_us;
}

bool MatchRule::gainMatches(double requested_db, std::optional<double> applied_db) const {
  return !applied_db || std::abs(*applied_db - requested_db) <= gain_tolerance_db;
}

BracketMatcher::BracketMatcher(std::vector<ExposureRequest> steps, MatchRule rule,
                               int max_retries_per_step)
    : steps_(std::move(steps)),
      state_(steps_.size()),
      rule_(rule),
      max_retries_per_step_(max_retries_per_step) {}

bool BracketMatcher::complete() const {
  return std::ranges::all_of(state_, [](const StepState& s) { return s.filled; });
}

std::optional<std::size_t> BracketMatcher::nextStep() const {
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (!state_[i].filled && state_[i].in_flight == 0) return i;
  }
  return std::nullopt;
}

void BracketMatcher::onQueued(std::size_t queued_for) { ++state_[queued_for].in_flight; }

std::optional<std::size_t> BracketMatcher::bestMatch(std::size_t queued_for,
                                                     const FrameMeta& meta) const {
  const auto fits = [&](std::size_t i) {
    return !state_[i].filled && rule_.exposureMatches(steps_[i].exposure_us, *meta.exposure_us) &&
           rule_.gainMatches(steps_[i].gain_db, meta.gain_db);
  };
  if (fits(queued_for)) return queued_for;
  std::optional<std::size_t> best;
  double best_distance = 0;
  for (std::size_t i = 0; i < steps_.size(); ++i) {
    if (!fits(i)) continue;
    const double distance = std::abs(std::log(*meta.exposure_us / steps_[i].exposure_us));
    if (!best || distance < best_distance) {
      best = i;
      best_distance = distance;
    }
  }
  return best;
}

Result<std::optional<std::size_t>> BracketMatcher::onFrame(std::size_t queued_for,
                                                           const FrameMeta& meta) {
  --state_[queued_for].in_flight;
  if (!meta.exposure_us) {
    return hardwareError(fmt::format(
        "frame {} carries no ExposureTime metadata; cannot tell which bracket step it belongs to",
        meta.sequence));
  }
  if (const auto step = bestMatch(queued_for, meta)) {
    state_[*step].filled = true;
    return step;
  }
  const std::string what =
      fmt::format("frame {} carried {:.0f} µs{}", meta.sequence, *meta.exposure_us,
                  meta.gain_db ? fmt::format(", {:.2f} dB", *meta.gain_db) : std::string());
  GLARECAM_CHECK(chargeRetry(queued_for, what));
  return std::optional<std::size_t>{};
}

Status BracketMatcher::onFailure(std::size_t queued_for, std::string_view why) {
  --state_[queued_for].in_flight;
  return chargeRetry(queued_for, std::string(why));
}

Status BracketMatcher::chargeRetry(std::size_t queued_for, const std::string& what) {
  // A stale frame delays the step it was queued for; if that step was meanwhile filled by
  // another frame, it delays the first step still open.
  std::size_t charged = queued_for;
  if (state_[charged].filled) {
    const auto open = std::ranges::find_if(state_, [](const StepState& s) { return !s.filled; });
    if (open == state_.end()) return {};
    charged = static_cast<std::size_t>(open - state_.begin());
  }
  if (++state_[charged].retries > max_retries_per_step_) {
    return hardwareError(fmt::format("{}: {} frames discarded, more than the {} allowed (last: {})",
                                     describeStep(charged), state_[charged].retries,
                                     max_retries_per_step_, what));
  }
  return {};
}

std::string BracketMatcher::describeStep(std::size_t index) const {
  return fmt::format("bracket step {} of {} ({:.0f} µs, {:.2f} dB)", index + 1, steps_.size(),
                     steps_[index].exposure_us, steps_[index].gain_db);
}

// ---- raw layouts ---------------------------------------------------------------------------

namespace {

constexpr std::string_view kCsi2PackedSuffix = "_CSI2P";
constexpr std::array<std::string_view, 4> kBayerOrders{"RGGB", "GRBG", "GBRG", "BGGR"};

bool supportedDepth(int depth_bits, Packing packing) {
  switch (packing) {
    case Packing::k8Bit:
      return depth_bits == 8;
    case Packing::kLittleEndian16:
      return depth_bits == 10 || depth_bits == 12 || depth_bits == 14 || depth_bits == 16;
    case Packing::kCsi2Packed:
      return depth_bits == 10 || depth_bits == 12;
  }
  return false;
}

// CSI-2 RAW10: four 8-bit MSB bytes, then one byte with the four 2-bit LSBs, pixel 0 lowest.
void unpackCsi2Raw10(std::span<const std::uint8_t> row, std::span<std::uint16_t> out) {
  for (std::size_t x = 0; x < out.size(); ++x) {
    const std::size_t group = (x / 4) * 5;
    const std::size_t lane = x % 4;
    const unsigned msbs = row[group + lane];
    const unsigned lsbs = (row[group + 4] >> (2 * lane)) & 0x3u;
    out[x] = static_cast<std::uint16_t>((msbs << 2) | lsbs);
  }
}

// CSI-2 RAW12: two 8-bit MSB bytes, then one byte with the two 4-bit LSBs, pixel 0 lowest.
void unpackCsi2Raw12(std::span<const std::uint8_t> row, std::span<std::uint16_t> out) {
  for (std::size_t x = 0; x < out.size(); ++x) {
    const std::size_t group = (x / 2) * 3;
    const std::size_t lane = x % 2;
    const unsigned msbs = row[group + lane];
    const unsigned lsbs = (row[group + 2] >> (4 * lane)) & 0xFu;
    out[x] = static_cast<std::uint16_t>((msbs << 4) | lsbs);
  }
}

void unpackRow(std::span<const std::uint8_t> row, const RawLayout& layout,
               std::span<std::uint16_t> out) {
  switch (layout.packing) {
    case Packing::k8Bit:
      std::ranges::copy(row.first(out.size()), out.begin());
      return;
    case Packing::kLittleEndian16: {
      const auto mask = static_cast<std::uint16_t>((1u << layout.depth_bits) - 1u);
      for (std::size_t x = 0; x < out.size(); ++x) {
        out[x] = static_cast<std::uint16_t>((row[2 * x] | (row[2 * x + 1] << 8)) & mask);
      }
      return;
    }
    case Packing::kCsi2Packed:
      if (layout.depth_bits == 10) {
        unpackCsi2Raw10(row, out);
      } else {
        unpackCsi2Raw12(row, out);
      }
      return;
  }
}

}  // namespace

std::string RawLayout::genicamName() const {
  if (mono()) return fmt::format("Mono{}", depth_bits);
  return fmt::format("Bayer{}{}", bayer_order.substr(0, 2), depth_bits);
}

std::optional<RawLayout> parseRawLayout(std::string_view name) {
  RawLayout layout;
  if (name.ends_with(kCsi2PackedSuffix)) {
    layout.packing = Packing::kCsi2Packed;
    name.remove_suffix(kCsi2PackedSuffix.size());
  }
  if (name.starts_with('R')) {
    name.remove_prefix(1);
  } else if (name.starts_with('S') && name.size() > 5 &&
             std::ranges::find(kBayerOrders, name.substr(1, 4)) != kBayerOrders.end()) {
    layout.bayer_order = std::string(name.substr(1, 4));
    name.remove_prefix(5);
  } else {
    return std::nullopt;
  }
  int depth_bits = 0;
  const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), depth_bits);
  if (error != std::errc{} || end != name.data() + name.size()) return std::nullopt;
  layout.depth_bits = depth_bits;
  if (depth_bits == 8 && layout.packing != Packing::kCsi2Packed) layout.packing = Packing::k8Bit;
  if (!supportedDepth(depth_bits, layout.packing)) return std::nullopt;
  return layout;
}

std::size_t packedRowBytes(const RawLayout& layout, int width) {
  const auto pixels = static_cast<std::size_t>(std::max(width, 0));
  switch (layout.packing) {
    case Packing::k8Bit:
      return pixels;
    case Packing::kLittleEndian16:
      return 2 * pixels;
    case Packing::kCsi2Packed:
      return layout.depth_bits == 10 ? (pixels + 3) / 4 * 5 : (pixels + 1) / 2 * 3;
  }
  return 0;
}

Result<RawFrame> unpackRaw(std::span<const std::uint8_t> bytes, int width, int height,
                           std::size_t stride_bytes, const RawLayout& layout) {
  if (width <= 0 || height <= 0) {
    return hardwareError(fmt::format("raw frame has an empty size {}x{}", width, height));
  }
  const std::size_t row_bytes = packedRowBytes(layout, width);
  if (stride_bytes < row_bytes) {
    return hardwareError(fmt::format("{} row stride {} bytes is shorter than a row of {} bytes",
                                     layout.genicamName(), stride_bytes, row_bytes));
  }
  const std::size_t needed = stride_bytes * static_cast<std::size_t>(height - 1) + row_bytes;
  if (bytes.size() < needed) {
    return hardwareError(fmt::format("{} {}x{} frame needs {} bytes, the buffer holds {}",
                                     layout.genicamName(), width, height, needed, bytes.size()));
  }
  RawFrame frame(width, height);
  for (int y = 0; y < height; ++y) {
    unpackRow(bytes.subspan(static_cast<std::size_t>(y) * stride_bytes, row_bytes), layout,
              frame.row(y));
  }
  return frame;
}

}  // namespace glarecam::capture::libcam
