#include "capture/sim/module_model.h"

namespace glarecam::capture {

namespace {

// The SPF paper's fits of its Table III (docs/method.md): the biquadratic luminance fit
// (R² 0.983, the better of the two) and the logistic fits of both axes.
ModuleGlareModel standardModule() {
  return {.name = "standard",
          .lmax_cd_m2 = {.a = 1.235e-7, .b = -5.504e-5, .c = 13.2},
          .vertical_deg = {.a = 3.411, .b = 52.46, .c = 4.854, .d = 0.167},
          .horizontal_deg = {.a = -1395.0, .b = 190.5, .c = 5.621, .d = 0.05465}};
}

const std::vector<ModuleGlareModel>& registry() {
  static const std::vector<ModuleGlareModel> models{standardModule()};
  return models;
}

}  // namespace

std::vector<std::string> moduleNames() {
  std::vector<std::string> names;
  for (const auto& model : registry()) names.push_back(model.name);
  return names;
}

Result<ModuleGlareModel> moduleModel(std::string_view name) {
  for (const auto& model : registry()) {
    if (model.name == name) return model;
  }
  std::string known;
  for (const auto& n : moduleNames()) known += (known.empty() ? "" : ", ") + n;
  return badInput("unknown module \"" + std::string(name) + "\" (known: " + known + ")");
}

}  // namespace glarecam::capture
