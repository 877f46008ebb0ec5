// The sweep table (docs/stack-format.md, "Sweep table"): one row per stack of a sweep over the
// angle of incidence, as `glarecam sweep` writes it and `glarecam fit` / `datasheet` read it.
// Required columns: alpha_deg, limit_cd_m2, lmax_cd_m2, vertical_deg, horizontal_deg (an axis or
// the limit may be empty); the extra columns below are written by glarecam and optional on read.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/source_illuminance.h"
#include "pipeline/limit_curve.h"
#include "pipeline/result.h"

namespace glarecam::pipeline {

struct SweepRow {
  double alpha_deg = 0;
  std::optional<double> limit_cd_m2;  // empty: no limit at this α (above 80°)
  double lmax_cd_m2 = 0;
  std::optional<double> vertical_deg, horizontal_deg;  // empty: no limit ellipse
  // Extras (optional columns).
  std::optional<double> lmax_uncertainty_cd_m2;
  std::optional<double> vertical_uncertainty_deg, horizontal_uncertainty_deg;
  std::optional<double>
      alpha_uncertainty_deg;  // the rig's (inclinometer, clock); the sheet rounds α to it
  std::optional<double> fwhm_vertical_deg, fwhm_horizontal_deg;
  std::optional<bool> glare;
  std::string lmax_bound;    // "lower" (saturated top) or "upper" (all dark): Lmax only a bound
  std::string limit_status;  // result.json's limit.status, e.g. "measured", "below_level"
  // result.json's luminance.frames_consistent: false when a frame disagrees with the merge.
  std::optional<bool> frames_consistent;
  // Why the row's numbers are suspect ("frames disagree: frame-03.png reads +1610 %"), empty when
  // they are not. The fits leave suspect rows out unless asked (FitOptions::include_suspect).
  std::string suspect;
  // What the row was measured with (result.json's camera, image and calibration.id): a sweep
  // refuses to mix them unless asked, and a sheet of a simulated camera says so.
  std::string camera_backend, camera_serial;
  std::string module;  // result.json's module: the stack's module name or serial
  std::optional<int> width, height;
  std::string calibration_id;
  // What the calibration rests on (result.json's calibration block): the day its newest part was
  // measured (YYYY-MM-DD) and K with its standard uncertainty.
  std::string calibration_date;
  std::optional<double> luminance_factor, luminance_factor_u;
  // What the row's luminances and axes refer to (result.json's illuminance): the source's E and
  // u(E), its origin (sensor, given, clear_sky; "unreferred" or empty when there is none) and
  // E_ref. Referred and unreferred rows, or rows of two references, never mix in one table.
  std::optional<double> source_illuminance_lx, source_illuminance_u_lx;
  std::string source_origin;
  std::optional<double> reference_illuminance_lx;
  // How the row was measured (result.json's route): "camera", "brdf"; empty in tables written
  // before the BRDF route (the camera's).
  std::string route;
  std::string stack_id, stack;
  bool isSuspect() const { return !suspect.empty(); }
  bool isReferred() const { return reference_illuminance_lx.has_value(); }
};

struct SweepTable {
  std::vector<SweepRow> rows;      // as read; sorted by α when written
  std::vector<std::string> notes;  // '#' comment lines (without the '#'), e.g. skipped stacks
};

// Reads and validates a sweep table: header with the required columns (any order, extra columns
// ignored), numbers finite, α in [0, 90), Lmax > 0, axes > 0. Errors name the file and line.
Result<SweepTable> readSweepTable(const std::filesystem::path& path);

// The rows in order of α (rows at one α keep their order).
void sortByAlpha(SweepTable& table);

// The limit the table's rows were measured against: the α curve when every row's limit is the
// curve's (or empty), else the constant all rows share; `warning` is set when the rows mix limits
// (the α curve is then assumed).
GlareLimit inferGlareLimit(const SweepTable& table, std::string* warning = nullptr);

// True when any row was measured with the simulated camera (camera_backend "sim"): a sheet or
// profile made from it must say so, so that it can never pass for a measurement.
bool isSimulated(const SweepTable& table);
// What every output made from such rows says beside its SIMULATED mark.
inline constexpr const char* kSimulatedNote = "stacks of the simulated camera: not a measurement";

// The word sweep.csv's source_origin and the outputs use for a row without a source illuminance.
inline constexpr const char* kUnreferredWord = "unreferred";
// What every output made from unreferred rows says beside its UNREFERRED mark.
inline constexpr const char* kUnreferredNote =
    "at the day's own sun, not referred to a stated source illuminance";

// The row's route ("camera" when the table does not say) and the distinct routes of the rows, in
// order: a sheet names its route, and one made of both routes says so.
std::string routeText(const SweepRow& row);
std::vector<std::string> tableRoutes(const SweepTable& table);

// What a row refers to, as people read it: "100 klx" or "unreferred".
std::string referenceText(const SweepRow& row);
// The distinct references of the rows, in order ("100 klx", "unreferred").
std::vector<std::string> tableReferences(const SweepTable& table);
// Empty when every row refers to one reference (or every row is unreferred); else what mixes,
// naming the rows of each ("10 rows referred to 100 klx; 2 unreferred: stacks s-07 (α 45°),
// s-08 (α 50°)"): their luminances are not on one scale, so no fit or sheet can use them together
// (docs/method.md "Reference illuminance").
std::string mixedReferences(const SweepTable& table);
// The rows of one reference out of a mixed table: the referred rows of the most common reference
// (unreferred rows only when no row is referred), and a note naming what was left out; the table
// itself and no note when it does not mix. What a rig's day sheet uses when its instrument failed
// for some stacks: they stay in the day's sweep.csv, not in its fits.
SweepTable rowsOfOneReference(const SweepTable& table, std::string* left_out = nullptr);
// The reference every row shares, when they share one (none when unreferred or mixed).
std::optional<double> tableReferenceIlluminance(const SweepTable& table);
// The range and origins of the rows' source illuminances: "61.2–98.4 klx (sensor)"; empty when
// no row is referred.
std::string sourceIlluminanceRange(const SweepTable& table);

// The distinct cameras ("sim SIM-0001"), frame sizes ("320x256"), calibration ids and modules of
// the rows, in order, empty ones left out.
std::vector<std::string> tableCameras(const SweepTable& table);
std::vector<std::string> tableFrameSizes(const SweepTable& table);
std::vector<std::string> tableCalibrations(const SweepTable& table);
std::vector<std::string> tableModules(const SweepTable& table);

// One line for a row's calibration, as the sheet states it: "55e5f09d95ab9da6 of 2026-06-21,
// K 1500 ± 18.9 cd/m² per DN/µs" (the parts the row knows); empty without an id.
std::string calibrationSummary(const SweepRow& row);
// The distinct calibration summaries of the rows, in order.
std::vector<std::string> tableCalibrationSummaries(const SweepTable& table);

// The table as CSV text, rows sorted by α, notes as leading '#' lines.
std::string formatSweepTable(const SweepTable& table);

// A sweep row's α: present and in [0, 90) (the cosine function is undefined at 90°).
Status validateSweepAlpha(std::optional<double> alpha_deg);

// The row of one processed stack (at path `stack`) from its result (result.h); kBadInput when the
// result's α is missing or invalid (a sweep needs one). Errors do not repeat the stack's path: the
// caller names it.
Result<SweepRow> sweepRowFromResult(const StackResult& result, const std::string& stack);

}  // namespace glarecam::pipeline
