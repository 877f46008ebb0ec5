// The ocular hazard of glare (docs/ocular-hazard.md): what a glaring spot of luminance L, seen
// over a solid angle Ω, does to the eye, in the terms of Ho, Ghanbari & Diver 2011 and of Sandia's
// Solar Glare Hazard Analysis Tool (SGHAT) built on them: the retinal irradiance E_r and the
// subtended source angle ω, and where the point (ω, E_r) lies on their hazard plot: green (low
// potential for after-image), yellow (potential for after-image) or red (potential for permanent
// eye damage, retinal burn). Pure functions of their arguments; no state.
//
// From the luminance seen to the retina, for a uniform circular spot centred on the line of sight
// (one glaring step at one observer: the spot's mean luminance and its solid angle):
//   radiance            L_e = L / K                 K: the luminous efficacy of sunlight (lm/W);
//                                                   a reflection of the sun keeps its spectrum
//   subtended angle     ω = 2 arccos(1 − Ω / 2π)    the full apex angle of the circular cone of
//                                                   solid angle Ω (pipeline's beta_mrad too),
//                                                   computed as 4 asin √(Ω / 4π)
//   corneal irradiance  E_c = L_e · Ω               a small source: the cosine over the cone,
//                                                   cos²(ω/4) > 0.9993 below 0.1 rad, is left out
//   retinal irradiance  E_r = E_c · d_p² · τ / (f² · ω²)
//                       the power through the pupil, π d_p²/4 · E_c · τ, spread evenly over the
//                       retinal image of diameter f · ω (Ho et al. 2011; SGHAT Technical
//                       Reference Manual, "Determination of Ocular Impact"). For a given L it does
//                       not depend on Ω (radiance is conserved): E_r = π d_p² τ L_e / (4 f²).
// The class boundaries (Ho et al. 2011, the SGHAT ocular hazard plot), ω in rad, E_r in W/cm²:
//   retinal burn        E_r,burn(ω)  = 0.118 / ω
//   after-image         E_r,flash(ω) = 3.59·10⁻⁵ · ω^−2.21
// red when E_r ≥ E_r,burn, else yellow when E_r ≥ E_r,flash, else green. Both are straight lines
// on the log-log plot; they cross at ω ≈ 1.24 mrad, below which there is no yellow zone (a spot
// that small is red or green). The thresholds are for a glance: the blink and aversion response
// ends an exposure in about 0.15 s (Ho et al. 2011); they are not limits for staring.
//
// Verification: none of the constants below could be checked against the cited documents when
// this file was written (see docs/ocular-hazard.md, "Verification"). The eye's parameters are the
// defaults SGHAT's manuals and reports state; the boundaries' constants (0.118; 3.59·10⁻⁵ and
// −2.21) are Ho et al. 2011's as recorded by this file's author, not yet compared with the
// paper's text or its ocular-hazard figure. Each is one named constant below.
//
// References:
//   C. K. Ho, C. M. Ghanbari, R. B. Diver, "Methodology to assess potential glint and glare
//     hazards from concentrating solar power plants: analytical models and experimental
//     validation", J. Sol. Energy Eng. 133(3), 031021 (2011).
//   C. K. Ho, C. A. Sims, "Solar Glare Hazard Analysis Tool (SGHAT) Technical Reference Manual",
//     Sandia National Laboratories; C. K. Ho, C. A. Sims, J. E. Yellowhair, "SGHAT User's Manual
//     v. 2", SAND2013-7063P (2015): the ocular parameters' defaults.
//   P. J. Littlefair, "The luminous efficacy of daylight: a review", Lighting Res. Technol. 17(4),
//     162–182 (1985); "Measurements of the luminous efficacy of daylight", ibid. 20(4), 177–188
//     (1988): the direct beam's efficacy (docs/illuminance.md, as the rig's default).
//
// Errors: kBadInput for a luminance or solid angle that is not positive and finite, a solid angle
// above a hemisphere's 2π sr, or eye parameters that validate() refuses.
#pragma once

#include <string_view>

#include "core/error.h"

namespace glarecam::hazard {

// SGHAT's default ocular parameters (User's Manual v. 2, Technical Reference Manual): a
// daylight-adapted pupil, the eye's focal length, and the fraction of the light at the cornea
// that reaches the retina.
inline constexpr double kSghatPupilDiameterM = 0.002;
inline constexpr double kSghatEyeFocalLengthM = 0.017;
inline constexpr double kSghatOcularTransmission = 0.5;

// The luminous efficacy of direct sunlight, lm per W of the whole solar spectrum: a round middle
// of Littlefair's 1985 and 1988 measurements (70–105 lm/W, rising with the sun's elevation) for
// elevations above about 20°; the same value as the rig's W/m²-to-lux default
// (rig/illuminance/illuminance_config.h). Below 20° the true efficacy is lower and L / K
// understates the radiance.
inline constexpr double kSunlightLuminousEfficacyLmW = 93.0;

// The most a watt of light can give: 683 lm/W at 555 nm (the definition of the candela).
inline constexpr double kMaxLuminousEfficacyLmW = 683.0;

// Ho et al. 2011's boundaries: E_r,burn = kRetinalBurnCoefficient / ω and
// E_r,flash = kAfterImageCoefficient · ω^kAfterImageExponent, ω in rad, E_r in W/cm².
inline constexpr double kRetinalBurnCoefficientWCm2Rad = 0.118;
inline constexpr double kAfterImageCoefficientWCm2 = 3.59e-5;
inline constexpr double kAfterImageExponent = -2.21;

struct EyeParameters {
  double pupil_diameter_m = kSghatPupilDiameterM;
  double focal_length_m = kSghatEyeFocalLengthM;
  double ocular_transmission = kSghatOcularTransmission;  // 0 < τ ≤ 1
  double luminous_efficacy_lm_w = kSunlightLuminousEfficacyLmW;

  // The first problem in words: a length that is not positive and finite, a transmission outside
  // (0, 1], an efficacy outside (0, 683] lm/W.
  Status validate() const;
};

// Where a point lies on the hazard plot, in Ho et al. 2011's words.
enum class OcularClass {
  kLowAfterImage,  // green: low potential for after-image
  kAfterImage,     // yellow: potential for after-image
  kRetinalBurn,    // red: potential for permanent eye damage (retinal burn)
};

// "green", "yellow", "red": the plot's colour, as reports and files name the class.
std::string_view ocularClassName(OcularClass ocular_class);
// "low potential for after-image", "potential for after-image", "potential for permanent eye
// damage (retinal burn)": for a report's reader.
std::string_view ocularClassWords(OcularClass ocular_class);

struct OcularExposure {
  double retinal_irradiance_w_cm2 = 0;
  double subtended_angle_mrad = 0;  // ω, the full apex angle
  OcularClass ocular_class = OcularClass::kLowAfterImage;
  double corneal_irradiance_w_m2 = 0;  // E_c
  double radiance_w_m2_sr = 0;         // L_e = L / K
};

// The exposure of an eye to a spot of mean luminance `luminance_cd_m2` over `solid_angle_sr`.
Result<OcularExposure> ocularExposure(double luminance_cd_m2, double solid_angle_sr,
                                      const EyeParameters& eye = {});

// ω of the circular cone of solid angle Ω, in mrad; kBadInput unless 0 < Ω ≤ 2π.
Result<double> subtendedAngleMrad(double solid_angle_sr);

// The boundaries at ω (mrad), in W/cm²; NaN for an ω that is not positive and finite.
double afterImageThresholdWCm2(double subtended_angle_mrad);
double retinalBurnThresholdWCm2(double subtended_angle_mrad);

// The class of (ω, E_r); a threshold itself belongs to the class above it. kBadInput unless both
// are positive and finite.
Result<OcularClass> classify(double retinal_irradiance_w_cm2, double subtended_angle_mrad);

}  // namespace glarecam::hazard
