#include "surface/surface_fit.h"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>

namespace glarecam::surface {

namespace {

constexpr int kParameters = 3;  // ln width_x, ln width_y, ln lobe_weight
constexpr int kResiduals = 3;   // ln Lmax, vertical, horizontal

MicrofacetParameters withFitted(const MicrofacetParameters& start, const double* p) {
  MicrofacetParameters m = start;
  m.width_x_deg = std::exp(p[0]);
  m.width_y_deg = std::exp(p[1]);
  m.lobe_weight = std::exp(p[2]);
  return m;
}

// A row without an ellipse, or a model without one where the row has one, weighs as this many
// scales: the fit is pushed toward the right side of the limit, not left undefined.
constexpr double kMissingPenalty = 10;

struct RowCost {
  SurfaceFitRow row;
  const SurfaceFitOptions* options;
  bool operator()(const double* p, double* r) const {
    const MicrofacetParameters m = withFitted(options->start, p);
    if (!m.validate()) return false;
    const SurfacePrediction s = predict(m, row.alpha_deg, row.limit_cd_m2, options->lobe);
    r[0] = (std::log(s.lmax_cd_m2) - std::log(row.lmax_cd_m2)) / options->lmax_scale;
    const auto axis = [&](const std::optional<double>& model, const std::optional<double>& data) {
      if (model && data) return (*model - *data) / options->axis_scale_deg;
      return model.has_value() == data.has_value() ? 0.0 : kMissingPenalty;
    };
    r[1] = axis(s.vertical_deg, row.vertical_deg);
    r[2] = axis(s.horizontal_deg, row.horizontal_deg);
    return true;
  }
};

}  // namespace

Status SurfaceFitOptions::validate() const {
  GLARECAM_CHECK(start.validate());
  if (!(lmax_scale > 0 && axis_scale_deg > 0))
    return badInput("model fit: scales must be positive");
  if (max_iterations < 1) return badInput("model fit: at least one iteration");
  return {};
}

SurfacePrediction predict(const MicrofacetParameters& parameters, double alpha_deg,
                          double limit_cd_m2, const LobeOptions& lobe) {
  const MicrofacetBrdf model(parameters);
  const double levels[] = {limit_cd_m2};
  const LobeContours c = lobeContours(model, alpha_deg, levels, lobe);
  return {.alpha_deg = alpha_deg,
          .lmax_cd_m2 = c.peak_cd_m2,
          .vertical_deg = c.contours[0].vertical_deg,
          .horizontal_deg = c.contours[0].horizontal_deg};
}

Result<SurfaceFit> fitSurface(const std::vector<SurfaceFitRow>& rows,
                              const SurfaceFitOptions& options) {
  GLARECAM_CHECK(options.validate());
  if (rows.size() < 2)
    return badInput(fmt::format("model fit: {} rows; at least 2 for 3 parameters on 3 values a row",
                                rows.size()));
  double p[kParameters] = {std::log(options.start.width_x_deg), std::log(options.start.width_y_deg),
                           std::log(options.start.lobe_weight)};
  ceres::Problem problem;
  // Steps of 1 % in the log parameters: the contours are bisected to 1e-5°, and a step must
  // move them by far more than that (1 % of a 5° axis is 0.05°).
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = 1e-2;
  for (const SurfaceFitRow& row : rows)
    problem.AddResidualBlock(
        new ceres::NumericDiffCostFunction<RowCost, ceres::CENTRAL, kResiduals, kParameters>(
            new RowCost{row, &options}, ceres::TAKE_OWNERSHIP, kResiduals, diff),
        nullptr, p);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (std::getenv("GLARECAM_DEBUG_FIT")) fmt::print(stderr, "{}\n", summary.FullReport());
  if (!summary.IsSolutionUsable())
    return fail(ErrorCode::kInternal, "model fit: the solver failed: " + summary.message);
  SurfaceFit fit;
  fit.parameters = withFitted(options.start, p);
  fit.cost = summary.final_cost;
  fit.iterations = static_cast<int>(summary.iterations.size());
  // σ from the Jacobian at the optimum, (JᵀJ)⁻¹ scaled by the residuals' own variance (the
  // scales are guesses of the data's σ); none when JᵀJ is singular (a parameter the rows do
  // not determine).
  double cost = 0;
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, &crs);
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) jacobian(r, crs.cols[k]) = crs.values[k];
  const Eigen::MatrixXd normal = jacobian.transpose() * jacobian;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(normal);
  if (lu.rank() == kParameters) {
    const Eigen::MatrixXd c = lu.inverse();
    const int dof = static_cast<int>(rows.size()) * kResiduals - kParameters;
    const double s2 = dof > 0 ? 2 * fit.cost / dof : 1.0;
    fit.width_x_u_deg = fit.parameters.width_x_deg * std::sqrt(c(0, 0) * s2);
    fit.width_y_u_deg = fit.parameters.width_y_deg * std::sqrt(c(1, 1) * s2);
    fit.lobe_weight_u = fit.parameters.lobe_weight * std::sqrt(c(2, 2) * s2);
  }
  for (const SurfaceFitRow& row : rows)
    fit.fitted.push_back(predict(fit.parameters, row.alpha_deg, row.limit_cd_m2, options.lobe));
  return fit;
}

}  // namespace glarecam::surface
