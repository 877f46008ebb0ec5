// Empirical glare functions of a PV module (docs/method.md, "Across angles"): the luminance
// maximum and the two limit-ellipse axes as functions of the angle of incidence alpha.
// Modules are registered by name; "standard" is the SPF paper's standard module (Table III fits).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "pipeline/glare_functions.h"

namespace glarecam::capture {

using pipeline::BiquadraticLnCurve;
using pipeline::LogisticCurve;

struct ModuleGlareModel {
  std::string name;
  BiquadraticLnCurve lmax_cd_m2;
  LogisticCurve vertical_deg;    // full vertical axis of the limit ellipse
  LogisticCurve horizontal_deg;  // full horizontal axis of the limit ellipse
};

// The registered module models, by name; an unknown name is kBadInput listing the known ones.
Result<ModuleGlareModel> moduleModel(std::string_view name);
std::vector<std::string> moduleNames();

}  // namespace glarecam::capture
