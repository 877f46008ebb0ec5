// The module's glare profile (docs/glare-profile.md): Lmax and both limit-ellipse axes per 1° of
// α from the sweep's fits, the glare limit and whether the module glares, and the beam spread as
// glare-hazard tools model it: the circular cone of the same solid angle as the measured ellipse,
// and the surface slope error σ that gives that cone in beta = 2 (4.65 mrad + σ).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

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
};

// The equal-solid-angle circular cone of an elliptical cone with full axes in degrees (the
// ellipse lies in the azimuthal-equidistant angular plane, as glarecam measures it).
CircularBeamSpread circularBeamSpread(double vertical_deg, double horizontal_deg);

struct ProfileRow {
  double alpha_deg = 0;
  double lmax_cd_m2 = 0;  // from the better luminance fit
  std::optional<double> limit_cd_m2;
  bool glares = false;  // Lmax at or above the limit (as in result.json)
  std::optional<double> vertical_deg, horizontal_deg;  // from the logistic fits, where glaring
  std::optional<CircularBeamSpread> beam;
  bool extrapolated = false;  // outside the α range the given values were fitted on
};

inline constexpr int kProfileAlphaMaxDeg = 80;  // the method is defined up to 80°
inline constexpr int kProfileStepDeg = 1;

std::vector<ProfileRow> glareProfile(const SweepFits& fits, const GlareLimit& limit);

struct AlphaRange {
  double from_deg = 0, to_deg = 0;
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
  std::string module;
  std::string date;    // ISO 8601
  std::string source;  // the sweep table's path
};

// glarecam.glare-profile/1 (docs/glare-profile.md).
nlohmann::json glareProfileJson(const ProfileIdentity& identity, const SweepTable& table,
                                const SweepFits& fits, const GlareLimit& limit);

}  // namespace glarecam::pipeline
