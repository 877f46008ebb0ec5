// glarecam model: the paper's five-facet geometric model of beam spread, γ_ew and γ_ns per α
// (docs/datasheet.md, "The five-facet model").
#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "apps/glarecam/commands.h"
#include "core/json.h"
#include "pipeline/facet_model.h"

namespace glarecam::apps {
namespace {

constexpr double kMaxAlphaDeg = 90.0;
constexpr int kDefaultAlphaStepDeg = 5, kDefaultAlphaMaxDeg = 80;

struct ModelArgs {
  double beta_deg = 0;
  std::vector<double> alpha_deg;
  bool json = false;
};

Status runModel(const ModelArgs& args) {
  if (!(args.beta_deg > 0 && args.beta_deg <= pipeline::kMaxFacetTiltDeg))
    return badInput(fmt::format("--beta: expected a facet tilt in (0, {}] degrees, got {}",
                                pipeline::kMaxFacetTiltDeg, args.beta_deg));
  std::vector<double> alphas = args.alpha_deg;
  if (alphas.empty()) {
    for (int a = 0; a <= kDefaultAlphaMaxDeg; a += kDefaultAlphaStepDeg) alphas.push_back(a);
  }
  nlohmann::json rows = nlohmann::json::array();
  std::string table = "alpha_deg  gamma_ew_deg  gamma_ns_deg  valid\n";
  for (double alpha : alphas) {
    if (!(alpha >= 0 && alpha <= kMaxAlphaDeg))
      return badInput(fmt::format("--alpha: {} is outside [0, 90] degrees", alpha));
    const pipeline::FacetSpread s = pipeline::facetSpread(alpha, args.beta_deg);
    rows.push_back({{"alpha_deg", s.alpha_deg},
                    {"gamma_ew_deg", s.gamma_ew_deg},
                    {"gamma_ns_deg", s.gamma_ns_deg},
                    {"valid", s.valid}});
    table += fmt::format("{:>9.6g}  {:>12.4f}  {:>12.4f}  {}\n", s.alpha_deg, s.gamma_ew_deg,
                         s.gamma_ns_deg, s.valid ? "yes" : "no (elevation < beta)");
  }
  if (args.json) {
    const nlohmann::json out{{"model", "five-facet"}, {"beta_deg", args.beta_deg}, {"rows", rows}};
    std::printf("%s", jsonText(out).c_str());
  } else {
    std::printf("%s", table.c_str());
  }
  return {};
}

}  // namespace

void addModelCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<ModelArgs>();
  CLI::App* sub = app.add_subcommand(
      "model",
      "The paper's five-facet geometric model: γ_ew and γ_ns per α for facet tilt β "
      "(docs/datasheet.md)");
  sub->add_option("--beta", args->beta_deg, "facet tilt β in degrees, (0, 45]")->required();
  sub->add_option("--alpha", args->alpha_deg,
                  "angles of incidence in degrees from the normal (default 0, 5, ... 80)")
      ->expected(1, -1);
  sub->add_flag("--json", args->json,
                "print JSON: {model, beta_deg, rows: [{alpha_deg, "
                "gamma_ew_deg, gamma_ns_deg, valid}]}");
  sub->callback([args, &action] { action = [args] { return runModel(*args); }; });
}

}  // namespace glarecam::apps
