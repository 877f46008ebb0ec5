// The result document of one processed stack, schema glarecam.result/1 (docs/process.md, "The
// result document"), as one value type with one writer and one reader:
//   makeResult()      the document of a processed stack, from the analysis' plain values
//   toJson()          its text form: every field, null where there is no value
//   resultFromJson()  the reader: the schema checked and every field validated (type, range, the
//                     statuses and methods among the known words), one error naming the file and
//                     the field; toJson(*resultFromJson(toJson(r))) == toJson(r)
// Everything that reads a result (the sweep's rows, the daemon's status, `process --json`) reads
// this type, so a renamed or mistyped key fails loudly in one place.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/frame_consistency.h"
#include "core/error.h"
#include "core/generator.h"
#include "core/json.h"
#include "core/source_illuminance.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/luminance_stats.h"

namespace glarecam::pipeline {

inline constexpr std::string_view kResultSchema = "glarecam.result/1";

// The bounds the readers of measured ellipses hold them to (result.json, the sweep table): a full
// axis is an angle between two rays, at most 180°; an orientation is within ±90°.
inline constexpr double kMaxAxisDeg = 180.0;
inline constexpr double kMaxOrientationDeg = 90.0;

// One measured ellipse (glare_ellipse.h's GlareEllipse as written): full axes in degrees, the
// centre in pixels and as a direction, the fit's quality and the standard uncertainties.
struct ResultEllipse {
  double vertical_deg = 0, horizontal_deg = 0, major_deg = 0, minor_deg = 0;
  double orientation_deg = 0;
  std::array<double, 2> center_px{};             // x, y
  std::array<double, 2> center_direction_deg{};  // horizontal, vertical
  std::array<double, 2> semi_axes_px{};          // major, minor
  double solid_angle_sr = 0;
  double fit_rms_px = 0, fit_rms_deg = 0, shape_residual = 0;
  bool ellipticity_ok = false, truncated = false;
  long long regions = 0, contour_points = 0, region_pixels = 0, smoothing_radius_px = 0;
  double vertical_uncertainty_deg = 0, horizontal_uncertainty_deg = 0;
  std::optional<double> orientation_uncertainty_deg = std::nullopt;  // none for a circle
  double solid_angle_uncertainty_sr = 0;
  long long unweighted_contour_points = 0;
  bool operator==(const ResultEllipse&) const = default;
};

ResultEllipse resultEllipse(const GlareEllipse& ellipse);

// An ellipse at one luminance level (the FWHM, a threshold): why there is none, or the ellipse.
struct ResultLevel {
  double level_cd_m2 = 0;
  EllipseStatus status = EllipseStatus::kBelowLevel;
  std::optional<ResultEllipse> ellipse = std::nullopt;  // exactly when status is kMeasured
  bool operator==(const ResultLevel&) const = default;
};

// One rung of the contour ladder (glare_analysis.h): its kind and the ellipse at its level (with
// its σ; the fixed rungs' and the limit's include u(E) when referred, the half maximum's the
// peak's), or the status saying why there is none.
struct ResultContour {
  ContourKind kind = ContourKind::kLadder;
  ResultLevel level;
  bool operator==(const ResultContour&) const = default;
};

// How the stack's limit was set: the α curve, a constant (--threshold), or none (no α).
enum class LimitMode { kAlphaCurve, kConstant, kNone };
const char* toString(LimitMode mode);

// The limit ellipse: the level is the glare limit; no limit is status "no_limit" (nullopt here).
struct ResultLimit {
  std::optional<double> limit_cd_m2 = std::nullopt;
  LimitMode mode = LimitMode::kNone;
  std::optional<EllipseStatus> status = std::nullopt;  // nullopt: no limit
  std::optional<ResultEllipse> ellipse = std::nullopt;
  bool operator==(const ResultLimit&) const = default;
};

// What a result's luminances refer to (docs/method.md "Reference illuminance and the contour
// ladder"): referred to `reference_lx` through the stack's source illuminance, L_ref = L ·
// E_ref / E, or unreferred (no source: at face value, and never mixed with referred results).
struct ResultIlluminance {
  std::optional<SourceIlluminance> source = std::nullopt;  // none: unreferred
  std::optional<double> reference_lx = std::nullopt;       // exactly when there is a source
  bool referred() const { return source.has_value(); }
  // E_ref / E: what the measured luminances were multiplied by (1 when unreferred).
  double factor() const { return referred() ? *reference_lx / source->illuminance_lx : 1.0; }
  bool operator==(const ResultIlluminance&) const = default;
};

// "referred to 100 klx (source 92.5 ± 2.8 klx, sensor)" or "unreferred".
std::string describe(const ResultIlluminance& illuminance);

struct ResultLuminance {
  double max_cd_m2 = 0;  // referred when the result is
  // The maximum as measured, under the stack's own source (only when referred; else max_cd_m2).
  std::optional<double> measured_max_cd_m2 = std::nullopt;
  std::array<long long, 2> max_pixel{};  // max_position_px rounded
  std::array<double, 2> max_position_px{};
  PeakMethod max_method = PeakMethod::kQuadraticFit;
  std::optional<double> max_relative_uncertainty = std::nullopt;  // the merge's noise
  // With the uncertainties of the absolute scale: u(K) and, when referred, u(E), those known
  // (none when neither is).
  std::optional<double> max_relative_uncertainty_combined = std::nullopt;
  double valid_fraction = 0;
  long long saturated_pixels = 0, dark_pixels = 0, masked_pixels = 0;
  double median_relative_uncertainty = 0;
  // true: every frame checked and agreeing; false: one disagrees; nullopt: some frame could not
  // be checked (and none disagrees).
  std::optional<bool> frames_consistent = std::nullopt;
  bool isLowerBound() const { return max_method == PeakMethod::kLowerBound; }
  bool isUpperBound() const { return max_method == PeakMethod::kUpperBound; }
  bool operator==(const ResultLuminance&) const = default;
};

// A frame's agreement with the merge: median ratio (nullopt: too few samples to judge).
struct ResultFrame {
  std::string file = {};
  std::optional<double> median_ratio = std::nullopt;
  long long samples = 0;
  std::optional<bool> agrees = std::nullopt;  // nullopt with the ratio
  bool operator==(const ResultFrame&) const = default;
};

// A frame's median ratio against the other frames in words: "+9 %" or "-40 %" within a factor of
// 2 of them, else the factor: "17.1 times" or "1/500 of" (what a wrong or swapped exposure gives).
std::string formatFrameRatio(double median_ratio);

// The pairs of frames (indices into `median_ratios`, first < second) that look swapped: both
// disagree with the others by more than a factor of 2, in opposite directions and by the same
// factor to within 25 % (a swap makes one read r and the other about 1/r).
std::vector<std::pair<std::size_t, std::size_t>> swappedFramePairs(
    const std::vector<double>& median_ratios);

// A part of the calibration (dark, flat, luminance, ...): when and how it was measured.
struct CalibrationPart {
  std::optional<std::string> measured_at = std::nullopt;  // ISO 8601
  std::optional<std::string> method = std::nullopt;
  bool operator==(const CalibrationPart&) const = default;
};

// What a result's numbers rest on: the calibration's identity and its absolute scale K.
struct CalibrationIdentity {
  std::string origin = {};  // "inline", the manifest's path as written, or --calibration
  std::optional<std::string> file = std::nullopt;    // the file read, absolute (absent: inline)
  std::optional<std::string> sha256 = std::nullopt;  // of that file's bytes
  nlohmann::json camera = nullptr;  // the calibration's camera block (model, serial), or null
  std::optional<std::map<std::string, CalibrationPart>> parts = std::nullopt;
  // The calibration's values as used, in a short stable form: the first 16 hex digits of the
  // SHA-256 of the block's JSON with sorted keys. Equal for a file and its inline copy; what a
  // sweep compares to refuse mixing calibrations.
  std::string id = {};
  double luminance_factor = 0;                              // K
  std::optional<double> luminance_factor_u = std::nullopt;  // u(K), when the calibration has it
  bool noise_model_assumed = false;
  bool dark_frame = false;  // black subtracted pixel by pixel (else the black level)
  bool hot_pixels = false;  // the calibration's hot pixels masked out of the merge
  bool operator==(const CalibrationIdentity&) const = default;
};

// The day (YYYY-MM-DD) the newest of the parts was measured, or "" when none says.
std::string newestPartDate(const CalibrationIdentity& calibration);

// The files `process` writes beside result.json. A rig's retention may prune them from a past
// day's result to free space (daemon/storage/retention.h): `pruned_at` then says when, and the
// files named are gone (or, after a prune cut short, going): the numbers stay in result.json.
struct ResultOutputs {
  std::string luminance_exr = "luminance.exr";
  std::string quality_exr = "quality.exr";
  std::string luminance_png = "luminance.png";
  std::optional<std::string> pruned_at = std::nullopt;  // ISO 8601, UTC
  bool pruned() const { return pruned_at.has_value(); }
  // The three file names, in the order process writes them.
  std::array<std::string, 3> files() const { return {luminance_exr, quality_exr, luminance_png}; }
  bool operator==(const ResultOutputs&) const = default;
};

// How a result was measured (docs/brdf.md): the camera route (a stack photographed under the sun
// or a lamp) or the BRDF route (a goniophotometer's file seen under the reference sun).
enum class Route { kCamera, kBrdf };
const char* toString(Route route);  // "camera", "brdf"
std::optional<Route> routeFromString(std::string_view text);

struct StackResult {
  std::string stack = {};  // the stack's id (the BRDF route: the file and its θ_i)
  Route route = Route::kCamera;
  std::optional<double> alpha_deg = std::nullopt;
  // "manifest", "given" or (the BRDF route) "measurement"; none without α.
  std::optional<std::string> alpha_source = std::nullopt;
  std::optional<double> alpha_uncertainty_deg = std::nullopt;
  int width = 0, height = 0;        // image
  nlohmann::json camera = nullptr;  // the manifest's camera block (backend, model, serial), or null
  std::optional<std::string> module = std::nullopt;
  CalibrationIdentity calibration;
  ResultIlluminance illuminance;
  ResultLuminance luminance;
  std::vector<ResultFrame> frames = {};
  ResultLimit limit;
  ResultLevel fwhm;
  std::vector<ResultLevel> thresholds = {};  // in the order asked
  // The contour ladder by ascending level; none when it was not computed (`process --no-ladder`,
  // or a result written before the ladder existed).
  std::optional<std::vector<ResultContour>> contours = std::nullopt;
  // Lmax at or above the limit; nullopt without a limit, or when a bound cannot decide.
  std::optional<bool> glare = std::nullopt;
  ResultOutputs outputs;
  // The BRDF route's account of its input (brdf_route.h: the file, its grid and noise, the
  // Gaussian approximation); null on the camera route.
  nlohmann::json brdf = nullptr;
  Generator generator;
  bool operator==(const StackResult&) const = default;

  // The camera block's text field `key` ("backend", "serial", "model"), or "".
  std::string cameraText(std::string_view key) const;
};

struct FrameCheck {
  std::string file = {};
  calibration::FrameAgreement agreement;
};

struct ResultInputs {
  std::string stack_id = {};
  Route route = Route::kCamera;
  nlohmann::json brdf = nullptr;  // the BRDF route's block
  std::optional<double> alpha_deg = std::nullopt;
  // "manifest", "given" (process --alpha), "measurement" (a BRDF file's θ_i), or empty: no α.
  std::string alpha_source = {};
  // The manifest's geometry.alpha_uncertainty_deg (inclinometer and clock), when α is its.
  std::optional<double> alpha_uncertainty_deg = std::nullopt;
  nlohmann::json camera = nullptr;  // the manifest's camera block (backend, model, serial), or null
  std::optional<std::string> module = std::nullopt;  // the manifest's module, when it names one
  int width = 0, height = 0;
  CalibrationIdentity calibration;
  ResultIlluminance illuminance;  // the stats and glare below are referred when it is
  LuminanceStats stats;
  std::vector<FrameCheck> frames = {};
  std::optional<double> limit_cd_m2 = std::nullopt;
  bool constant_limit = false;  // --threshold rather than the α curve
  GlareAnalysis glare;
  bool ladder = true;  // the analysis computed the contour ladder (its `ladder` may be empty)
};

StackResult makeResult(const ResultInputs& inputs);

nlohmann::json toJson(const StackResult& result);
// Reads a result document; `file` names it in errors.
Result<StackResult> resultFromJson(const nlohmann::json& document, const std::string& file);
// Reads result.json at `path`.
Result<StackResult> readResult(const std::filesystem::path& path);

// Whether `document` says it is a glarecam result (its schema), whatever else it holds: what may
// be overwritten or deleted as one.
bool hasResultSchema(const nlohmann::json& document);

}  // namespace glarecam::pipeline
