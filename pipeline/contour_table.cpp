#include "pipeline/contour_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>

#include "core/csv.h"

namespace glarecam::pipeline {
namespace {

enum ContourColumn {
  kColStackId,
  kColAlpha,
  kColLevel,
  kColKind,
  kColStatus,
  kColVertical,
  kColHorizontal,
  kColOrientation,
  kColSolidAngle,
  kColVerticalU,
  kColHorizontalU,
  kColOrientationU,
  kColSolidAngleU,
  kColReference,
  kContourColumnCount
};

constexpr std::array<const char*, kContourColumnCount> kContourColumnNames = {
    "stack_id",
    "alpha_deg",
    "level_cd_m2",
    "kind",
    "status",
    "vertical_deg",
    "horizontal_deg",
    "orientation_deg",
    "solid_angle_sr",
    "vertical_uncertainty_deg",
    "horizontal_uncertainty_deg",
    "orientation_uncertainty_deg",
    "solid_angle_uncertainty_sr",
    "reference_illuminance_lx"};

std::string contourNumber(const std::optional<double>& value) {
  return value ? fmt::format("{}", *value) : std::string();  // shortest exact form
}

template <typename Fields>
std::string contourCsvLine(const Fields& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) line += ',';
    line.append(fields[i]);
  }
  return line + '\n';
}

// An empty field is none; anything else must be a finite number.
Result<std::optional<double>> contourField(const std::string& text, const char* column) {
  if (text.empty()) return std::optional<double>{};
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return badInput(fmt::format("{}: \"{}\" is not a number", column, text));
  return std::optional(value);
}

Status checkContourRow(const ContourRow& row) {
  if (!(row.alpha_deg >= 0 && row.alpha_deg < 90))
    return badInput(fmt::format("alpha_deg: {:g} is outside [0, 90)", row.alpha_deg));
  if (!(row.level_cd_m2 > 0)) return badInput("level_cd_m2: must be positive");
  if (row.kind == ContourKind::kLadder && !isLadderLevel(row.level_cd_m2))
    return badInput(fmt::format("level_cd_m2: {:g} is not a level of the ladder", row.level_cd_m2));
  const std::optional<double>* ellipse[] = {&row.vertical_deg,
                                            &row.horizontal_deg,
                                            &row.orientation_deg,
                                            &row.solid_angle_sr,
                                            &row.vertical_uncertainty_deg,
                                            &row.horizontal_uncertainty_deg,
                                            &row.solid_angle_uncertainty_sr};
  const bool any = std::any_of(std::begin(ellipse), std::end(ellipse),
                               [](const auto* v) { return v->has_value(); }) ||
                   row.orientation_uncertainty_deg.has_value();
  const bool all = std::all_of(std::begin(ellipse), std::end(ellipse),
                               [](const auto* v) { return v->has_value(); });
  if (row.measured() && !all)
    return badInput(
        "status measured, but an ellipse column (axes, orientation, solid angle and "
        "their uncertainties) is empty");
  if (!row.measured() && any)
    return badInput(
        fmt::format("status {}, but the ellipse's columns are given", toString(row.status)));
  if (!row.measured()) return {};
  for (const double axis : {*row.vertical_deg, *row.horizontal_deg})
    if (!(axis > 0 && axis <= kMaxAxisDeg))
      return badInput(fmt::format("an axis of {:g}° is outside (0, 180]", axis));
  if (!(std::abs(*row.orientation_deg) <= kMaxOrientationDeg))
    return badInput(fmt::format("orientation_deg: {:g} is outside ±90°", *row.orientation_deg));
  if (!(*row.solid_angle_sr >= 0 && *row.solid_angle_sr <= 4 * std::numbers::pi))
    return badInput("solid_angle_sr: outside [0, 4π]");
  for (const auto* u : {&row.vertical_uncertainty_deg, &row.horizontal_uncertainty_deg,
                        &row.orientation_uncertainty_deg, &row.solid_angle_uncertainty_sr})
    if (u->has_value() && !(**u >= 0)) return badInput("an uncertainty is negative");
  if (row.reference_illuminance_lx && !(*row.reference_illuminance_lx > 0))
    return badInput("reference_illuminance_lx: must be positive");
  return {};
}

}  // namespace

std::vector<ContourRow> contourRowsFromResult(const StackResult& result) {
  std::vector<ContourRow> rows;
  if (!result.alpha_deg || !result.contours) return rows;
  for (const ResultContour& c : *result.contours) {
    ContourRow row{.stack_id = result.stack,
                   .alpha_deg = *result.alpha_deg,
                   .level_cd_m2 = c.level.level_cd_m2,
                   .kind = c.kind,
                   .status = c.level.status,
                   .reference_illuminance_lx = result.illuminance.reference_lx};
    if (c.level.ellipse) {
      const ResultEllipse& e = *c.level.ellipse;
      row.vertical_deg = e.vertical_deg;
      row.horizontal_deg = e.horizontal_deg;
      row.orientation_deg = e.orientation_deg;
      row.solid_angle_sr = e.solid_angle_sr;
      row.vertical_uncertainty_deg = e.vertical_uncertainty_deg;
      row.horizontal_uncertainty_deg = e.horizontal_uncertainty_deg;
      row.orientation_uncertainty_deg = e.orientation_uncertainty_deg;
      row.solid_angle_uncertainty_sr = e.solid_angle_uncertainty_sr;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string formatContourTable(const ContourTable& table) {
  std::string text = contourCsvLine(kContourColumnNames);
  std::vector<ContourRow> rows = table.rows;
  std::stable_sort(rows.begin(), rows.end(), [](const ContourRow& a, const ContourRow& b) {
    return a.alpha_deg != b.alpha_deg ? a.alpha_deg < b.alpha_deg : a.level_cd_m2 < b.level_cd_m2;
  });
  for (const ContourRow& r : rows) {
    std::string stack_id = r.stack_id;
    std::replace_if(
        stack_id.begin(), stack_id.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    const std::array<std::string, kContourColumnCount> fields{
        quoteCsvField(stack_id),
        contourNumber(r.alpha_deg),
        contourNumber(r.level_cd_m2),
        toString(r.kind),
        toString(r.status),
        contourNumber(r.vertical_deg),
        contourNumber(r.horizontal_deg),
        contourNumber(r.orientation_deg),
        contourNumber(r.solid_angle_sr),
        contourNumber(r.vertical_uncertainty_deg),
        contourNumber(r.horizontal_uncertainty_deg),
        contourNumber(r.orientation_uncertainty_deg),
        contourNumber(r.solid_angle_uncertainty_sr),
        contourNumber(r.reference_illuminance_lx)};
    text += contourCsvLine(fields);
  }
  return text;
}

Result<ContourTable> readContourTable(const std::filesystem::path& path) {
  ContourTable table;
  std::optional<std::array<std::size_t, kContourColumnCount>> columns;
  GLARECAM_CHECK(
      readCsvFile(path, "contour table", [&](std::vector<std::string>& fields) -> Status {
        if (!columns) {
          std::map<std::string, std::size_t> index;
          for (std::size_t i = 0; i < fields.size(); ++i) index.emplace(fields[i], i);
          columns.emplace();
          for (std::size_t c = 0; c < kContourColumnCount; ++c) {
            const auto it = index.find(kContourColumnNames[c]);
            if (it == index.end())
              return badInput(
                  fmt::format("the header lacks the column {}", kContourColumnNames[c]));
            (*columns)[c] = it->second;
          }
          return {};
        }
        const auto field = [&](int c) -> const std::string& {
          static const std::string kEmpty;
          const std::size_t i = (*columns)[static_cast<std::size_t>(c)];
          return i < fields.size() ? fields[i] : kEmpty;
        };
        ContourRow row;
        row.stack_id = field(kColStackId);
        std::optional<double> alpha, level;
        GLARECAM_ASSIGN(alpha, contourField(field(kColAlpha), "alpha_deg"));
        GLARECAM_ASSIGN(level, contourField(field(kColLevel), "level_cd_m2"));
        if (!alpha || !level) return badInput("alpha_deg and level_cd_m2 must be given");
        row.alpha_deg = *alpha;
        row.level_cd_m2 = *level;
        const auto kind = contourKindFromString(field(kColKind));
        if (!kind)
          return badInput(
              fmt::format("kind: \"{}\" is not ladder, limit or half_maximum", field(kColKind)));
        row.kind = *kind;
        const auto status = ellipseStatusFromString(field(kColStatus));
        if (!status)
          return badInput(
              fmt::format("status: \"{}\" is not an ellipse status", field(kColStatus)));
        row.status = *status;
        const std::pair<int, std::optional<double>*> numbers[] = {
            {kColVertical, &row.vertical_deg},
            {kColHorizontal, &row.horizontal_deg},
            {kColOrientation, &row.orientation_deg},
            {kColSolidAngle, &row.solid_angle_sr},
            {kColVerticalU, &row.vertical_uncertainty_deg},
            {kColHorizontalU, &row.horizontal_uncertainty_deg},
            {kColOrientationU, &row.orientation_uncertainty_deg},
            {kColSolidAngleU, &row.solid_angle_uncertainty_sr},
            {kColReference, &row.reference_illuminance_lx}};
        for (const auto& [column, target] : numbers)
          GLARECAM_ASSIGN(*target, contourField(field(column), kContourColumnNames[column]));
        GLARECAM_CHECK(checkContourRow(row));
        table.rows.push_back(std::move(row));
        return {};
      }));
  if (!columns) return badInput(path.string() + ": empty contour table (no header)");
  return table;
}

}  // namespace glarecam::pipeline
