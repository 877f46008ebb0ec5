// Statistics of raw frames that every calibration procedure needs: a region of interest, the
// mean and variance of a frame (or of the difference of two) inside it, the per-pixel mean of
// several frames, and the robust centre and spread (median, MAD) of an image. Values are in DN.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

struct Roi {
  int x = 0, y = 0, width = 0, height = 0;
  long long pixelCount() const { return static_cast<long long>(width) * height; }
};

// The central quarter of the area (half the width and half the height): away from the corners,
// where vignetting and stray light are largest, and still 25 % of the pixels.
Roi centralRoi(int width, int height);
// "x,y,w,h" in pixels; `what` names the option in errors.
Result<Roi> parseRoi(std::string_view text, std::string_view what);
// Inside an image of that size, non-empty; the error names `what`.
Status checkRoi(const Roi& roi, int width, int height, std::string_view what);
std::string roiText(const Roi& roi);

struct RegionStats {
  double mean_dn = 0;
  double variance_dn2 = 0;  // unbiased (n - 1)
  double max_dn = 0;
};

RegionStats regionStats(const RawFrame& frame, const Roi& roi);
// Of (a - b) over the ROI: the fixed pattern cancels, what is left is twice the temporal variance.
RegionStats differenceStats(const RawFrame& a, const RawFrame& b, const Roi& roi);

// Per-pixel mean of the frames (all of one size) minus `offset_dn`.
FloatImage meanFrame(std::span<const RawFrame* const> frames, double offset_dn = 0);

struct RobustSpread {
  double median = 0;
  double sigma = 0;  // 1.4826 MAD: the standard deviation for normally distributed values
};
RobustSpread robustSpread(const FloatImage& image);

// Frames taken at one setting (exposure and gain equal to 1e-6 relative): indices into the list,
// in order; the groups sorted by exposure.
struct ExposureGroup {
  double exposure_us = 0;
  double gain_db = 0;
  std::vector<std::size_t> frames;
};
std::vector<ExposureGroup> groupByExposure(std::span<const FrameSpec> specs);

// Refuses groups at more than one gain (procedures that compare frames by exposure alone).
Status checkOneGain(std::span<const ExposureGroup> groups, std::string_view procedure);

// Mean of `image` in a square window of side `size` centred on (cx, cy), clipped to the image.
double windowMean(const FloatImage& image, double cx, double cy, int size);

}  // namespace glarecam::calibration
