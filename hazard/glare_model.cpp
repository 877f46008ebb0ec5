#include "hazard/glare_model.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/spelling.h"
#include "pipeline/glare_profile.h"

namespace glarecam::hazard {
namespace {

constexpr std::string_view kConePrefix = "cone:";
constexpr std::string_view kSigmaPrefix = "sigma:";
constexpr double kDegPerMrad = 180.0 / std::numbers::pi / 1000.0;
// A slope error above this makes a cone wider than a hemisphere: no module's.
constexpr double kMaxSlopeErrorMrad = 1000;

// A whole item parsed as a finite number, or nullopt.
std::optional<double> numberOf(const std::string& text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size() ||
      !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

}  // namespace

double sghatBeamDeg(double slope_error_mrad) {
  return 2 * (pipeline::kSunHalfAngleMrad + slope_error_mrad) * kDegPerMrad;
}

std::string GlareModel::name() const {
  switch (kind) {
    case ModelKind::kEllipse:
      return "ellipse";
    case ModelKind::kCircle:
      return "circle";
    case ModelKind::kCone: {
      char text[40];
      if (slope_error_mrad)
        std::snprintf(text, sizeof text, "sigma:%g", *slope_error_mrad);
      else
        std::snprintf(text, sizeof text, "cone:%g", cone_deg);
      return text;
    }
  }
  return "unknown";
}

Result<std::vector<GlareModel>> parseModels(std::string_view list, std::string_view what) {
  const std::string where(what);
  std::vector<GlareModel> models;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = trim(list.substr(start, comma - start));
    start = comma + 1;
    GlareModel model;
    if (item == "ellipse") {
      model.kind = ModelKind::kEllipse;
    } else if (item == "circle") {
      model.kind = ModelKind::kCircle;
    } else if (item.starts_with(kConePrefix)) {
      const std::optional<double> degrees = numberOf(item.substr(kConePrefix.size()));
      if (!degrees || *degrees <= 0 || *degrees > pipeline::kMaxFullAxisDeg) {
        return badInput(where + ": \"" + item +
                        "\" is not cone:DEG with a full angle DEG in (0, 180] degrees");
      }
      model.kind = ModelKind::kCone;
      model.cone_deg = *degrees;
    } else if (item.starts_with(kSigmaPrefix)) {
      const std::optional<double> sigma = numberOf(item.substr(kSigmaPrefix.size()));
      if (!sigma || *sigma < 0 || *sigma > kMaxSlopeErrorMrad) {
        return badInput(where + ": \"" + item +
                        "\" is not sigma:MRAD with a slope error MRAD in [0, 1000] mrad");
      }
      model.kind = ModelKind::kCone;
      model.cone_deg = sghatBeamDeg(*sigma);
      model.slope_error_mrad = *sigma;
    } else {
      std::string message = where + ": unknown model \"" + item + "\"";
      const std::vector<std::string> known{"ellipse", "circle", "cone:DEG", "sigma:MRAD"};
      const std::optional<std::string> suggestion = closestSpelling(item, known);
      message += suggestion ? " (did you mean " + *suggestion + "?)"
                            : " (models: ellipse, circle, cone:DEG, sigma:MRAD)";
      return badInput(message);
    }
    if (std::find(models.begin(), models.end(), model) != models.end())
      return badInput(where + ": model \"" + item + "\" is given twice");
    models.push_back(model);
  }
  return models;
}

std::optional<RegionAxesDeg> regionAxes(const GlareModel& model, const SpreadAt& spread) {
  switch (model.kind) {
    case ModelKind::kEllipse:
      if (spread.vertical_deg && spread.horizontal_deg)
        return RegionAxesDeg{*spread.vertical_deg, *spread.horizontal_deg};
      return std::nullopt;
    case ModelKind::kCircle:
      if (spread.circle_deg) return RegionAxesDeg{*spread.circle_deg, *spread.circle_deg};
      return std::nullopt;
    case ModelKind::kCone:
      return RegionAxesDeg{model.cone_deg, model.cone_deg};
  }
  return std::nullopt;
}

double maxFullAxisDeg(const GlareModel& model, const ProfileTable& profile) {
  return model.kind == ModelKind::kCone ? model.cone_deg : profile.maxFullAxisDeg();
}

}  // namespace glarecam::hazard
