// `glarecam calibrate intrinsics`: views of a checkerboard (one per stack: the stack's best
// exposed frame) give the pinhole model and distortion (k1, k2, p1, p2, k3) through OpenCV's
// calib3d (findChessboardCornersSB, calibrateCamera), with the RMS reprojection error and how
// much of the image the corners covered: distortion grows towards the corners, so a board kept
// in the middle leaves it unmeasured there.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "calibration/input_frame.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

// calibrateCamera needs views from several orientations to separate focal length from distance.
inline constexpr std::size_t kMinBoardViews = 3;
// Coverage is counted on a grid of this many cells a side; below kMinCoverage of the cells
// holding a corner the result warns.
inline constexpr int kCoverageCells = 4;
inline constexpr double kMinCoverage = 0.75;

struct BoardSpec {
  int inner_columns = 9, inner_rows = 6;  // inner corners
  double square_mm = 25;
  Status validate() const;  // 3x3 corners or more, not square; squares of positive size
};

struct BoardView {  // one candidate image of the board
  std::string name;
  FloatImage image;  // any units; only contrast matters
};

struct IntrinsicsCalibration {
  Intrinsics intrinsics;
  double rms_reprojection_px = 0;
  std::vector<std::string> views_used, views_without_board;
  double coverage = 0;  // fraction of the grid's cells with a corner
  std::vector<std::string> warnings;
  int width = 0, height = 0;
};

struct IntrinsicsOptions {
  bool fit_k3 = false;  // k3 only for wide-angle lenses: with few views it takes up noise
};

Result<IntrinsicsCalibration> calibrateIntrinsics(std::span<const BoardView> views,
                                                  const BoardSpec& board,
                                                  const IntrinsicsOptions& options = {});

// The frame of a stack to look for the board in: the one with the widest range of values that is
// not saturated (5th to 95th percentile; saturated frames lose the white squares' edges).
std::size_t bestExposedFrame(std::span<const InputFrame> frames, double saturation_dn);

nlohmann::json intrinsicsValues(const IntrinsicsCalibration& result, const BoardSpec& board);

}  // namespace glarecam::calibration
