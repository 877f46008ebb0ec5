#include "hazard/profile_table.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"

namespace glarecam::hazard {
namespace {

using pipeline::kProfileAlphaMaxDeg;

constexpr double kRadPerMrad = 1e-3;

std::optional<double> lerp(std::optional<double> a, std::optional<double> b, double t) {
  if (a && b) return *a + (*b - *a) * t;
  return a ? a : b;
}

// Linear in ln L; a luminance that is not positive counts as absent.
std::optional<double> lerpLog(std::optional<double> a, std::optional<double> b, double t) {
  if (a && !(*a > 0)) a.reset();
  if (b && !(*b > 0)) b.reset();
  if (a && b) return std::exp(std::log(*a) + (std::log(*b) - std::log(*a)) * t);
  return a ? a : b;
}

}  // namespace

ProfileTable::ProfileTable(const pipeline::GlareProfile& profile)
    : module_(profile.module), simulated_(profile.simulated), ranges_(profile.glare_ranges) {
  identity_ = {{"module", profile.module},
               {"simulated", profile.simulated},
               {"calibrations", profile.calibrations}};
  if (profile.date) identity_["date"] = *profile.date;
  if (profile.source) identity_["source"] = *profile.source;
  if (!profile.routes.empty()) identity_["routes"] = profile.routes;
  for (const pipeline::ProfileRow& source : profile.rows) {
    Row& row = rows_[static_cast<std::size_t>(source.alpha_deg)];
    row.lmax_cd_m2 = source.lmax_cd_m2;
    row.limit_cd_m2 = source.limit_cd_m2;
    row.vertical_deg = source.vertical_deg;
    row.horizontal_deg = source.horizontal_deg;
    if (source.beam) row.circle_deg = degrees(source.beam->beta_mrad * kRadPerMrad);
    // A zero (or vanishing) axis is no region at all: treat it like a missing one.
    for (std::optional<double>* axis : {&row.vertical_deg, &row.horizontal_deg, &row.circle_deg}) {
      if (*axis && !(**axis >= kMinAxisDeg)) axis->reset();
      if (*axis) max_full_axis_deg_ = std::max(max_full_axis_deg_, **axis);
    }
  }
  if (profile.referred == true && profile.reference_illuminance_lx && !profile.ladder.empty()) {
    ladder_reference_lx_ = profile.reference_illuminance_lx;
    profile_ = std::make_shared<const pipeline::GlareProfile>(profile);
    for (const pipeline::ProfileLadderRow& row : profile.ladder) {
      for (const pipeline::ProfileContour& contour : row.contours)
        max_ladder_axis_deg_ =
            std::max({max_ladder_axis_deg_, contour.vertical_deg, contour.horizontal_deg});
    }
  }
  for (int alpha = kProfileAlphaMaxDeg; alpha >= 0; --alpha) {
    const Row& row = rows_[static_cast<std::size_t>(alpha)];
    if (row.vertical_deg && row.horizontal_deg) {
      last_defined_ = SpreadAt{.status = SpreadStatus::kGlare,
                               .vertical_deg = row.vertical_deg,
                               .horizontal_deg = row.horizontal_deg,
                               .circle_deg = row.circle_deg};
      break;
    }
  }
}

Result<ProfileTable> ProfileTable::read(const std::filesystem::path& path) {
  pipeline::GlareProfile profile;
  GLARECAM_ASSIGN(profile, pipeline::readGlareProfile(path));
  ProfileTable table(profile);
  table.path_ = path;
  table.identity_["path"] = path.string();
  return table;
}

Result<ProfileTable> ProfileTable::fromJson(const nlohmann::json& document,
                                            const std::string& file) {
  pipeline::GlareProfile profile;
  GLARECAM_ASSIGN(profile, pipeline::glareProfileFromJson(document, file));
  return ProfileTable(profile);
}

bool ProfileTable::glaresWithin(double from_deg, double to_deg) const {
  return std::any_of(ranges_.begin(), ranges_.end(), [&](const pipeline::AlphaRange& range) {
    return range.from_deg <= to_deg && from_deg <= range.to_deg;
  });
}

SpreadAt ProfileTable::spreadAt(double alpha_deg) const {
  SpreadAt spread;
  spread.status = SpreadStatus::kGlare;
  const double alpha = std::clamp(alpha_deg, 0.0, static_cast<double>(kProfileAlphaMaxDeg));
  const int below = std::min(static_cast<int>(alpha), kProfileAlphaMaxDeg);
  const int above = std::min(below + 1, kProfileAlphaMaxDeg);
  const double t = alpha - below;
  const Row& a = rows_[static_cast<std::size_t>(below)];
  const Row& b = rows_[static_cast<std::size_t>(above)];
  spread.vertical_deg = lerp(a.vertical_deg, b.vertical_deg, t);
  spread.horizontal_deg = lerp(a.horizontal_deg, b.horizontal_deg, t);
  spread.circle_deg = lerp(a.circle_deg, b.circle_deg, t);
  return spread;
}

SpreadAt ProfileTable::at(double alpha_deg) const {
  SpreadAt none;
  if (alpha_deg > kProfileAlphaMaxDeg) {
    none.status = SpreadStatus::kBeyondMethod;
    return none;
  }
  if (!(alpha_deg >= 0) || !glaresWithin(alpha_deg, alpha_deg)) return none;
  return spreadAt(alpha_deg);
}

LuminancesAt ProfileTable::luminancesAt(double alpha_deg) const {
  const double alpha = std::clamp(alpha_deg, 0.0, static_cast<double>(kProfileAlphaMaxDeg));
  const int below = std::min(static_cast<int>(alpha), kProfileAlphaMaxDeg);
  const int above = std::min(below + 1, kProfileAlphaMaxDeg);
  const double t = alpha - below;
  const Row& a = rows_[static_cast<std::size_t>(below)];
  const Row& b = rows_[static_cast<std::size_t>(above)];
  return {.lmax_cd_m2 = lerpLog(a.lmax_cd_m2, b.lmax_cd_m2, t),
          .limit_cd_m2 = lerpLog(a.limit_cd_m2, b.limit_cd_m2, t)};
}

LadderRegion ProfileTable::regionAtLevel(double alpha_deg, double level_cd_m2) const {
  LadderRegion region;
  const std::optional<double> lmax_cd_m2 = luminancesAt(alpha_deg).lmax_cd_m2;
  if (!profile_ || !lmax_cd_m2) return region;
  if (level_cd_m2 > *lmax_cd_m2) {
    region.status = LadderRegion::Status::kNoGlare;
    return region;
  }
  const std::vector<pipeline::ProfileLadderRow>& ladder = profile_->ladder;
  const double alpha = std::clamp(alpha_deg, ladder.front().alpha_deg, ladder.back().alpha_deg);
  region.beyond_ladder = alpha != alpha_deg;
  if (const std::optional<pipeline::ProfileContour> contour =
          pipeline::contourAt(*profile_, alpha, level_cd_m2)) {
    region.status = LadderRegion::Status::kRegion;
    region.vertical_deg = contour->vertical_deg;
    region.horizontal_deg = contour->horizontal_deg;
    region.solid_angle_sr = contour->solid_angle_sr;
    return region;
  }
  // Above the highest rung of the nearest degree: a log-quadratic peak's contours are similar
  // ellipses with axes² ∝ ln(Lmax / level), so the rung's shrink by √(ln(Lmax/T) / ln(Lmax/T_top)).
  const auto nearest = std::ranges::min_element(
      ladder, {},
      [&](const pipeline::ProfileLadderRow& row) { return std::abs(row.alpha_deg - alpha); });
  if (nearest->contours.empty()) return region;
  const pipeline::ProfileContour& top = nearest->contours.back();
  if (level_cd_m2 < top.level_cd_m2 || !(*lmax_cd_m2 > top.level_cd_m2)) return region;
  const double scale =
      std::sqrt(std::log(*lmax_cd_m2 / level_cd_m2) / std::log(*lmax_cd_m2 / top.level_cd_m2));
  region.status = LadderRegion::Status::kRegion;
  region.above_rungs = true;
  region.vertical_deg = top.vertical_deg * scale;
  region.horizontal_deg = top.horizontal_deg * scale;
  region.solid_angle_sr = top.solid_angle_sr * scale * scale;
  return region;
}

}  // namespace glarecam::hazard
