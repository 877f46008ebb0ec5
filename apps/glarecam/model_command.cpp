// glarecam model: the paper's five-facet geometric model of beam spread, γ_ew and γ_ns per α
// (docs/datasheet.md, "The five-facet model").
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/glarecam/commands.h"
#include "brdf/surface_model_fit.h"
#include "core/atomic_file.h"
#include "core/json.h"
#include "pipeline/facet_model.h"
#include "surface/surface_catalogue.h"

namespace glarecam::apps {
namespace {

constexpr double kMaxAlphaDeg = 90.0;
constexpr int kDefaultAlphaStepDeg = 5, kDefaultAlphaMaxDeg = 80;

struct ModelArgs {
  std::optional<double> beta_deg;
  std::vector<double> alpha_deg;
  bool json = false;
};

Status runModel(const ModelArgs& args) {
  if (!args.beta_deg)
    return badInput("model: --beta is required (the five-facet model), or `model fit TABLE`");
  if (!(*args.beta_deg > 0 && *args.beta_deg <= pipeline::kMaxFacetTiltDeg))
    return badInput(fmt::format("--beta: expected a facet tilt in (0, {}] degrees, got {}",
                                pipeline::kMaxFacetTiltDeg, *args.beta_deg));
  std::vector<double> alphas = args.alpha_deg;
  if (alphas.empty()) {
    for (int a = 0; a <= kDefaultAlphaMaxDeg; a += kDefaultAlphaStepDeg) alphas.push_back(a);
  }
  nlohmann::json rows = nlohmann::json::array();
  std::string table = "alpha_deg  gamma_ew_deg  gamma_ns_deg  valid\n";
  for (double alpha : alphas) {
    if (!(alpha >= 0 && alpha <= kMaxAlphaDeg))
      return badInput(fmt::format("--alpha: {} is outside [0, 90] degrees", alpha));
    const pipeline::FacetSpread s = pipeline::facetSpread(alpha, *args.beta_deg);
    rows.push_back({{"alpha_deg", s.alpha_deg},
                    {"gamma_ew_deg", s.gamma_ew_deg},
                    {"gamma_ns_deg", s.gamma_ns_deg},
                    {"valid", s.valid}});
    table += fmt::format("{:>9.6g}  {:>12.4f}  {:>12.4f}  {}\n", s.alpha_deg, s.gamma_ew_deg,
                         s.gamma_ns_deg, s.valid ? "yes" : "no (elevation < beta)");
  }
  if (args.json) {
    const nlohmann::json out{{"model", "five-facet"}, {"beta_deg", *args.beta_deg}, {"rows", rows}};
    std::printf("%s", jsonText(out).c_str());
  } else {
    std::printf("%s", table.c_str());
  }
  return {};
}

struct ModelFitArgs {
  std::string table;
  std::optional<std::string> distribution, start;
  std::optional<double> refractive_index;
  double source_radius_deg = surface::kSunHalfAngleDeg;
  std::optional<std::string> out;
  bool json = false;
};

std::string orNone(const std::optional<double>& v, const char* format) {
  return v ? fmt::format(fmt::runtime(format), *v) : std::string("–");
}

Status runModelFit(const ModelFitArgs& args) {
  if (args.table.empty()) return badInput("TABLE: expected a path, got an empty string");
  brdf::ModelFitOptions options;
  if (args.start) GLARECAM_ASSIGN(options.start, surface::readMicrofacetFile(*args.start));
  if (args.distribution) {
    const auto distribution = surface::slopeDistributionFromString(*args.distribution);
    if (!distribution)
      return badInput(
          fmt::format("--distribution: \"{}\" is not ggx or beckmann", *args.distribution));
    options.start.distribution = *distribution;
  }
  if (args.refractive_index) options.start.refractive_index = *args.refractive_index;
  options.sun_half_angle_deg = args.source_radius_deg;
  brdf::ModelFitReport report;
  GLARECAM_ASSIGN(report, brdf::fitModelToTable(args.table, options));
  for (const std::string& warning : report.warnings) spdlog::warn("{}", warning);
  const surface::MicrofacetParameters& p = report.fit.parameters;
  if (args.out)
    GLARECAM_CHECK(writeFileAtomic(
        *args.out,
        brdf::surfaceToml(p, fmt::format("fitted by `glarecam model fit {}`", args.table))));
  if (args.json) {
    std::printf("%s", jsonText(brdf::toJson(report)).c_str());
    return {};
  }
  std::string text = fmt::format(
      "{} surface fitted to {} ({} rows, E_ref {:g} klx{}):\n"
      "  width_x  {:.4g}° ± {}  (in the plane of incidence: the vertical axis)\n"
      "  width_y  {:.4g}° ± {}  (across it: the horizontal axis)\n"
      "  lobe_weight {:.4g} ± {}\n"
      "R²            ln Lmax  vertical  horizontal\n"
      "  model       {:7.3f}  {:>8}  {:>10}\n"
      "  empirical   {:7}  {:>8}  {:>10}   (cosine / biquadratic, logistic)\n"
      "alpha_deg  Lmax_cd_m2  model_Lmax  ratio  vertical  model  horizontal  model\n",
      surface::toString(p.distribution), report.source, report.rows.size(),
      report.reference_illuminance_lx / 1000, report.unreferred ? ", unreferred" : "",
      p.width_x_deg, orNone(report.fit.width_x_u_deg, "{:.2g}°"), p.width_y_deg,
      orNone(report.fit.width_y_u_deg, "{:.2g}°"), p.lobe_weight,
      orNone(report.fit.lobe_weight_u, "{:.2g}"), report.model_r2_ln_lmax,
      orNone(report.model_r2_vertical, "{:.3f}"), orNone(report.model_r2_horizontal, "{:.3f}"),
      fmt::format("{}/{}", orNone(report.cosine_r2, "{:.3f}"),
                  orNone(report.biquadratic_r2, "{:.3f}")),
      orNone(report.logistic_vertical_r2, "{:.3f}"),
      orNone(report.logistic_horizontal_r2, "{:.3f}"));
  for (const brdf::ModelFitRow& row : report.rows)
    text += fmt::format(
        "{:>9g}  {:>10.4g}  {:>10.4g}  {:5.2f}  {:>8}  {:>5}  {:>10}  {:>5}\n", row.data.alpha_deg,
        row.data.lmax_cd_m2, row.model.lmax_cd_m2, row.model.lmax_cd_m2 / row.data.lmax_cd_m2,
        orNone(row.data.vertical_deg, "{:.2f}"), orNone(row.model.vertical_deg, "{:.2f}"),
        orNone(row.data.horizontal_deg, "{:.2f}"), orNone(row.model.horizontal_deg, "{:.2f}"));
  text += "prediction: alpha_deg  Lmax_cd_m2  vertical  horizontal\n";
  for (const surface::SurfacePrediction& s : report.predictions)
    text += fmt::format("{:>21g}  {:>10.4g}  {:>8}  {:>10}\n", s.alpha_deg, s.lmax_cd_m2,
                        orNone(s.vertical_deg, "{:.2f}"), orNone(s.horizontal_deg, "{:.2f}"));
  std::printf("%s", text.c_str());
  return {};
}

}  // namespace

void addModelCommand(CLI::App& app, Action& action) {
  auto args = std::make_shared<ModelArgs>();
  CLI::App* sub = app.add_subcommand(
      "model",
      "The paper's five-facet geometric model: γ_ew and γ_ns per α for facet tilt β "
      "(docs/datasheet.md)");
  sub->add_option("--beta", args->beta_deg,
                  "facet tilt β in degrees, (0, 45] (required without fit)");
  sub->add_option("--alpha", args->alpha_deg,
                  "angles of incidence in degrees from the normal (default 0, 5, ... 80)")
      ->expected(1, -1);
  sub->add_flag("--json", args->json,
                "print JSON: {model, beta_deg, rows: [{alpha_deg, "
                "gamma_ew_deg, gamma_ns_deg, valid}]}");
  auto fit_args = std::make_shared<ModelFitArgs>();
  CLI::App* fit = sub->add_subcommand(
      "fit",
      "Fit the microfacet surface model to a sweep (sweep.csv or contours.csv, either route): "
      "its widths and lobe weight with σ, R² beside the empirical fits, the prediction over α "
      "(docs/brdf.md)");
  fit->add_option("TABLE", fit_args->table, "sweep.csv or contours.csv")->required();
  fit->add_option("--start", fit_args->start,
                  "a surface file (TOML, model microfacet) to start from: its coating, second lobe "
                  "and floor are held, its widths and lobe weight fitted")
      ->option_text("FILE");
  fit->add_option("--distribution", fit_args->distribution,
                  "the facets' slope distribution: ggx (default) or beckmann");
  fit->add_option("--refractive-index", fit_args->refractive_index,
                  "the glass's index, held fixed (default 1.52, or --start's)")
      ->check(CLI::Range(1.01, 3.0));
  fit->add_option("--source-radius", fit_args->source_radius_deg,
                  "the source's angular radius in degrees (default 0.2664: the sun; 0: a point)")
      ->check(CLI::Range(0.0, 5.0));
  fit->add_option("--out", fit_args->out, "write the fitted surface as a surface file (TOML)");
  fit->add_flag("--json", fit_args->json, "print the report as JSON");
  fit->callback([fit_args, &action] { action = [fit_args] { return runModelFit(*fit_args); }; });
  sub->callback([args, fit, &action] {
    if (fit->parsed()) return;
    action = [args] { return runModel(*args); };
  });
}

}  // namespace glarecam::apps
