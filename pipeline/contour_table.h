// The contour table, contours.csv (docs/sweep.md, "The contour table"): a sweep's contour ladders
// (glare_analysis.h) in long form, one row per stack and level, as `glarecam sweep` writes it
// beside sweep.csv and `glarecam datasheet` reads it for the glare profile's ladder. Columns:
// stack_id, alpha_deg, level_cd_m2, kind (ladder, limit, half_maximum), status (result.json's:
// "measured" or why there is no ellipse), the ellipse's vertical_deg, horizontal_deg,
// orientation_deg, solid_angle_sr and their standard uncertainties (empty without an ellipse;
// the orientation's also empty for a circle), reference_illuminance_lx (empty: unreferred).
// Rows sorted by α, then level; any column order on read, extra columns ignored.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/result.h"

namespace glarecam::pipeline {

inline constexpr const char* kContourTableFileName = "contours.csv";

struct ContourRow {
  std::string stack_id = {};
  double alpha_deg = 0;
  double level_cd_m2 = 0;
  ContourKind kind = ContourKind::kLadder;
  EllipseStatus status = EllipseStatus::kBelowLevel;
  // The ellipse, exactly when status is measured.
  std::optional<double> vertical_deg = std::nullopt, horizontal_deg = std::nullopt;
  std::optional<double> orientation_deg = std::nullopt, solid_angle_sr = std::nullopt;
  std::optional<double> vertical_uncertainty_deg = std::nullopt,
                        horizontal_uncertainty_deg = std::nullopt;
  std::optional<double> orientation_uncertainty_deg = std::nullopt,
                        solid_angle_uncertainty_sr = std::nullopt;
  std::optional<double> reference_illuminance_lx = std::nullopt;  // none: unreferred
  bool measured() const { return status == EllipseStatus::kMeasured; }
  bool operator==(const ContourRow&) const = default;
};

struct ContourTable {
  std::vector<ContourRow> rows;
};

// The rows of one processed stack's ladder (none without α or without a ladder).
std::vector<ContourRow> contourRowsFromResult(const StackResult& result);

// The table as CSV text, rows sorted by α, then level (rows at one α and level keep their order).
std::string formatContourTable(const ContourTable& table);

// Reads and validates contours.csv: the header naming every column above, numbers finite, α in
// [0, 90), levels positive, kind and status known words, the ellipse's columns present exactly
// when measured and in range (axes in (0, 180]°, orientation within ±90°). Errors name the file
// and line (kBadInput).
Result<ContourTable> readContourTable(const std::filesystem::path& path);

}  // namespace glarecam::pipeline
