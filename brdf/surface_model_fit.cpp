#include "brdf/surface_model_fit.h"

#include <fmt/format.h>

#include <cmath>
#include <numeric>

#include "core/csv.h"
#include "pipeline/contour_table.h"
#include "pipeline/glare_fits.h"
#include "pipeline/limit_curve.h"

namespace glarecam::brdf {

namespace fs = std::filesystem;

Status ModelFitOptions::validate() const {
  GLARECAM_CHECK(start.validate());
  if (!(sun_half_angle_deg >= 0 && sun_half_angle_deg <= 5))
    return badInput("--source-radius: must be in [0, 5]°");
  return {};
}

namespace {

bool isContourTable(const fs::path& path) {
  std::string first;
  (void)readCsvFile(path, "table", [&](std::vector<std::string>& fields) -> Status {
    if (first.empty()) first = fields.empty() ? "-" : fields.front();
    return badInput("stop");  // the header is all that is needed
  });
  return first == "stack_id";
}

double rSquared(const std::vector<double>& data, const std::vector<double>& model) {
  const double mean = std::accumulate(data.begin(), data.end(), 0.0) / data.size();
  double ss_res = 0, ss_tot = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    ss_res += (data[i] - model[i]) * (data[i] - model[i]);
    ss_tot += (data[i] - mean) * (data[i] - mean);
  }
  return ss_tot > 0 ? 1 - ss_res / ss_tot : 0.0;
}

}  // namespace

Result<std::vector<surface::SurfaceFitRow>> readFitRows(const fs::path& path,
                                                        std::optional<double>& reference_lx) {
  std::vector<surface::SurfaceFitRow> rows;
  if (isContourTable(path)) {
    pipeline::ContourTable table;
    GLARECAM_ASSIGN(table, pipeline::readContourTable(path));
    // One row per stack: its limit rung and its half maximum (Lmax = twice its level).
    std::map<std::string, surface::SurfaceFitRow> by_stack;
    std::map<std::string, bool> has_limit, has_half;
    for (const pipeline::ContourRow& c : table.rows) {
      surface::SurfaceFitRow& row = by_stack[c.stack_id];
      row.alpha_deg = c.alpha_deg;
      if (c.reference_illuminance_lx) reference_lx = c.reference_illuminance_lx;
      if (c.kind == pipeline::ContourKind::kLimit) {
        row.limit_cd_m2 = c.level_cd_m2;
        row.vertical_deg = c.vertical_deg;
        row.horizontal_deg = c.horizontal_deg;
        has_limit[c.stack_id] = true;
      } else if (c.kind == pipeline::ContourKind::kHalfMaximum) {
        row.lmax_cd_m2 = 2 * c.level_cd_m2;
        has_half[c.stack_id] = true;
      }
    }
    for (auto& [stack, row] : by_stack)
      if (has_limit[stack] && has_half[stack]) rows.push_back(row);
    if (rows.empty())
      return badInput(path.string() +
                      ": no stack with both a limit rung and a half maximum: nothing to fit");
  } else {
    pipeline::SweepTable table;
    GLARECAM_ASSIGN(table, pipeline::readSweepTable(path));
    reference_lx = pipeline::tableReferenceIlluminance(table);
    for (const pipeline::SweepRow& r : table.rows) {
      if (!r.limit_cd_m2 || r.isSuspect() || !r.lmax_bound.empty()) continue;
      rows.push_back({.alpha_deg = r.alpha_deg,
                      .limit_cd_m2 = *r.limit_cd_m2,
                      .lmax_cd_m2 = r.lmax_cd_m2,
                      .vertical_deg = r.vertical_deg,
                      .horizontal_deg = r.horizontal_deg});
    }
    if (rows.empty())
      return badInput(path.string() + ": no row with a limit (and a measured Lmax) to fit");
  }
  std::ranges::sort(rows, {}, &surface::SurfaceFitRow::alpha_deg);
  return rows;
}

Result<ModelFitReport> fitModelToTable(const fs::path& path, const ModelFitOptions& options) {
  GLARECAM_CHECK(options.validate());
  ModelFitReport report;
  report.source = path.string();
  std::optional<double> reference;
  std::vector<surface::SurfaceFitRow> rows;
  GLARECAM_ASSIGN(rows, readFitRows(path, reference));
  report.unreferred = !reference;
  report.reference_illuminance_lx = reference.value_or(kDefaultReferenceIlluminanceLx);
  if (report.unreferred)
    report.warnings.push_back(fmt::format(
        "{}: unreferred: fitted as if its luminances were at E = {:g} klx (the lobe weight "
        "then carries the day's sun)",
        path.string(), report.reference_illuminance_lx / 1000));
  surface::SurfaceFitOptions fit_options;
  fit_options.start = options.start;
  fit_options.lobe.illuminance_lx = report.reference_illuminance_lx;
  fit_options.lobe.sun_half_angle_deg = options.sun_half_angle_deg;
  fit_options.lobe.disc_rings = 3;  // 49 points: the disc blurs a lobe of degrees by 0.1 %
  GLARECAM_ASSIGN(report.fit, surface::fitSurface(rows, fit_options));
  std::vector<double> ln_data, ln_model, v_data, v_model, h_data, h_model, alphas;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const surface::SurfacePrediction& m = report.fit.fitted[i];
    report.rows.push_back({rows[i], m});
    alphas.push_back(rows[i].alpha_deg);
    ln_data.push_back(std::log(rows[i].lmax_cd_m2));
    ln_model.push_back(std::log(m.lmax_cd_m2));
    if (rows[i].vertical_deg && m.vertical_deg) {
      v_data.push_back(*rows[i].vertical_deg);
      v_model.push_back(*m.vertical_deg);
    }
    if (rows[i].horizontal_deg && m.horizontal_deg) {
      h_data.push_back(*rows[i].horizontal_deg);
      h_model.push_back(*m.horizontal_deg);
    }
  }
  report.model_r2_ln_lmax = rSquared(ln_data, ln_model);
  if (v_data.size() >= 2) report.model_r2_vertical = rSquared(v_data, v_model);
  if (h_data.size() >= 2) report.model_r2_horizontal = rSquared(h_data, h_model);
  // The paper's empirical fits on the same rows.
  pipeline::SweepTable same;
  for (const surface::SurfaceFitRow& r : rows) {
    pipeline::SweepRow row;
    row.alpha_deg = r.alpha_deg;
    row.limit_cd_m2 = r.limit_cd_m2;
    row.lmax_cd_m2 = r.lmax_cd_m2;
    row.vertical_deg = r.vertical_deg;
    row.horizontal_deg = r.horizontal_deg;
    same.rows.push_back(std::move(row));
  }
  if (const auto empirical = pipeline::fitSweep(same)) {
    report.cosine_r2 = empirical->cosine.quality.r2;
    report.biquadratic_r2 = empirical->biquadratic.quality.r2;
    if (empirical->vertical.logistic)
      report.logistic_vertical_r2 = empirical->vertical.logistic->quality.r2;
    if (empirical->horizontal.logistic)
      report.logistic_horizontal_r2 = empirical->horizontal.logistic->quality.r2;
  } else {
    report.warnings.push_back("the empirical fits could not be made: " + empirical.error().message);
  }
  for (double a = 0; a <= options.predict_max_deg + 1e-9; a += options.predict_step_deg) {
    const std::optional<double> limit = pipeline::glareLimitCdM2(a);
    if (!limit) continue;
    report.predictions.push_back(
        surface::predict(report.fit.parameters, a, *limit, fit_options.lobe));
  }
  return report;
}

nlohmann::json toJson(const ModelFitReport& r) {
  const surface::MicrofacetParameters& p = r.fit.parameters;
  const auto optional = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  nlohmann::json rows = nlohmann::json::array();
  for (const ModelFitRow& row : r.rows)
    rows.push_back({{"alpha_deg", row.data.alpha_deg},
                    {"limit_cd_m2", row.data.limit_cd_m2},
                    {"lmax_cd_m2", row.data.lmax_cd_m2},
                    {"model_lmax_cd_m2", row.model.lmax_cd_m2},
                    {"lmax_ratio", row.model.lmax_cd_m2 / row.data.lmax_cd_m2},
                    {"vertical_deg", optional(row.data.vertical_deg)},
                    {"model_vertical_deg", optional(row.model.vertical_deg)},
                    {"horizontal_deg", optional(row.data.horizontal_deg)},
                    {"model_horizontal_deg", optional(row.model.horizontal_deg)}});
  nlohmann::json predictions = nlohmann::json::array();
  for (const surface::SurfacePrediction& s : r.predictions)
    predictions.push_back({{"alpha_deg", s.alpha_deg},
                           {"lmax_cd_m2", s.lmax_cd_m2},
                           {"vertical_deg", optional(s.vertical_deg)},
                           {"horizontal_deg", optional(s.horizontal_deg)}});
  return {{"source", r.source},
          {"reference_illuminance_lx", r.reference_illuminance_lx},
          {"unreferred", r.unreferred},
          {"model",
           {{"distribution", surface::toString(p.distribution)},
            {"width_x_deg", p.width_x_deg},
            {"width_x_u_deg", optional(r.fit.width_x_u_deg)},
            {"width_y_deg", p.width_y_deg},
            {"width_y_u_deg", optional(r.fit.width_y_u_deg)},
            {"lobe_weight", p.lobe_weight},
            {"lobe_weight_u", optional(r.fit.lobe_weight_u)},
            {"refractive_index", p.refractive_index}}},
          {"r2",
           {{"model_ln_lmax", r.model_r2_ln_lmax},
            {"model_vertical", optional(r.model_r2_vertical)},
            {"model_horizontal", optional(r.model_r2_horizontal)},
            {"cosine_ln_lmax", optional(r.cosine_r2)},
            {"biquadratic_ln_lmax", optional(r.biquadratic_r2)},
            {"logistic_vertical", optional(r.logistic_vertical_r2)},
            {"logistic_horizontal", optional(r.logistic_horizontal_r2)}}},
          {"rows", rows},
          {"predictions", predictions},
          {"warnings", r.warnings}};
}

std::string surfaceToml(const surface::MicrofacetParameters& p, const std::string& comment) {
  std::string text;
  for (std::size_t start = 0; start < comment.size();) {
    const std::size_t end = comment.find('\n', start);
    text += "# " + comment.substr(start, end == std::string::npos ? end : end - start) + "\n";
    if (end == std::string::npos) break;
    start = end + 1;
  }
  text += fmt::format(
      "[surface]\nmodel = \"microfacet\"\ndistribution = \"{}\"\nwidth_x_deg = {:.6g}\n"
      "width_y_deg = {:.6g}\nlobe_weight = {:.6g}\nrefractive_index = {:.6g}\n",
      surface::toString(p.distribution), p.width_x_deg, p.width_y_deg, p.lobe_weight,
      p.refractive_index);
  if (p.coating_index)
    text += fmt::format("coating_index = {:.6g}\ncoating_thickness_nm = {:.6g}\n", *p.coating_index,
                        p.coating_thickness_nm);
  if (p.second_lobe_weight > 0)
    text += fmt::format("second_lobe_weight = {:.6g}\nsecond_lobe_width_deg = {:.6g}\n",
                        p.second_lobe_weight, p.second_lobe_width_deg);
  if (p.diffuse_reflectance > 0)
    text += fmt::format("diffuse_reflectance = {:.6g}\n", p.diffuse_reflectance);
  return text;
}

}  // namespace glarecam::brdf
