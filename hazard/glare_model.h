// The glare regions a hazard calculation compares (../shared/docs/hazard.md, "Comparison
// models"): `ellipse`, the method's measured elliptical, α-dependent spread (the default);
// `circle`, the profile's equal-solid-angle circular cone (what SGHAT-style tools do with this
// module's own data); `cone:DEG`, one constant full angle at every glaring α (blendtool.ch, SGHAT
// with one slope error).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "hazard/profile_table.h"

namespace glarecam::hazard {

enum class ModelKind { kEllipse, kCircle, kCone };

// SGHAT's circular beam: full angle β = 2 (4.65 mrad + σ) for a slope error σ (Ho & Sims, SGHAT
// Technical Reference Manual; pipeline::kSunHalfAngleMrad).
double sghatBeamDeg(double slope_error_mrad);

struct GlareModel {
  ModelKind kind = ModelKind::kEllipse;
  double cone_deg = 0;  // kCone's full angle
  // A kCone given as `sigma:MRAD`: SGHAT's slope error, cone_deg = sghatBeamDeg(it).
  std::optional<double> slope_error_mrad{};

  std::string name() const;  // "ellipse", "circle", "cone:0.5", "sigma:2"
  friend bool operator==(const GlareModel&, const GlareModel&) = default;
};

// Full axes of a region in degrees: vertical (in the plane of incidence) and horizontal.
struct RegionAxesDeg {
  double vertical_deg = 0, horizontal_deg = 0;
};

// "ellipse,circle,cone:0.5,sigma:2": names separated by commas, each once (sigma:MRAD is the
// constant cone SGHAT-style tools draw for a slope error of MRAD, as commonly set: 2 mrad for a
// smooth glass module, hazard.md). kBadInput naming the
// option (`what`, e.g. "--models") and the unknown or repeated model.
Result<std::vector<GlareModel>> parseModels(std::string_view list, std::string_view what);

// The model's region at a glaring α (spread.status == kGlare); nullopt when the profile gives
// no spread for it there (an unknown spread, counted, never "no glare").
std::optional<RegionAxesDeg> regionAxes(const GlareModel& model, const SpreadAt& spread);

// The largest full axis this model's regions reach with `profile`, in degrees.
double maxFullAxisDeg(const GlareModel& model, const ProfileTable& profile);

}  // namespace glarecam::hazard
