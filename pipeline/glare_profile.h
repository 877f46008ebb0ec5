// The module's glare profile (docs/glare-profile.md): Lmax and both limit-ellipse axes per 1° of
// α from the sweep's fits, the glare limit and whether the module glares, and the beam spread as
// glare-hazard tools model it: the circular cone of the same solid angle as the measured ellipse,
// and the surface slope error σ that gives that cone in beta = 2 (4.65 mrad + σ).
//
// Since /2 it also carries the contour ladder per whole degree of α (docs/method.md, "Reference
// illuminance and the contour ladder"), from the sweep's contours.csv, and says what its
// luminances refer to; contourAt() answers the contour at any α, level and source illuminance.
//
// The document, glarecam.glare-profile/2, is one value type (GlareProfile) with one writer
// (toJson) and one reader (glareProfileFromJson, readGlareProfile), which every consumer (the
// hazard calculation, tests, other tools through the docs) goes through. The reader accepts the
// versions in kGlareProfileSchemas and profiles written by earlier glarecam versions, which lack
// what was added since: only schema, module, glare_ranges_deg and profile (one row per whole
// degree 0–80, each with alpha_deg) are required; a row's other fields may be null or absent.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/generator.h"
#include "pipeline/contour_table.h"
#include "pipeline/glare_analysis.h"
#include "pipeline/glare_fits.h"
#include "pipeline/limit_curve.h"

namespace glarecam::pipeline {

inline constexpr const char* kGlareProfileFileName = "glare-profile.json";

// The sun's angular radius used by SGHAT-style tools (docs/method.md).
inline constexpr double kSunHalfAngleMrad = 4.65;

struct CircularBeamSpread {
  double solid_angle_sr = 0;    // of the elliptical cone with the measured full axes
  double beta_mrad = 0;         // full apex angle of the circular cone of that solid angle
  double slope_error_mrad = 0;  // σ with beta = 2 (4.65 mrad + σ); negative: narrower than the sun
  bool operator==(const CircularBeamSpread&) const = default;
};

// The equal-solid-angle circular cone of an elliptical cone with full axes in degrees (the
// ellipse lies in the azimuthal-equidistant angular plane, as glarecam measures it).
CircularBeamSpread circularBeamSpread(double vertical_deg, double horizontal_deg);

struct ProfileRow {
  double alpha_deg = 0;
  std::optional<double> lmax_cd_m2 =
      std::nullopt;  // from the better luminance fit (always written)
  std::optional<double> limit_cd_m2 = std::nullopt;
  bool glares = false;  // Lmax at or above the limit (as in result.json)
  std::optional<double> vertical_deg = std::nullopt,
                        horizontal_deg = std::nullopt;  // from the logistic fits, where glaring
  std::optional<CircularBeamSpread> beam = std::nullopt;
  bool extrapolated = false;  // outside the α range the given values were fitted on
  bool operator==(const ProfileRow&) const = default;
};

inline constexpr int kProfileAlphaMaxDeg = 80;  // the method is defined up to 80°
inline constexpr int kProfileStepDeg = 1;

std::vector<ProfileRow> glareProfile(const SweepFits& fits, const GlareLimit& limit);

struct AlphaRange {
  double from_deg = 0, to_deg = 0;
  bool operator==(const AlphaRange&) const = default;
};
inline constexpr double kGlareRangeResolutionDeg = 0.1;

// The α ranges within 0–80° where the fitted Lmax reaches the limit, to 0.1°: where the module
// glares by its data sheet (empty: nowhere).
std::vector<AlphaRange> glareRanges(const SweepFits& fits, const GlareLimit& limit);

// A full ellipse axis is an angle between two rays: (0, 180°]. A fitted axis curve outside it
// (a logistic extrapolated past its data falls below zero) is neither exported nor drawn.
inline constexpr double kMaxFullAxisDeg = 180.0;
bool isPhysicalAxisDeg(double axis_deg);

struct ProfileIdentity {
  std::string module = {};
  std::string date = {};    // ISO 8601
  std::string source = {};  // the sweep table's path
};

inline constexpr std::string_view kGlareProfileSchema = "glarecam.glare-profile/2";
inline constexpr std::string_view kGlareProfileSchemaV1 = "glarecam.glare-profile/1";
// The schemas glareProfileFromJson() reads.
inline constexpr std::initializer_list<std::string_view> kGlareProfileSchemas = {
    kGlareProfileSchema, kGlareProfileSchemaV1};

// One contour of the ladder at one α: a fixed rung (kind ladder) or the half maximum, its full
// axes, orientation (major axis from the horizontal, (-90°, 90°]), solid angle and their standard
// uncertainties, referred like the profile.
struct ProfileContour {
  double level_cd_m2 = 0;
  ContourKind kind = ContourKind::kLadder;
  double vertical_deg = 0, horizontal_deg = 0, orientation_deg = 0, solid_angle_sr = 0;
  double vertical_uncertainty_deg = 0, horizontal_uncertainty_deg = 0;
  std::optional<double> orientation_uncertainty_deg = std::nullopt;  // none for a circle
  double solid_angle_uncertainty_sr = 0;
  bool operator==(const ProfileContour&) const = default;
};

// The ladder at one whole degree of α, by ascending level. Between two measured stacks' α a
// rung's axes, orientation, solid angle and σ are linear in α, for the levels both measured (the
// half maximum's level log-linear); at a measured α they are that stack's (the mean of stacks at
// one α).
struct ProfileLadderRow {
  double alpha_deg = 0;
  std::vector<ProfileContour> contours = {};
  bool operator==(const ProfileLadderRow&) const = default;
};

// The ladder per whole degree of α, from a sweep's contour table (contour_table.h): the degrees
// within the measured α range (up to 80°), each with the rungs measured at both neighbouring α.
std::vector<ProfileLadderRow> profileLadder(const ContourTable& contours);

// A calibration the profile's rows rest on (by id, in the rows' order): its date and K ± u(K).
struct ProfileCalibration {
  std::string id = {};
  std::optional<std::string> date = std::nullopt;  // YYYY-MM-DD of its newest part
  std::optional<double> luminance_factor = std::nullopt, luminance_factor_u = std::nullopt;
  bool operator==(const ProfileCalibration&) const = default;
};

// A row of the sweep table, as the profile lists it for reference.
struct MeasuredRow {
  double alpha_deg = 0;
  std::optional<double> limit_cd_m2 = std::nullopt;
  double lmax_cd_m2 = 0;
  std::optional<std::string> lmax_bound = std::nullopt;  // "lower" or "upper": Lmax only a bound
  std::optional<double> vertical_deg = std::nullopt, horizontal_deg = std::nullopt;
  bool operator==(const MeasuredRow&) const = default;
};

// glarecam.glare-profile/1 (docs/glare-profile.md). Fields marked "since" may be absent in a
// profile of an earlier version, where the reader leaves them at their defaults.
struct GlareProfile {
  std::string module = {};
  std::optional<std::string> date = std::nullopt;    // YYYY-MM-DD
  std::optional<std::string> source = std::nullopt;  // the sweep table's path
  bool simulated = false;  // any row from the simulated camera: not a measurement
  // Since /2: how the rows were measured, "camera" and/or "brdf" (sweep_table.h's tableRoutes);
  // empty in a profile that does not record it.
  std::vector<std::string> routes = {};
  std::vector<std::string> cameras = {}, calibrations = {};
  std::vector<ProfileCalibration> calibration_details = {};
  std::optional<std::string> luminance_fit = std::nullopt;  // "cos" or "biquadratic"
  std::vector<AlphaRange> glare_ranges = {};                // within 0–80°, ascending
  GlareLimit limit;                                         // absent: the α curve
  double sun_half_angle_mrad = kSunHalfAngleMrad;
  std::vector<ProfileRow> rows = {};  // α = 0, 1, … kProfileAlphaMaxDeg, in order
  std::vector<MeasuredRow> measured = {};
  // Since /2: what the luminances refer to: true, referred to `reference_illuminance_lx` (every
  // row of the sweep referred to it); false, unreferred; nullopt, a /1 profile (it does not say;
  // written again as status "unstated").
  std::optional<bool> referred = std::nullopt;
  std::optional<double> reference_illuminance_lx = std::nullopt;  // exactly when referred
  // The sweep's source illuminances and where they came from, as the sheet says them: "61.2–98.4
  // klx (sensor)", "80.0 klx (given)", "… (clear_sky)"; empty when unreferred or unstated.
  std::string sources = {};
  // Since /2: the contour ladder per whole degree of α, ascending (empty: the sweep had none).
  std::vector<ProfileLadderRow> ladder = {};
  // The fits exactly as `glarecam fit --json` writes them (glarecam.fits/1, fitsJson()), or null.
  nlohmann::json fits = nullptr;
  std::optional<Generator> generator = std::nullopt;
  bool operator==(const GlareProfile&) const = default;
};

// The profile of a sweep's fits under `limit`, with the table's rows and identity, and the
// ladder of its contour table when given.
GlareProfile makeGlareProfile(const ProfileIdentity& identity, const SweepTable& table,
                              const SweepFits& fits, const GlareLimit& limit,
                              const ContourTable* contours = nullptr);

// The contour at angle of incidence `alpha_deg` and referred luminance `level_cd_m2` from the
// profile's ladder: linear in ln level between the two rungs around it (axes, orientation, solid
// angle, σ), then linear in α between the whole degrees around `alpha_deg`. None outside the
// ladder's α, above its highest rung at either degree (above the peak there is no contour; between
// the highest rung and the peak none is claimed) or below its lowest (none is claimed). The
// contour's kind is ladder unless both degrees' rungs at exactly that level are half maxima.
// Between rungs the axes' and the solid angle's standard uncertainties include the linear
// interpolation's own error, estimated from the parabola in ln level through the next rung.
std::optional<ProfileContour> contourAt(const GlareProfile& profile, double alpha_deg,
                                        double level_cd_m2);

// The contour where a source of direct normal illuminance `source_illuminance_lx` makes the
// luminance reach `level_cd_m2`: the referred contour at level · E_ref / E (docs/method.md).
// kBadInput when the profile is not referred (it cannot say) or E is not a positive number.
Result<std::optional<ProfileContour>> contourAt(const GlareProfile& profile, double alpha_deg,
                                                double level_cd_m2, double source_illuminance_lx);

nlohmann::json toJson(const GlareProfile& profile);
// Reads a profile document, validating every field it has; `file` names it in errors (kBadInput).
Result<GlareProfile> glareProfileFromJson(const nlohmann::json& document, const std::string& file);
Result<GlareProfile> readGlareProfile(const std::filesystem::path& path);

}  // namespace glarecam::pipeline
