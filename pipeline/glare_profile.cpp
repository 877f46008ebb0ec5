#include "pipeline/glare_profile.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/version.h"
#include "pipeline/glare_ellipse.h"

namespace glarecam::pipeline {

namespace {

using nlohmann::json;

constexpr double kMradPerRad = 1000.0;

json optionalNumber(const std::optional<double>& value) {
  return value ? json(*value) : json(nullptr);
}

json beamJson(const std::optional<CircularBeamSpread>& beam) {
  if (!beam) return nullptr;
  return {{"solid_angle_sr", beam->solid_angle_sr},
          {"beta_mrad", beam->beta_mrad},
          {"slope_error_mrad", beam->slope_error_mrad}};
}

json rangesJson(const std::vector<AlphaRange>& ranges) {
  json out = json::array();
  for (const AlphaRange& r : ranges) out.push_back({r.from_deg, r.to_deg});
  return out;
}

json rowJson(const ProfileRow& row) {
  return {{"alpha_deg", row.alpha_deg},
          {"lmax_cd_m2", row.lmax_cd_m2},
          {"limit_cd_m2", optionalNumber(row.limit_cd_m2)},
          {"glares", row.glares},
          {"vertical_deg", optionalNumber(row.vertical_deg)},
          {"horizontal_deg", optionalNumber(row.horizontal_deg)},
          {"circular_beam", beamJson(row.beam)},
          {"extrapolated", row.extrapolated}};
}

json measuredJson(const SweepRow& row) {
  return {{"alpha_deg", row.alpha_deg},
          {"limit_cd_m2", optionalNumber(row.limit_cd_m2)},
          {"lmax_cd_m2", row.lmax_cd_m2},
          {"lmax_bound", row.lmax_bound.empty() ? json(nullptr) : json(row.lmax_bound)},
          {"vertical_deg", optionalNumber(row.vertical_deg)},
          {"horizontal_deg", optionalNumber(row.horizontal_deg)}};
}

// Each distinct calibration of the rows (by id, in order): its date and K ± u(K).
json calibrationDetails(const SweepTable& table) {
  json details = json::array();
  std::vector<std::string> seen;
  for (const SweepRow& row : table.rows) {
    if (row.calibration_id.empty() || std::ranges::find(seen, row.calibration_id) != seen.end())
      continue;
    seen.push_back(row.calibration_id);
    details.push_back(
        {{"id", row.calibration_id},
         {"date", row.calibration_date.empty() ? json(nullptr) : json(row.calibration_date)},
         {"luminance_factor", optionalNumber(row.luminance_factor)},
         {"luminance_factor_u", optionalNumber(row.luminance_factor_u)}});
  }
  return details;
}

std::optional<double> axisAt(const AxisFit& axis, double alpha_deg) {
  if (!axis.logistic) return std::nullopt;
  const double axis_deg = axis.logistic->curve(alpha_deg);
  if (!isPhysicalAxisDeg(axis_deg)) return std::nullopt;  // an extrapolated fit run off
  return axis_deg;
}

// The method's verdict on the fits: the fitted Lmax at or above the limit (as in result.json).
bool glaresAt(const SweepFits& fits, const GlareLimit& limit, double alpha_deg) {
  const auto limit_cd_m2 = limit.at(alpha_deg);
  return limit_cd_m2 && fits.lmaxCdM2(alpha_deg) >= *limit_cd_m2;
}

bool outside(double alpha_deg, double lo_deg, double hi_deg) {
  return alpha_deg < lo_deg || alpha_deg > hi_deg;
}

}  // namespace

bool isPhysicalAxisDeg(double axis_deg) { return axis_deg > 0 && axis_deg <= kMaxFullAxisDeg; }

CircularBeamSpread circularBeamSpread(double vertical_deg, double horizontal_deg) {
  CircularBeamSpread beam;
  beam.solid_angle_sr = ellipseSolidAngleSr(vertical_deg / 2, horizontal_deg / 2);
  // A circular cone of half-angle θ spans 2π (1 - cos θ).
  const double half_angle_rad = std::acos(1.0 - beam.solid_angle_sr / (2 * std::numbers::pi));
  beam.beta_mrad = 2 * half_angle_rad * kMradPerRad;
  beam.slope_error_mrad = beam.beta_mrad / 2 - kSunHalfAngleMrad;
  return beam;
}

std::vector<ProfileRow> glareProfile(const SweepFits& fits, const GlareLimit& limit) {
  std::vector<ProfileRow> rows;
  for (int alpha = 0; alpha <= kProfileAlphaMaxDeg; alpha += kProfileStepDeg) {
    ProfileRow row;
    row.alpha_deg = alpha;
    row.lmax_cd_m2 = fits.lmaxCdM2(alpha);
    row.limit_cd_m2 = limit.at(alpha);
    row.glares = glaresAt(fits, limit, alpha);
    row.extrapolated = outside(alpha, fits.alpha_min_deg, fits.alpha_max_deg);
    if (row.glares) {
      row.vertical_deg = axisAt(fits.vertical, alpha);
      row.horizontal_deg = axisAt(fits.horizontal, alpha);
    }
    for (const AxisFit* axis : {&fits.vertical, &fits.horizontal}) {
      if (axis->logistic && row.glares)
        row.extrapolated |= outside(alpha, axis->alpha_min_deg, axis->alpha_max_deg);
    }
    if (row.vertical_deg && row.horizontal_deg && *row.vertical_deg > 0 && *row.horizontal_deg > 0)
      row.beam = circularBeamSpread(*row.vertical_deg, *row.horizontal_deg);
    rows.push_back(row);
  }
  return rows;
}

std::vector<AlphaRange> glareRanges(const SweepFits& fits, const GlareLimit& limit) {
  std::vector<AlphaRange> ranges;
  bool inside = false;
  const int steps = static_cast<int>(std::lround(kProfileAlphaMaxDeg / kGlareRangeResolutionDeg));
  for (int i = 0; i <= steps; ++i) {
    const double alpha = i / (1 / kGlareRangeResolutionDeg);  // 49.8, not 49.800000000000004
    const bool glares = glaresAt(fits, limit, alpha);
    if (glares && !inside) ranges.push_back({alpha, alpha});
    if (glares) ranges.back().to_deg = alpha;
    inside = glares;
  }
  return ranges;
}

json glareProfileJson(const ProfileIdentity& identity, const SweepTable& table,
                      const SweepFits& fits, const GlareLimit& limit) {
  json profile = json::array();
  for (const ProfileRow& row : glareProfile(fits, limit)) profile.push_back(rowJson(row));
  json measured = json::array();
  for (const SweepRow& row : table.rows) measured.push_back(measuredJson(row));
  return {
      {"schema", "glarecam.glare-profile/1"},
      {"module", identity.module},
      {"date", identity.date},
      {"source", identity.source},
      // Stacks of the simulated camera make a simulated profile, never a measurement's.
      {"simulated", isSimulated(table)},
      {"cameras", tableCameras(table)},
      {"calibrations", tableCalibrations(table)},
      {"calibration_details", calibrationDetails(table)},
      {"luminance_fit", fits.cosineIsBetter() ? "cos" : "biquadratic"},
      {"glare_ranges_deg", rangesJson(glareRanges(fits, limit))},
      {"limit", {{"mode", limit.mode()}, {"constant_cd_m2", optionalNumber(limit.constant_cd_m2)}}},
      {"sun_half_angle_mrad", kSunHalfAngleMrad},
      {"profile", profile},
      {"measured", measured},
      {"fits", fitsJson(fits)},
      {"generator", {{"name", "glarecam"}, {"version", kVersion}}}};
}

}  // namespace glarecam::pipeline
