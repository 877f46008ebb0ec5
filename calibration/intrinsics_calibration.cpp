#include "calibration/intrinsics_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <set>

namespace glarecam::calibration {
namespace {

// The 5th and 95th percentiles of a frame, for contrast and for scaling to 8 bits.
std::pair<double, double> percentileRange(const float* values, std::size_t count) {
  std::vector<float> sorted(values, values + count);
  const auto at = [&](double q) {
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(count - 1));
    std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
    return static_cast<double>(sorted[static_cast<std::size_t>(k)]);
  };
  constexpr double kLow = 0.05, kHigh = 0.95;
  return {at(kLow), at(kHigh)};
}

// 8-bit for the corner detector: the 5th..95th percentile stretched to 0..255.
cv::Mat toGray8(const FloatImage& image) {
  const auto [low, high] = percentileRange(image.data(), image.pixelCount());
  const double scale = high > low ? 255.0 / (high - low) : 1.0;
  cv::Mat source(image.height(), image.width(), CV_32F, const_cast<float*>(image.data()));
  cv::Mat gray;
  source.convertTo(gray, CV_8U, scale, -low * scale);
  return gray;
}

std::vector<cv::Point3f> boardPoints(const BoardSpec& board) {
  std::vector<cv::Point3f> points;
  for (int row = 0; row < board.inner_rows; ++row)
    for (int column = 0; column < board.inner_columns; ++column)
      points.emplace_back(static_cast<float>(column * board.square_mm),
                          static_cast<float>(row * board.square_mm), 0.0f);
  return points;
}

double coverage(const std::vector<std::vector<cv::Point2f>>& corners, int width, int height) {
  std::set<int> cells;
  for (const auto& view : corners) {
    for (const cv::Point2f& p : view) {
      const int i =
          std::clamp(static_cast<int>(p.x * kCoverageCells / width), 0, kCoverageCells - 1);
      const int j =
          std::clamp(static_cast<int>(p.y * kCoverageCells / height), 0, kCoverageCells - 1);
      cells.insert(j * kCoverageCells + i);
    }
  }
  return static_cast<double>(cells.size()) / (kCoverageCells * kCoverageCells);
}

}  // namespace

Status BoardSpec::validate() const {
  if (inner_columns < 3 || inner_rows < 3 || inner_columns == inner_rows)
    return badInput(fmt::format(
        "calibrate intrinsics: board {}x{}: needs at least 3x3 inner corners, and different "
        "counts across and down (a square board's orientation is ambiguous)",
        inner_columns, inner_rows));
  if (!(square_mm > 0)) return badInput("calibrate intrinsics: --square-mm must be positive");
  return {};
}

std::size_t bestExposedFrame(std::span<const InputFrame> frames, double saturation_dn) {
  std::size_t best = 0;
  double best_range = -1;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const RawFrame& frame = frames[i].frame;
    std::vector<float> values(frame.data(), frame.data() + frame.pixelCount());
    const auto [low, high] = percentileRange(values.data(), values.size());
    const double range = high >= saturation_dn ? 0 : high - low;
    if (range > best_range) {
      best_range = range;
      best = i;
    }
  }
  return best;
}

Result<IntrinsicsCalibration> calibrateIntrinsics(std::span<const BoardView> views,
                                                  const BoardSpec& board,
                                                  const IntrinsicsOptions& options) {
  GLARECAM_CHECK(board.validate());
  if (views.empty()) return badInput("calibrate intrinsics: no images");
  IntrinsicsCalibration result;
  result.width = views.front().image.width();
  result.height = views.front().image.height();
  const cv::Size pattern(board.inner_columns, board.inner_rows);
  std::vector<std::vector<cv::Point2f>> image_points;
  for (const BoardView& view : views) {
    if (!view.image.sameSize(result.width, result.height))
      return badInput(fmt::format("{}: {}x{}, but the first image is {}x{}", view.name,
                                  view.image.width(), view.image.height(), result.width,
                                  result.height));
    std::vector<cv::Point2f> corners;
    if (cv::findChessboardCornersSB(toGray8(view.image), pattern, corners,
                                    cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY)) {
      image_points.push_back(std::move(corners));
      result.views_used.push_back(view.name);
    } else {
      result.views_without_board.push_back(view.name);
    }
  }
  if (image_points.size() < kMinBoardViews) {
    return badInput(fmt::format(
        "calibrate intrinsics: the {}x{} board was found in {} of {} image(s); needs {} or more "
        "views (check --board: inner corners across x down)",
        board.inner_columns, board.inner_rows, image_points.size(), views.size(), kMinBoardViews));
  }
  const std::vector<std::vector<cv::Point3f>> object_points(image_points.size(),
                                                            boardPoints(board));
  cv::Mat camera = cv::Mat::eye(3, 3, CV_64F), distortion = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rotations, translations;
  const int flags = options.fit_k3 ? 0 : cv::CALIB_FIX_K3;
  result.rms_reprojection_px =
      cv::calibrateCamera(object_points, image_points, cv::Size(result.width, result.height),
                          camera, distortion, rotations, translations, flags);
  result.intrinsics = {.fx = camera.at<double>(0, 0),
                       .fy = camera.at<double>(1, 1),
                       .cx = camera.at<double>(0, 2),
                       .cy = camera.at<double>(1, 2)};
  for (int i = 0; i < 5; ++i) result.intrinsics.distortion[i] = distortion.at<double>(i);
  result.coverage = coverage(image_points, result.width, result.height);
  if (result.coverage < kMinCoverage) {
    result.warnings.push_back(fmt::format(
        "the board's corners reached {:.0f} % of the image ({}x{} cells), under {:.0f} %: "
        "distortion is extrapolated near the edges; add views with the board in the corners",
        100 * result.coverage, kCoverageCells, kCoverageCells, 100 * kMinCoverage));
  }
  for (const std::string& name : result.views_without_board)
    result.warnings.push_back(name + ": board not found (left out)");
  return result;
}

nlohmann::json intrinsicsValues(const IntrinsicsCalibration& result, const BoardSpec& board) {
  const Intrinsics& k = result.intrinsics;
  return {{"intrinsics",
           {{"fx", k.fx},
            {"fy", k.fy},
            {"cx", k.cx},
            {"cy", k.cy},
            {"distortion", k.distortion},
            {"rms_reprojection_px", result.rms_reprojection_px},
            {"width", result.width},
            {"height", result.height},
            {"board",
             {{"inner_columns", board.inner_columns},
              {"inner_rows", board.inner_rows},
              {"square_mm", board.square_mm}}},
            {"views", result.views_used.size()},
            {"coverage", result.coverage}}}};
}

}  // namespace glarecam::calibration
