#include "hazard/ocular_hazard.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

namespace glarecam::hazard {
namespace ocular_hazard {

constexpr double kMradPerRad = 1000;
constexpr double kCm2PerM2 = 1e4;
constexpr double kHemisphereSr = 2 * std::numbers::pi;

bool positiveFinite(double value) { return std::isfinite(value) && value > 0; }

double radiansOf(double mrad) { return mrad / kMradPerRad; }

}  // namespace ocular_hazard

Status EyeParameters::validate() const {
  using ocular_hazard::positiveFinite;
  if (!positiveFinite(pupil_diameter_m))
    return badInput(fmt::format("pupil diameter {} m: must be positive", pupil_diameter_m));
  if (!positiveFinite(focal_length_m))
    return badInput(fmt::format("eye focal length {} m: must be positive", focal_length_m));
  if (!(positiveFinite(ocular_transmission) && ocular_transmission <= 1))
    return badInput(
        fmt::format("ocular transmission {}: must be above 0 and at most 1", ocular_transmission));
  if (!(positiveFinite(luminous_efficacy_lm_w) &&
        luminous_efficacy_lm_w <= kMaxLuminousEfficacyLmW))
    return badInput(fmt::format("luminous efficacy {} lm/W: must be above 0 and at most {} lm/W",
                                luminous_efficacy_lm_w, kMaxLuminousEfficacyLmW));
  return {};
}

std::string_view ocularClassName(OcularClass ocular_class) {
  switch (ocular_class) {
    case OcularClass::kAfterImage:
      return "yellow";
    case OcularClass::kRetinalBurn:
      return "red";
    case OcularClass::kLowAfterImage:
      break;
  }
  return "green";
}

std::string_view ocularClassWords(OcularClass ocular_class) {
  switch (ocular_class) {
    case OcularClass::kAfterImage:
      return "potential for after-image";
    case OcularClass::kRetinalBurn:
      return "potential for permanent eye damage (retinal burn)";
    case OcularClass::kLowAfterImage:
      break;
  }
  return "low potential for after-image";
}

Result<double> subtendedAngleMrad(double solid_angle_sr) {
  using ocular_hazard::kHemisphereSr, ocular_hazard::kMradPerRad, ocular_hazard::positiveFinite;
  if (!(positiveFinite(solid_angle_sr) && solid_angle_sr <= kHemisphereSr))
    return badInput(fmt::format("solid angle {} sr: must be above 0 and at most a hemisphere's 2π",
                                solid_angle_sr));
  // Ω = 2π (1 − cos(ω/2)) = 4π sin²(ω/4): the arcsine keeps the digits of a small cone that
  // 1 − Ω/2π would lose to cancellation.
  return 4 * std::asin(std::sqrt(solid_angle_sr / (4 * std::numbers::pi))) * kMradPerRad;
}

double afterImageThresholdWCm2(double subtended_angle_mrad) {
  using ocular_hazard::positiveFinite, ocular_hazard::radiansOf;
  if (!positiveFinite(subtended_angle_mrad)) return std::nan("");
  return kAfterImageCoefficientWCm2 *
         std::pow(radiansOf(subtended_angle_mrad), kAfterImageExponent);
}

double retinalBurnThresholdWCm2(double subtended_angle_mrad) {
  using ocular_hazard::positiveFinite, ocular_hazard::radiansOf;
  if (!positiveFinite(subtended_angle_mrad)) return std::nan("");
  return kRetinalBurnCoefficientWCm2Rad / radiansOf(subtended_angle_mrad);
}

Result<OcularClass> classify(double retinal_irradiance_w_cm2, double subtended_angle_mrad) {
  using ocular_hazard::positiveFinite;
  if (!positiveFinite(retinal_irradiance_w_cm2))
    return badInput(fmt::format("retinal irradiance {} W/cm²: must be positive and finite",
                                retinal_irradiance_w_cm2));
  if (!positiveFinite(subtended_angle_mrad))
    return badInput(
        fmt::format("subtended angle {} mrad: must be positive and finite", subtended_angle_mrad));
  if (retinal_irradiance_w_cm2 >= retinalBurnThresholdWCm2(subtended_angle_mrad))
    return OcularClass::kRetinalBurn;
  if (retinal_irradiance_w_cm2 >= afterImageThresholdWCm2(subtended_angle_mrad))
    return OcularClass::kAfterImage;
  return OcularClass::kLowAfterImage;
}

Result<OcularExposure> ocularExposure(double luminance_cd_m2, double solid_angle_sr,
                                      const EyeParameters& eye) {
  using ocular_hazard::kCm2PerM2, ocular_hazard::positiveFinite, ocular_hazard::radiansOf;
  GLARECAM_CHECK(eye.validate());
  if (!positiveFinite(luminance_cd_m2))
    return badInput(
        fmt::format("luminance {} cd/m²: must be positive and finite", luminance_cd_m2));
  OcularExposure exposure;
  GLARECAM_ASSIGN(exposure.subtended_angle_mrad, subtendedAngleMrad(solid_angle_sr));
  exposure.radiance_w_m2_sr = luminance_cd_m2 / eye.luminous_efficacy_lm_w;
  exposure.corneal_irradiance_w_m2 = exposure.radiance_w_m2_sr * solid_angle_sr;
  const double omega_rad = radiansOf(exposure.subtended_angle_mrad);
  const double retinal_w_m2 = exposure.corneal_irradiance_w_m2 * eye.pupil_diameter_m *
                              eye.pupil_diameter_m * eye.ocular_transmission /
                              (eye.focal_length_m * eye.focal_length_m * omega_rad * omega_rad);
  exposure.retinal_irradiance_w_cm2 = retinal_w_m2 / kCm2PerM2;
  // An absurd luminance (beyond any double's reach, or below its least) overflows or
  // underflows: say so rather than classify an infinity or a zero.
  if (!positiveFinite(exposure.retinal_irradiance_w_cm2))
    return badInput(
        fmt::format("luminance {} cd/m² over {} sr: the retinal irradiance is not a "
                    "positive finite number",
                    luminance_cd_m2, solid_angle_sr));
  GLARECAM_ASSIGN(exposure.ocular_class,
                  classify(exposure.retinal_irradiance_w_cm2, exposure.subtended_angle_mrad));
  return exposure;
}

}  // namespace glarecam::hazard
