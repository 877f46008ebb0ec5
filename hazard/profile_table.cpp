#include "hazard/profile_table.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/stack_manifest.h"
#include "hazard/json_fields.h"

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

Result<std::optional<double>> optionalNumber(const JsonFields& fields, const nlohmann::json& row,
                                             const std::string& where, const char* key, double low,
                                             double high, const char* unit) {
  const nlohmann::json* value = JsonFields::optionalMember(row, key);
  if (value == nullptr) return std::optional<double>{};
  double x = 0;
  GLARECAM_ASSIGN(x, fields.numberIn(*value, JsonFields::child(where, key), low, high, unit));
  return std::optional<double>{x};
}

}  // namespace

Result<ProfileTable> ProfileTable::read(const std::filesystem::path& path) {
  nlohmann::json document;
  GLARECAM_ASSIGN(document, readJsonFile(path.string()));
  ProfileTable table;
  GLARECAM_ASSIGN(table, fromJson(document, path.string()));
  table.path_ = path;
  table.identity_["path"] = path.string();
  return table;
}

Result<ProfileTable> ProfileTable::fromJson(const nlohmann::json& document,
                                            const std::string& file) {
  const JsonFields fields(file);
  if (!document.is_object()) return fields.fail("the document", "is not a JSON object");
  const nlohmann::json* value = nullptr;
  GLARECAM_ASSIGN(value, fields.member(document, "", "schema"));
  if (!value->is_string() || value->get<std::string>() != kProfileSchema) {
    return fields.fail("schema", value->dump() + " is not \"" + std::string(kProfileSchema) +
                                     "\" (not a glare profile)");
  }
  ProfileTable table;
  GLARECAM_ASSIGN(value, fields.member(document, "", "module"));
  GLARECAM_ASSIGN(table.module_, fields.text(*value, "module"));
  table.identity_ = {{"module", table.module_}};
  for (const char* key : {"date", "simulated", "calibrations", "source"}) {
    if (const nlohmann::json* item = JsonFields::optionalMember(document, key))
      table.identity_[key] = *item;
  }

  GLARECAM_ASSIGN(value, fields.member(document, "", "glare_ranges_deg"));
  GLARECAM_CHECK(fields.array(*value, "glare_ranges_deg"));
  for (std::size_t i = 0; i < value->size(); ++i) {
    const std::string field = JsonFields::element("glare_ranges_deg", i);
    const nlohmann::json& range = (*value)[i];
    GLARECAM_CHECK(fields.array(range, field));
    if (range.size() != 2) return fields.fail(field, "is not [from, to] in degrees");
    pipeline::AlphaRange alpha;
    GLARECAM_ASSIGN(alpha.from_deg,
                    fields.numberIn(range[0], JsonFields::element(field, 0), 0, 90, "°"));
    GLARECAM_ASSIGN(alpha.to_deg,
                    fields.numberIn(range[1], JsonFields::element(field, 1), 0, 90, "°"));
    if (alpha.from_deg > alpha.to_deg) return fields.fail(field, "runs backwards (from > to)");
    table.ranges_.push_back(alpha);
  }

  GLARECAM_ASSIGN(value, fields.member(document, "", "profile"));
  GLARECAM_CHECK(fields.array(*value, "profile"));
  std::array<bool, kProfileAlphaMaxDeg + 1> seen{};
  for (std::size_t i = 0; i < value->size(); ++i) {
    const std::string where = JsonFields::element("profile", i);
    const nlohmann::json& json = (*value)[i];
    GLARECAM_CHECK(fields.object(json, where));
    const nlohmann::json* alpha_json = nullptr;
    GLARECAM_ASSIGN(alpha_json, fields.member(json, where, "alpha_deg"));
    double alpha = 0;
    GLARECAM_ASSIGN(alpha, fields.numberIn(*alpha_json, JsonFields::child(where, "alpha_deg"), 0,
                                           kProfileAlphaMaxDeg, "°"));
    if (alpha != std::floor(alpha))
      return fields.fail(JsonFields::child(where, "alpha_deg"), "is not a whole degree");
    const auto index = static_cast<std::size_t>(alpha);
    if (seen[index])
      return fields.fail(JsonFields::child(where, "alpha_deg"), "repeats an earlier row's α");
    seen[index] = true;
    Row& row = table.rows_[index];
    GLARECAM_ASSIGN(row.lmax_cd_m2,
                    optionalNumber(fields, json, where, "lmax_cd_m2", -1e300, 1e300, " cd/m²"));
    GLARECAM_ASSIGN(row.limit_cd_m2,
                    optionalNumber(fields, json, where, "limit_cd_m2", 0, 1e300, " cd/m²"));
    GLARECAM_ASSIGN(row.vertical_deg, optionalNumber(fields, json, where, "vertical_deg", 0,
                                                     pipeline::kMaxFullAxisDeg, "°"));
    GLARECAM_ASSIGN(row.horizontal_deg, optionalNumber(fields, json, where, "horizontal_deg", 0,
                                                       pipeline::kMaxFullAxisDeg, "°"));
    if (const nlohmann::json* beam = JsonFields::optionalMember(json, "circular_beam")) {
      const std::string beam_where = JsonFields::child(where, "circular_beam");
      GLARECAM_CHECK(fields.object(*beam, beam_where));
      std::optional<double> beta_mrad;
      GLARECAM_ASSIGN(beta_mrad,
                      optionalNumber(fields, *beam, beam_where, "beta_mrad", 0,
                                     radians(pipeline::kMaxFullAxisDeg) / kRadPerMrad, " mrad"));
      if (beta_mrad) row.circle_deg = degrees(*beta_mrad * kRadPerMrad);
    }
    // A zero (or vanishing) axis is no region at all: treat it like a missing one.
    for (std::optional<double>* axis : {&row.vertical_deg, &row.horizontal_deg, &row.circle_deg}) {
      if (*axis && !(**axis >= kMinAxisDeg)) axis->reset();
      if (*axis) table.max_full_axis_deg_ = std::max(table.max_full_axis_deg_, **axis);
    }
  }
  for (int alpha = 0; alpha <= kProfileAlphaMaxDeg; ++alpha) {
    if (!seen[static_cast<std::size_t>(alpha)])
      return fields.fail("profile", "has no row for α = " + std::to_string(alpha) + "°");
  }
  for (int alpha = kProfileAlphaMaxDeg; alpha >= 0; --alpha) {
    const Row& row = table.rows_[static_cast<std::size_t>(alpha)];
    if (row.vertical_deg && row.horizontal_deg) {
      table.last_defined_ = SpreadAt{.status = SpreadStatus::kGlare,
                                     .vertical_deg = row.vertical_deg,
                                     .horizontal_deg = row.horizontal_deg,
                                     .circle_deg = row.circle_deg};
      break;
    }
  }
  return table;
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

}  // namespace glarecam::hazard
