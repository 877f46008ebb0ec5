#include "pipeline/sweep_table.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>

#include "core/csv.h"

namespace glarecam::pipeline {

namespace {

enum Column {
  kAlpha,
  kLimit,
  kLmax,
  kVertical,
  kHorizontal,
  kLmaxUncertainty,
  kVerticalUncertainty,
  kHorizontalUncertainty,
  kAlphaUncertainty,
  kFwhmVertical,
  kFwhmHorizontal,
  kGlare,
  kLmaxBound,
  kLimitStatus,
  kFramesConsistent,
  kSuspect,
  kCameraBackend,
  kCameraSerial,
  kModule,
  kWidth,
  kHeight,
  kCalibrationId,
  kCalibrationDate,
  kLuminanceFactor,
  kLuminanceFactorU,
  kSourceIlluminance,
  kSourceIlluminanceU,
  kSourceOrigin,
  kReferenceIlluminance,
  kRoute,
  kStackId,
  kStack,
  kColumnCount
};
constexpr int kRequiredColumns = kHorizontal + 1;

constexpr std::array<const char*, kColumnCount> kColumnNames{"alpha_deg",
                                                             "limit_cd_m2",
                                                             "lmax_cd_m2",
                                                             "vertical_deg",
                                                             "horizontal_deg",
                                                             "lmax_uncertainty_cd_m2",
                                                             "vertical_uncertainty_deg",
                                                             "horizontal_uncertainty_deg",
                                                             "alpha_uncertainty_deg",
                                                             "fwhm_vertical_deg",
                                                             "fwhm_horizontal_deg",
                                                             "glare",
                                                             "lmax_bound",
                                                             "limit_status",
                                                             "frames_consistent",
                                                             "suspect",
                                                             "camera_backend",
                                                             "camera_serial",
                                                             "module",
                                                             "width",
                                                             "height",
                                                             "calibration_id",
                                                             "calibration_date",
                                                             "luminance_factor",
                                                             "luminance_factor_u",
                                                             "source_illuminance_lx",
                                                             "source_illuminance_u_lx",
                                                             "source_origin",
                                                             "reference_illuminance_lx",
                                                             "route",
                                                             "stack_id",
                                                             "stack"};

// Physical bound: no reflection is brighter than the sun's disk (about 1.6e9 cd/m²). The axes'
// bound is the result's (result.h, kMaxAxisDeg).
constexpr double kMaxLuminanceCdM2 = 1e10;

// α is the angle from the module normal; at 90° the cosine function is undefined.
constexpr double kMaxAlphaDeg = 90.0;

std::string trim(std::string_view text) { return trimCsvText(text); }

Result<std::optional<double>> parseNumber(const std::string& text, const char* column) {
  if (text.empty()) return std::nullopt;
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value))
    return badInput(fmt::format("{}: \"{}\" is not a finite number", column, text));
  return value;
}

struct Header {
  std::array<int, kColumnCount> index;  // -1: column absent
};

Result<Header> parseHeader(const std::vector<std::string>& fields) {
  Header header;
  header.index.fill(-1);
  for (int i = 0; i < static_cast<int>(fields.size()); ++i) {
    for (int c = 0; c < kColumnCount; ++c) {
      if (trim(fields[i]) != kColumnNames[c]) continue;
      if (header.index[c] >= 0)
        return badInput(fmt::format("column {} appears twice (fields {} and {})", kColumnNames[c],
                                    header.index[c] + 1, i + 1));
      header.index[c] = i;
    }
  }
  std::string missing;
  for (int c = 0; c < kRequiredColumns; ++c) {
    if (header.index[c] < 0)
      missing += (missing.empty() ? "" : ", ") + std::string(kColumnNames[c]);
  }
  if (!missing.empty() && fields.size() == 1 && fields[0].find(';') != std::string::npos)
    return badInput(
        "the header has no commas but semicolons: the sweep table is comma-separated "
        "(export CSV with ',' as the separator and '.' as the decimal point)");
  if (!missing.empty())
    return badInput("missing column(s) " + missing +
                    " (the header needs alpha_deg, limit_cd_m2, lmax_cd_m2, vertical_deg, "
                    "horizontal_deg; see docs/stack-format.md)");
  return header;
}

// The field of column c ("" when the column is absent or the line short).
std::string field(const Header& header, const std::vector<std::string>& fields, Column c) {
  const int i = header.index[c];
  return i >= 0 && i < static_cast<int>(fields.size()) ? trim(fields[i]) : std::string();
}

Status requirePositive(const std::optional<double>& value, const char* column) {
  if (value && *value <= 0) return badInput(fmt::format("{}: {} must be positive", column, *value));
  return {};
}

Status requireAtMost(const std::optional<double>& value, double most, const char* column) {
  if (value && *value > most)
    return badInput(
        fmt::format("{}: {} is beyond the physical range (at most {:g})", column, *value, most));
  return {};
}

// The row's source and reference illuminance columns: a referred row has all but the
// uncertainty, an unreferred one says "unreferred" (or, from an older table, nothing) and has
// neither illuminance.
Status parseRowIlluminance(const Header& header, const std::vector<std::string>& fields,
                           const std::array<std::optional<double>, kColumnCount>& numbers,
                           SweepRow& row) {
  row.source_origin = field(header, fields, kSourceOrigin);
  row.source_illuminance_lx = numbers[kSourceIlluminance];
  row.source_illuminance_u_lx = numbers[kSourceIlluminanceU];
  row.reference_illuminance_lx = numbers[kReferenceIlluminance];
  for (int c : {kSourceIlluminance, kReferenceIlluminance}) {
    if (numbers[c] && !(*numbers[c] > 0 && *numbers[c] <= kMaxSourceIlluminanceLx))
      return badInput(fmt::format("{}: {} is outside (0, {:g}] lx", kColumnNames[c], *numbers[c],
                                  kMaxSourceIlluminanceLx));
  }
  if (row.source_illuminance_u_lx && *row.source_illuminance_u_lx < 0)
    return badInput(fmt::format("source_illuminance_u_lx: {} must not be negative",
                                *row.source_illuminance_u_lx));
  const bool unreferred = row.source_origin.empty() || row.source_origin == kUnreferredWord;
  if (!unreferred && !originFromWord(row.source_origin))
    return badInput(fmt::format(
        "source_origin: \"{}\" is not sensor, given, clear_sky or unreferred", row.source_origin));
  if (unreferred && (row.source_illuminance_lx || row.reference_illuminance_lx))
    return badInput(
        "source_origin: an unreferred row has no source_illuminance_lx or "
        "reference_illuminance_lx");
  if (!unreferred && !(row.source_illuminance_lx && row.reference_illuminance_lx))
    return badInput(
        fmt::format("source_origin {}: a referred row needs source_illuminance_lx and "
                    "reference_illuminance_lx",
                    row.source_origin));
  return {};
}

Result<SweepRow> parseRow(const Header& header, const std::vector<std::string>& fields) {
  SweepRow row;
  std::array<std::optional<double>, kColumnCount> numbers;
  for (int c :
       {kAlpha, kLimit, kLmax, kVertical, kHorizontal, kLmaxUncertainty, kVerticalUncertainty,
        kHorizontalUncertainty, kAlphaUncertainty, kFwhmVertical, kFwhmHorizontal, kLuminanceFactor,
        kLuminanceFactorU, kSourceIlluminance, kSourceIlluminanceU, kReferenceIlluminance}) {
    GLARECAM_ASSIGN(numbers[c], parseNumber(field(header, fields, Column(c)), kColumnNames[c]));
  }
  GLARECAM_CHECK(validateSweepAlpha(numbers[kAlpha]));
  if (!numbers[kLmax]) return badInput("lmax_cd_m2 is empty");
  row.alpha_deg = *numbers[kAlpha];
  for (int c : {kLimit, kLmax, kVertical, kHorizontal, kAlphaUncertainty, kLuminanceFactor})
    GLARECAM_CHECK(requirePositive(numbers[c], kColumnNames[c]));
  for (int c : {kLimit, kLmax})
    GLARECAM_CHECK(requireAtMost(numbers[c], kMaxLuminanceCdM2, kColumnNames[c]));
  for (int c : {kVertical, kHorizontal})
    GLARECAM_CHECK(requireAtMost(numbers[c], kMaxAxisDeg, kColumnNames[c]));
  row.limit_cd_m2 = numbers[kLimit];
  row.lmax_cd_m2 = *numbers[kLmax];
  row.vertical_deg = numbers[kVertical];
  row.horizontal_deg = numbers[kHorizontal];
  row.lmax_uncertainty_cd_m2 = numbers[kLmaxUncertainty];
  row.vertical_uncertainty_deg = numbers[kVerticalUncertainty];
  row.horizontal_uncertainty_deg = numbers[kHorizontalUncertainty];
  row.alpha_uncertainty_deg = numbers[kAlphaUncertainty];
  row.fwhm_vertical_deg = numbers[kFwhmVertical];
  row.fwhm_horizontal_deg = numbers[kFwhmHorizontal];
  const std::string glare = field(header, fields, kGlare);
  if (glare == "true" || glare == "false") row.glare = glare == "true";
  row.lmax_bound = field(header, fields, kLmaxBound);
  if (!row.lmax_bound.empty() && row.lmax_bound != "lower" && row.lmax_bound != "upper")
    return badInput("lmax_bound: expected lower, upper or nothing, got \"" + row.lmax_bound + "\"");
  row.limit_status = field(header, fields, kLimitStatus);
  const std::string consistent = field(header, fields, kFramesConsistent);
  if (!consistent.empty() && consistent != "true" && consistent != "false")
    return badInput("frames_consistent: expected true, false or nothing, got \"" + consistent +
                    "\"");
  if (!consistent.empty()) row.frames_consistent = consistent == "true";
  row.suspect = field(header, fields, kSuspect);
  row.camera_backend = field(header, fields, kCameraBackend);
  row.camera_serial = field(header, fields, kCameraSerial);
  row.module = field(header, fields, kModule);
  for (auto [column, size] : {std::pair{kWidth, &row.width}, {kHeight, &row.height}}) {
    const std::string text = field(header, fields, column);
    if (text.empty()) continue;
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < 1)
      return badInput(fmt::format("{}: expected a whole number of pixels, got \"{}\"",
                                  kColumnNames[column], text));
    *size = value;
  }
  row.calibration_id = field(header, fields, kCalibrationId);
  row.calibration_date = field(header, fields, kCalibrationDate);
  row.luminance_factor = numbers[kLuminanceFactor];
  row.luminance_factor_u = numbers[kLuminanceFactorU];
  if (row.luminance_factor_u && *row.luminance_factor_u < 0)
    return badInput(
        fmt::format("luminance_factor_u: {} must not be negative", *row.luminance_factor_u));
  GLARECAM_CHECK(parseRowIlluminance(header, fields, numbers, row));
  if (row.frames_consistent == false && row.suspect.empty())
    row.suspect = "frames disagree with the merge";
  row.route = field(header, fields, kRoute);
  if (!row.route.empty() && !routeFromString(row.route))
    return badInput(fmt::format("route: \"{}\" is not camera or brdf", row.route));
  row.stack_id = field(header, fields, kStackId);
  row.stack = field(header, fields, kStack);
  return row;
}

// Text on one line: the table is read line by line, so a line break in a note or a field (a stack
// path may hold one) would break it; it becomes a space.
std::string oneLine(std::string text) {
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return text;
}

template <typename Fields>
std::string csvLine(const Fields& fields) {
  std::string line;
  bool first = true;
  for (std::string_view f : fields) {
    if (!first) line += ',';
    line.append(f);
    first = false;
  }
  return line + '\n';
}

std::string number(const std::optional<double>& value) {
  return value ? fmt::format("{}", *value) : std::string();  // shortest exact form
}

}  // namespace

GlareLimit inferGlareLimit(const SweepTable& table, std::string* warning) {
  // Tables written by hand or by other tools may round the limit.
  constexpr double kSameLimitRelative = 1e-5;
  const auto same = [](double a, double b) { return std::abs(a - b) <= kSameLimitRelative * b; };
  bool curve = true;
  std::optional<double> constant;
  bool one_constant = true;
  for (const SweepRow& row : table.rows) {
    if (!row.limit_cd_m2) continue;
    const auto expected = glareLimitCdM2(row.alpha_deg);
    curve = curve && expected && same(*row.limit_cd_m2, *expected);
    if (!constant) constant = row.limit_cd_m2;
    one_constant = one_constant && same(*row.limit_cd_m2, *constant);
  }
  if (curve || !constant) return {};
  if (one_constant) return {.constant_cd_m2 = constant};
  if (warning)
    *warning =
        "the rows' limit_cd_m2 follow neither the α curve nor one constant; the sheet and "
        "profile use the α curve";
  return {};
}

Result<SweepTable> readSweepTable(const std::filesystem::path& path) {
  SweepTable table;
  std::optional<Header> header;
  GLARECAM_CHECK(readCsvFile(
      path, "sweep table",
      [&](std::vector<std::string>& fields) -> Status {
        if (!header) {
          GLARECAM_ASSIGN(header, parseHeader(fields));
          return {};
        }
        SweepRow row;
        GLARECAM_ASSIGN(row, parseRow(*header, fields));
        table.rows.push_back(std::move(row));
        return {};
      },
      [&](std::string comment) { table.notes.push_back(std::move(comment)); }));
  if (!header) return badInput(path.string() + ": empty sweep table (no header line)");
  if (table.rows.empty()) return badInput(path.string() + ": the sweep table has no rows");
  return table;
}

std::string formatSweepTable(const SweepTable& table) {
  std::string text;
  for (const std::string& note : table.notes) text += "# " + oneLine(note) + "\n";
  text += csvLine(kColumnNames);
  std::vector<SweepRow> rows = table.rows;
  std::stable_sort(rows.begin(), rows.end(),
                   [](const SweepRow& a, const SweepRow& b) { return a.alpha_deg < b.alpha_deg; });
  for (const SweepRow& r : rows) {
    const std::array<std::string, kColumnCount> fields{
        number(r.alpha_deg),
        number(r.limit_cd_m2),
        number(r.lmax_cd_m2),
        number(r.vertical_deg),
        number(r.horizontal_deg),
        number(r.lmax_uncertainty_cd_m2),
        number(r.vertical_uncertainty_deg),
        number(r.horizontal_uncertainty_deg),
        number(r.alpha_uncertainty_deg),
        number(r.fwhm_vertical_deg),
        number(r.fwhm_horizontal_deg),
        r.glare ? (*r.glare ? "true" : "false") : "",
        r.lmax_bound,
        quoteCsvField(oneLine(r.limit_status)),
        r.frames_consistent ? (*r.frames_consistent ? "true" : "false") : "",
        quoteCsvField(oneLine(r.suspect)),
        quoteCsvField(oneLine(r.camera_backend)),
        quoteCsvField(oneLine(r.camera_serial)),
        quoteCsvField(oneLine(r.module)),
        r.width ? std::to_string(*r.width) : "",
        r.height ? std::to_string(*r.height) : "",
        quoteCsvField(oneLine(r.calibration_id)),
        quoteCsvField(oneLine(r.calibration_date)),
        number(r.luminance_factor),
        number(r.luminance_factor_u),
        number(r.source_illuminance_lx),
        number(r.source_illuminance_u_lx),
        r.isReferred() ? r.source_origin : std::string(kUnreferredWord),
        number(r.reference_illuminance_lx),
        r.route.empty() ? std::string("camera") : r.route,
        quoteCsvField(oneLine(r.stack_id)),
        quoteCsvField(oneLine(r.stack))};
    text += csvLine(fields);
  }
  return text;
}

Status validateSweepAlpha(std::optional<double> alpha_deg) {
  if (!alpha_deg) return badInput("alpha_deg is missing; a sweep needs the angle of incidence");
  if (*alpha_deg < 0 || *alpha_deg >= kMaxAlphaDeg)
    return badInput(fmt::format("alpha_deg {} is outside [0, 90)", *alpha_deg));
  return {};
}

namespace {

// "frames disagree: frame-03.png reads 17.1 times, ..." from result.json's frames check.
std::string disagreeingFrames(const StackResult& result) {
  std::string reason = "frames disagree with the merge";
  std::string sep = ": ";
  for (const ResultFrame& frame : result.frames) {
    if (frame.agrees != false) continue;
    reason += sep + frame.file;
    if (frame.median_ratio) reason += " reads " + formatFrameRatio(*frame.median_ratio);
    sep = ", ";
  }
  return reason;
}

std::optional<double> axis(const std::optional<ResultEllipse>& ellipse,
                           double ResultEllipse::*field) {
  return ellipse ? std::optional((*ellipse).*field) : std::nullopt;
}

}  // namespace

Result<SweepRow> sweepRowFromResult(const StackResult& result, const std::string& stack) {
  GLARECAM_CHECK(validateSweepAlpha(result.alpha_deg));
  const ResultLuminance& luminance = result.luminance;
  if (!(luminance.max_cd_m2 > 0)) return badInput("no positive luminance maximum in the result");
  SweepRow row;
  row.alpha_deg = *result.alpha_deg;
  row.alpha_uncertainty_deg = result.alpha_uncertainty_deg;
  row.lmax_cd_m2 = luminance.max_cd_m2;
  row.limit_cd_m2 = result.limit.limit_cd_m2;
  // The row's own uncertainty: the merge's noise and, for a referred row, u(E), which differs
  // from row to row (each stack its own reading). u(K), common to every row, moves the whole
  // sweep alike and stays out (the sheet states it with the calibration). The BRDF route's "K"
  // is 1 exactly and its u the grid's interpolation, which is each row's own (brdf/brdf_route.h).
  const ResultIlluminance& illuminance = result.illuminance;
  const double e_u = illuminance.referred() ? illuminance.source->relativeUncertainty() : 0.0;
  const CalibrationIdentity& calibration = result.calibration;
  const double grid_u = result.route == Route::kBrdf && calibration.luminance_factor_u &&
                                calibration.luminance_factor > 0
                            ? *calibration.luminance_factor_u / calibration.luminance_factor
                            : 0.0;
  if (luminance.max_relative_uncertainty)
    row.lmax_uncertainty_cd_m2 =
        std::hypot(*luminance.max_relative_uncertainty, e_u, grid_u) * luminance.max_cd_m2;
  if (illuminance.referred()) {
    row.source_illuminance_lx = illuminance.source->illuminance_lx;
    row.source_illuminance_u_lx = illuminance.source->illuminance_u_lx;
    row.source_origin = std::string(originWord(illuminance.source->origin));
    row.reference_illuminance_lx = illuminance.reference_lx;
  } else {
    row.source_origin = kUnreferredWord;
  }
  const std::optional<ResultEllipse>& limit = result.limit.ellipse;
  row.vertical_deg = axis(limit, &ResultEllipse::vertical_deg);
  row.horizontal_deg = axis(limit, &ResultEllipse::horizontal_deg);
  row.vertical_uncertainty_deg = axis(limit, &ResultEllipse::vertical_uncertainty_deg);
  row.horizontal_uncertainty_deg = axis(limit, &ResultEllipse::horizontal_uncertainty_deg);
  row.fwhm_vertical_deg = axis(result.fwhm.ellipse, &ResultEllipse::vertical_deg);
  row.fwhm_horizontal_deg = axis(result.fwhm.ellipse, &ResultEllipse::horizontal_deg);
  row.glare = result.glare;
  if (luminance.isLowerBound()) row.lmax_bound = "lower";
  if (luminance.isUpperBound()) row.lmax_bound = "upper";
  row.limit_status = result.limit.status ? toString(*result.limit.status) : "no_limit";
  row.frames_consistent = luminance.frames_consistent;
  if (row.frames_consistent == false) row.suspect = disagreeingFrames(result);
  row.camera_backend = result.cameraText("backend");
  row.camera_serial = result.cameraText("serial");
  row.module = result.module.value_or("");
  row.calibration_id = result.calibration.id;
  row.calibration_date = newestPartDate(result.calibration);
  row.luminance_factor = result.calibration.luminance_factor;
  row.luminance_factor_u = result.calibration.luminance_factor_u;
  row.width = result.width;
  row.height = result.height;
  row.route = toString(result.route);
  row.stack_id = result.stack;
  row.stack = stack;
  return row;
}

void sortByAlpha(SweepTable& table) {
  std::stable_sort(table.rows.begin(), table.rows.end(),
                   [](const SweepRow& a, const SweepRow& b) { return a.alpha_deg < b.alpha_deg; });
}

bool isSimulated(const SweepTable& table) {
  return std::ranges::any_of(table.rows,
                             [](const SweepRow& row) { return row.camera_backend == "sim"; });
}

namespace {

std::vector<std::string> distinctValues(const SweepTable& table,
                                        const std::function<std::string(const SweepRow&)>& of) {
  std::vector<std::string> values;
  for (const SweepRow& row : table.rows) {
    std::string value = of(row);
    if (!value.empty() && std::ranges::find(values, value) == values.end())
      values.push_back(std::move(value));
  }
  return values;
}

}  // namespace

std::vector<std::string> tableCameras(const SweepTable& table) {
  return distinctValues(table, [](const SweepRow& row) {
    return row.camera_serial.empty() ? row.camera_backend
                                     : row.camera_backend + " " + row.camera_serial;
  });
}

std::vector<std::string> tableFrameSizes(const SweepTable& table) {
  return distinctValues(table, [](const SweepRow& row) {
    return row.width && row.height ? fmt::format("{}x{}", *row.width, *row.height) : std::string();
  });
}

std::string routeText(const SweepRow& row) { return row.route.empty() ? "camera" : row.route; }

std::vector<std::string> tableRoutes(const SweepTable& table) {
  std::vector<std::string> routes;
  for (const SweepRow& row : table.rows)
    if (std::ranges::find(routes, routeText(row)) == routes.end()) routes.push_back(routeText(row));
  return routes;
}

std::string referenceText(const SweepRow& row) {
  return row.isReferred() ? fmt::format("{:g} klx", *row.reference_illuminance_lx / 1000)
                          : std::string(kUnreferredWord);
}

std::vector<std::string> tableReferences(const SweepTable& table) {
  return distinctValues(table, referenceText);
}

std::string mixedReferences(const SweepTable& table) {
  const std::vector<std::string> references = tableReferences(table);
  if (references.size() < 2) return {};
  // The largest group is the table's; the others are named row by row (a few, then a count).
  constexpr std::size_t kRowsNamed = 4;
  std::vector<std::vector<const SweepRow*>> groups(references.size());
  for (const SweepRow& row : table.rows)
    groups[std::ranges::find(references, referenceText(row)) - references.begin()].push_back(&row);
  const std::size_t largest =
      std::ranges::max_element(groups, {}, &std::vector<const SweepRow*>::size) - groups.begin();
  std::string text;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const bool referred = groups[g].front()->isReferred();
    text += fmt::format("{}{} row(s) {}{}", text.empty() ? "" : "; ", groups[g].size(),
                        referred ? "referred to " : "", references[g]);
    if (g == largest) continue;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < groups[g].size() && i < kRowsNamed; ++i) {
      const SweepRow& row = *groups[g][i];
      names.push_back(
          fmt::format("{} (α {:g}°)", row.stack_id.empty() ? "?" : row.stack_id, row.alpha_deg));
    }
    if (groups[g].size() > kRowsNamed)
      names.push_back(fmt::format("and {} more", groups[g].size() - kRowsNamed));
    text += fmt::format(": {}", fmt::join(names, ", "));
  }
  return text;
}

SweepTable rowsOfOneReference(const SweepTable& table, std::string* left_out) {
  const std::string mixed = mixedReferences(table);
  if (mixed.empty()) return table;
  std::map<std::string, std::size_t> counts;
  for (const SweepRow& row : table.rows)
    if (row.isReferred()) ++counts[referenceText(row)];
  std::string kept = kUnreferredWord;
  std::size_t most = 0;
  for (const std::string& reference : tableReferences(table)) {  // first seen wins a tie
    const auto it = counts.find(reference);
    if (it != counts.end() && it->second > most) {
      kept = it->first;
      most = it->second;
    }
  }
  SweepTable one;
  one.notes = table.notes;
  for (const SweepRow& row : table.rows)
    if (referenceText(row) == kept) one.rows.push_back(row);
  if (left_out)
    *left_out = fmt::format("{} row(s) not referred to {} left out ({})",
                            table.rows.size() - one.rows.size(), kept, mixed);
  return one;
}

std::optional<double> tableReferenceIlluminance(const SweepTable& table) {
  if (table.rows.empty() || !mixedReferences(table).empty()) return std::nullopt;
  return table.rows.front().reference_illuminance_lx;
}

std::string sourceIlluminanceRange(const SweepTable& table) {
  std::optional<double> low, high;
  for (const SweepRow& row : table.rows) {
    if (!row.source_illuminance_lx) continue;
    low = std::min(low.value_or(*row.source_illuminance_lx), *row.source_illuminance_lx);
    high = std::max(high.value_or(*row.source_illuminance_lx), *row.source_illuminance_lx);
  }
  if (!low) return {};
  const std::vector<std::string> origins = distinctValues(
      table, [](const SweepRow& row) { return row.isReferred() ? row.source_origin : ""; });
  const std::string range = *low == *high
                                ? fmt::format("{:.1f} klx", *low / 1000)
                                : fmt::format("{:.1f}–{:.1f} klx", *low / 1000, *high / 1000);
  return fmt::format("{} ({})", range, fmt::join(origins, ", "));
}

std::vector<std::string> tableCalibrations(const SweepTable& table) {
  return distinctValues(table, [](const SweepRow& row) { return row.calibration_id; });
}

std::vector<std::string> tableModules(const SweepTable& table) {
  return distinctValues(table, [](const SweepRow& row) { return row.module; });
}

std::string calibrationSummary(const SweepRow& row) {
  if (row.calibration_id.empty()) return {};
  std::string text = row.calibration_id;
  if (!row.calibration_date.empty()) text += " of " + row.calibration_date;
  if (row.luminance_factor) {
    text += fmt::format(", K {:.5g}", *row.luminance_factor);
    if (row.luminance_factor_u) text += fmt::format(" \u00b1 {:.3g}", *row.luminance_factor_u);
    text += " cd/m\u00b2 per DN/\u00b5s";
  }
  return text;
}

std::vector<std::string> tableCalibrationSummaries(const SweepTable& table) {
  return distinctValues(table, calibrationSummary);
}

}  // namespace glarecam::pipeline
