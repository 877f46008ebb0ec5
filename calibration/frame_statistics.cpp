#include "calibration/frame_statistics.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

namespace glarecam::calibration {
namespace {

// MAD to standard deviation for a normal distribution: 1 / Phi^-1(3/4).
constexpr double kMadToSigma = 1.4826;

// Sums over the ROI in double; `value(x, y)` gives the pixel.
template <typename Value>
RegionStats accumulate(const Roi& roi, Value value) {
  double sum = 0, sum_sq = 0, max_dn = -1e300;
  // Shifted by the first pixel: the variance of values near 4000 DN keeps its digits.
  const double shift = value(roi.x, roi.y);
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const double v = value(x, y);
      sum += v - shift;
      sum_sq += (v - shift) * (v - shift);
      max_dn = std::max(max_dn, v);
    }
  }
  const double n = static_cast<double>(roi.pixelCount());
  const double mean_shifted = sum / n;
  return {.mean_dn = mean_shifted + shift,
          .variance_dn2 = n > 1 ? (sum_sq - n * mean_shifted * mean_shifted) / (n - 1) : 0.0,
          .max_dn = max_dn};
}

}  // namespace

Roi centralRoi(int width, int height) {
  return {.x = width / 4,
          .y = height / 4,
          .width = std::max(1, width / 2),
          .height = std::max(1, height / 2)};
}

Result<Roi> parseRoi(std::string_view text, std::string_view what) {
  int values[4] = {};
  std::string_view rest = text;
  for (int i = 0; i < 4; ++i) {
    const auto comma = rest.find(',');
    const std::string_view part = rest.substr(0, comma);
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), values[i]);
    if (part.empty() || error != std::errc() || end != part.data() + part.size() ||
        (i < 3) == (comma == std::string_view::npos)) {
      return badInput(fmt::format("{} \"{}\": expected x,y,w,h in whole pixels", what, text));
    }
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
  }
  if (values[0] < 0 || values[1] < 0 || values[2] <= 0 || values[3] <= 0)
    return badInput(fmt::format("{} \"{}\": x, y must be >= 0 and w, h > 0", what, text));
  return Roi{.x = values[0], .y = values[1], .width = values[2], .height = values[3]};
}

Status checkOneGain(std::span<const ExposureGroup> groups, std::string_view procedure) {
  for (const ExposureGroup& group : groups) {
    if (group.gain_db != groups.front().gain_db) {
      return badInput(
          fmt::format("calibrate {}: frames at {:g} dB and {:g} dB: take all at one gain",
                      procedure, groups.front().gain_db, group.gain_db));
    }
  }
  return {};
}

Status checkRoi(const Roi& roi, int width, int height, std::string_view what) {
  // In long long: x + w of a parsed "2147483000,0,1000,10" would overflow int.
  if (roi.width <= 0 || roi.height <= 0 || roi.x < 0 || roi.y < 0 ||
      static_cast<long long>(roi.x) + roi.width > width ||
      static_cast<long long>(roi.y) + roi.height > height) {
    return badInput(
        fmt::format("{} {} is not inside the {}x{} frames", what, roiText(roi), width, height));
  }
  return {};
}

std::string roiText(const Roi& roi) {
  return fmt::format("{},{},{},{}", roi.x, roi.y, roi.width, roi.height);
}

RegionStats regionStats(const RawFrame& frame, const Roi& roi) {
  return accumulate(roi, [&](int x, int y) { return static_cast<double>(frame.at(x, y)); });
}

RegionStats differenceStats(const RawFrame& a, const RawFrame& b, const Roi& roi) {
  return accumulate(roi, [&](int x, int y) {
    return static_cast<double>(a.at(x, y)) - static_cast<double>(b.at(x, y));
  });
}

FloatImage meanFrame(std::span<const RawFrame* const> frames, double offset_dn) {
  const RawFrame& first = *frames.front();
  std::vector<double> sum(first.pixelCount(), 0.0);
  for (const RawFrame* frame : frames) {
    const std::uint16_t* pixels = frame->data();
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += pixels[i];
  }
  FloatImage mean(first.width(), first.height());
  const double n = static_cast<double>(frames.size());
  for (std::size_t i = 0; i < sum.size(); ++i)
    mean.data()[i] = static_cast<float>(sum[i] / n - offset_dn);
  return mean;
}

RobustSpread robustSpread(const FloatImage& image) {
  std::vector<float> values(image.data(), image.data() + image.pixelCount());
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  const double median = *middle;
  for (float& v : values) v = static_cast<float>(std::abs(v - median));
  std::nth_element(values.begin(), middle, values.end());
  return {.median = median, .sigma = kMadToSigma * *middle};
}

std::vector<ExposureGroup> groupByExposure(std::span<const FrameSpec> specs) {
  constexpr double kSameSetting = 1e-6;  // relative: a camera's readback of one request
  const auto same = [](double a, double b) {
    return std::abs(a - b) <= kSameSetting * std::max(std::abs(a), std::abs(b));
  };
  std::vector<ExposureGroup> groups;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto group = std::ranges::find_if(groups, [&](const ExposureGroup& g) {
      return same(g.exposure_us, specs[i].exposure_us) &&
             std::abs(g.gain_db - specs[i].gain_db) <= kSameSetting;
    });
    if (group != groups.end()) {
      group->frames.push_back(i);
    } else {
      groups.push_back(
          {.exposure_us = specs[i].exposure_us, .gain_db = specs[i].gain_db, .frames = {i}});
    }
  }
  std::ranges::stable_sort(groups, [](const ExposureGroup& a, const ExposureGroup& b) {
    return a.exposure_us != b.exposure_us ? a.exposure_us < b.exposure_us : a.gain_db < b.gain_db;
  });
  return groups;
}

double windowMean(const FloatImage& image, double cx, double cy, int size) {
  const int half = size / 2;
  const long cx_px = std::lround(cx), cy_px = std::lround(cy);
  const int x0 = static_cast<int>(std::clamp<long>(cx_px - half, 0, image.width() - 1));
  const int y0 = static_cast<int>(std::clamp<long>(cy_px - half, 0, image.height() - 1));
  const int x1 = static_cast<int>(std::clamp<long>(cx_px - half + size, x0 + 1, image.width()));
  const int y1 = static_cast<int>(std::clamp<long>(cy_px - half + size, y0 + 1, image.height()));
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += image.at(x, y);
  return sum / static_cast<double>((x1 - x0) * (y1 - y0));
}

}  // namespace glarecam::calibration
