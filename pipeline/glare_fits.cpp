#include "pipeline/glare_fits.h"

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <tuple>

#include "core/json.h"

namespace glarecam::pipeline {

namespace {

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

// A scaled-Jacobian condition number above this means some combination of parameters moves the
// curve by less than 1e-4 of what the best-determined one does: the parameters trade off
// against each other (the horizontal logistic of the paper's Table III is the textbook case).
// Belsley, Kuh & Welsch (1980) call condition indices above 30-100 strong dependence; we flag
// only what makes individual parameters meaningless.
constexpr double kIllConditionedNumber = 1e4;
// Two estimates correlated this strongly inflate each other's variance by 1 / (1 - r²) >= 500:
// each is known 20 times worse than if the other were fixed, so neither means much alone.
constexpr double kStrongCorrelation = 0.999;

// Multi-start: the shape parameters of a separable model are gridded, the linear ones solved
// exactly at each grid point, and the best distinct grid points refined.
constexpr int kRefinedStarts = 8;
constexpr int kGridSteps = 48;
// The logistic's centre b is searched this many measured α spans beyond the data on each side
// (the paper's horizontal fit has b = 190.5° for data up to 80°: a logistic tail).
constexpr double kCentreSearchSpans = 3.0;
// |d| (1/°) and |c| of the cosine function are gridded log-uniformly over these decades.
constexpr double kSteepnessMin = 1e-3, kSteepnessMax = 3.0;
constexpr double kCosinePowerMin = 1e-3, kCosinePowerMax = 10.0;
constexpr int kSolverIterations = 1000;
constexpr double kSolverTolerance = 1e-14;

// The smallest and largest α of a non-empty set.
std::pair<double, double> alphaRange(std::span<const double> alpha_deg) {
  const auto [lo, hi] = std::minmax_element(alpha_deg.begin(), alpha_deg.end());
  return {*lo, *hi};
}

struct Samples {
  std::span<const double> alpha_deg, y;
  int size() const { return static_cast<int>(alpha_deg.size()); }
};

// ---- quality of a fit -------------------------------------------------------------------------

FitQuality assessFit(const Samples& s, const Vector& residuals, const Matrix& jacobian,
                     std::vector<double> parameters) {
  FitQuality q;
  q.parameters = std::move(parameters);
  q.points = s.size();
  const int p = static_cast<int>(q.parameters.size());
  const double mean = Eigen::Map<const Vector>(s.y.data(), s.size()).mean();
  double total = 0;
  for (double y : s.y) total += (y - mean) * (y - mean);
  const double sse = residuals.squaredNorm();
  q.r2 = total > 0 ? 1.0 - sse / total : std::numeric_limits<double>::quiet_NaN();
  q.rmse = std::sqrt(sse / q.points);
  q.under_determined = q.points <= p;

  Vector scale = jacobian.colwise().norm().transpose();
  for (double& v : scale) v = v > 0 ? v : 1.0;
  const Matrix scaled = jacobian * scale.cwiseInverse().asDiagonal();
  Eigen::JacobiSVD<Matrix> svd(scaled, Eigen::ComputeThinV);
  const Vector sigma = svd.singularValues();
  // Beyond 1/ε the smallest singular value is rounding noise: the Jacobian is singular.
  constexpr double kSingularCondition = 1 / std::numeric_limits<double>::epsilon();
  q.condition_number = sigma(sigma.size() - 1) > 0 ? sigma(0) / sigma(sigma.size() - 1)
                                                   : std::numeric_limits<double>::infinity();
  if (q.condition_number > kSingularCondition)
    q.condition_number = std::numeric_limits<double>::infinity();
  q.standard_errors.assign(p, std::nullopt);
  q.ill_conditioned = !(q.condition_number < kIllConditionedNumber);
  if (!std::isfinite(q.condition_number)) {
    q.max_correlation = std::numeric_limits<double>::quiet_NaN();  // singular: undefined
    return q;
  }
  // Covariance s² (JᵀJ)⁻¹, via the SVD of the scaled Jacobian; correlations need no s².
  const Matrix v_over_sigma = svd.matrixV() * sigma.cwiseInverse().asDiagonal();
  const Matrix covariance = v_over_sigma * v_over_sigma.transpose();  // scaled, without s²
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < i; ++j) {
      const double r = covariance(i, j) / std::sqrt(covariance(i, i) * covariance(j, j));
      q.max_correlation = std::min(1.0, std::max(q.max_correlation, std::abs(r)));
    }
  }
  q.ill_conditioned = q.ill_conditioned || q.max_correlation >= kStrongCorrelation;
  if (q.under_determined) return q;
  const double variance = sse / (q.points - p);
  for (int i = 0; i < p; ++i)
    q.standard_errors[i] = std::sqrt(variance * covariance(i, i)) / scale(i);
  return q;
}

// ---- linear least squares ---------------------------------------------------------------------

// Coefficients minimising |X β - y|, columns scaled to unit norm first (α⁴ and 1 differ by 1e7).
Vector solveLinear(const Matrix& x, const Vector& y) {
  Vector scale = x.colwise().norm().transpose();
  for (double& v : scale) v = v > 0 ? v : 1.0;
  const Matrix scaled = x * scale.cwiseInverse().asDiagonal();
  return scaled.colPivHouseholderQr().solve(y).cwiseQuotient(scale);
}

// ---- separable models: shape grid, linear solve, Ceres refinement ---------------------------

// A model y = lin0 * basis(α; shape) + lin1 [+ lin2 * ...]: the shape parameters are gridded;
// for each, the linear parameters follow by least squares.
struct GridPoint {
  std::vector<double> parameters;  // all of them, in the model's order
  double sse = std::numeric_limits<double>::infinity();
  std::array<int, 2> cell{};  // the shape parameters' grid indices
};

// A grid axis: values and, for each, a signed index in which neighbours differ by 1.
struct GridAxis {
  std::vector<double> values;
  std::vector<int> index;
};

// ±lo ... ±hi, log-uniform; the index runs -steps..-1, 1..steps so that +lo and -lo are apart.
GridAxis logSpacedBothSigns(double lo, double hi, int steps) {
  GridAxis axis;
  for (int i = 0; i < steps; ++i) {
    const double v = lo * std::pow(hi / lo, static_cast<double>(i) / (steps - 1));
    for (int sign : {1, -1}) {
      axis.values.push_back(sign * v);
      axis.index.push_back(sign * (i + 1));
    }
  }
  return axis;
}

GridAxis linSpaced(double lo, double hi, int steps) {
  GridAxis axis;
  for (int i = 0; i < steps; ++i) {
    axis.values.push_back(lo + (hi - lo) * i / (steps - 1));
    axis.index.push_back(i);
  }
  return axis;
}

// The logistic's centre b: the regular grid plus every sample's α and every midpoint between
// neighbouring samples, so that a transition steeper than the sample spacing has a start on each
// side of every sample (Levenberg–Marquardt cannot move b across a sample there: ∂f/∂b ≈ 0).
GridAxis centreCandidates(const Samples& s, const GridAxis& regular) {
  std::vector<double> values = regular.values;
  std::vector<double> alphas(s.alpha_deg.begin(), s.alpha_deg.end());
  std::sort(alphas.begin(), alphas.end());
  alphas.erase(std::unique(alphas.begin(), alphas.end()), alphas.end());
  for (std::size_t i = 0; i < alphas.size(); ++i) {
    values.push_back(alphas[i]);
    if (i + 1 < alphas.size()) values.push_back((alphas[i] + alphas[i + 1]) / 2);
  }
  std::sort(values.begin(), values.end());
  GridAxis axis;
  for (double v : values) {
    axis.values.push_back(v);
    axis.index.push_back(static_cast<int>(axis.index.size()));
  }
  return axis;
}

bool neighbours(const GridPoint& a, const GridPoint& b) {
  return std::abs(a.cell[0] - b.cell[0]) <= 1 && std::abs(a.cell[1] - b.cell[1]) <= 1;
}

// The best grid points, none a grid neighbour of a better one chosen before it (neighbouring
// starts converge to the same minimum).
std::vector<GridPoint> bestDistinct(std::vector<GridPoint> grid, int count) {
  std::sort(grid.begin(), grid.end(),
            [](const GridPoint& a, const GridPoint& b) { return a.sse < b.sse; });
  std::vector<GridPoint> chosen;
  for (const GridPoint& g : grid) {
    if (!std::isfinite(g.sse) || static_cast<int>(chosen.size()) == count) break;
    if (std::none_of(chosen.begin(), chosen.end(),
                     [&](const GridPoint& c) { return neighbours(c, g); }))
      chosen.push_back(g);
  }
  return chosen;
}

// Residual y_i - f(α_i; p) of a model given as Model::evaluate(alpha, const T* p).
template <typename Model>
struct Residual {
  double alpha, y;
  template <typename T>
  bool operator()(const T* p, T* residual) const {
    residual[0] = T(y) - Model::evaluate(alpha, p);
    return true;
  }
};

template <typename Model, int kParameters>
std::unique_ptr<ceres::Problem> makeProblem(const Samples& s, double* parameters) {
  auto problem = std::make_unique<ceres::Problem>();
  for (int i = 0; i < s.size(); ++i) {
    using Cost = Residual<Model>;
    problem->AddResidualBlock(
        new ceres::AutoDiffCostFunction<Cost, 1, kParameters>(new Cost{s.alpha_deg[i], s.y[i]}),
        nullptr, parameters);
  }
  return problem;
}

double problemCost(ceres::Problem& problem) {
  double cost = 0;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, nullptr);
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

// The model's canonical form of the parameters, unless rewriting them loses accuracy (in a
// logistic tail, a + c cancels catastrophically): then they stay as the solver left them.
template <typename Model>
void canonicaliseIfExact(ceres::Problem& problem, double* p, int count) {
  constexpr double kCostSlack = 1e-9;  // relative: rounding, not a different curve
  const std::vector<double> solved(p, p + count);
  const double cost = problemCost(problem);
  Model::canonicalise(p);
  if (!(problemCost(problem) <= cost * (1 + kCostSlack)))
    std::copy(solved.begin(), solved.end(), p);
}

// Levenberg–Marquardt from `start`; the fit's quality from the Jacobian at the optimum.
template <typename Model, int kParameters>
FitQuality refine(const Samples& s, const std::vector<double>& start) {
  std::array<double, kParameters> p{};
  std::copy(start.begin(), start.end(), p.begin());
  auto problem = makeProblem<Model, kParameters>(s, p.data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = kSolverIterations;
  options.function_tolerance = kSolverTolerance;
  options.parameter_tolerance = kSolverTolerance;
  options.gradient_tolerance = kSolverTolerance;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, problem.get(), &summary);
  canonicaliseIfExact<Model>(*problem, p.data(), kParameters);

  double cost = 0;
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  problem->Evaluate(ceres::Problem::EvaluateOptions(), &cost, &residuals, nullptr, &crs);
  Matrix jacobian = Matrix::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) jacobian(r, crs.cols[k]) = crs.values[k];
  }
  // Ceres's residual is y - f, so its Jacobian is -∂f/∂p: the sign does not matter below.
  return assessFit(s, Eigen::Map<Vector>(residuals.data(), residuals.size()), jacobian,
                   std::vector<double>(p.begin(), p.end()));
}

// Refines every start and keeps the best, recording what each start reached. A fit's work is
// bounded by kRefinedStarts × kSolverIterations Levenberg–Marquardt iterations whatever the
// table holds: on hostile numbers (most starts drifting along a valley to the limit) that is
// about 0.1 s for 40 rows (measured, release build; issue 21's fuzzing).
template <typename Model, int kParameters>
Result<FitQuality> multiStart(const Samples& s, const std::vector<GridPoint>& starts) {
  if (starts.empty())
    return badInput("no finite starting point: the values are far outside a physical range");
  FitQuality best;
  best.r2 = -std::numeric_limits<double>::infinity();
  std::vector<double> reached;
  for (const GridPoint& start : starts) {
    FitQuality q = refine<Model, kParameters>(s, start.parameters);
    reached.push_back(q.r2);
    const bool better = std::isfinite(q.r2) && !(q.r2 <= best.r2);  // NaN R² never wins
    if (better || best.parameters.empty()) best = std::move(q);
  }
  best.start_r2 = std::move(reached);
  return best;
}

// ---- the three models -------------------------------------------------------------------------

struct CosineModel {  // p = (a, b, c)
  template <typename T>
  static T evaluate(double alpha, const T* p) {
    return cosineLnL(alpha, p[0], p[1], p[2]);
  }
  static void canonicalise(double*) {}
};

struct LogisticModel {  // p = (a, b, c, d)
  template <typename T>
  static T evaluate(double alpha, const T* p) {
    return logistic(alpha, p[0], p[1], p[2], p[3]);
  }
  // (a, b, c, d) and (-a, b, a + c, -d) are the same curve; report the one with d >= 0, as the
  // paper does, so that parameters compare across fits.
  static void canonicalise(double* p) {
    if (p[3] >= 0) return;
    p[2] += p[0];
    p[0] = -p[0];
    p[3] = -p[3];
  }
};

// For each shape value, the linear parameters (the basis' coefficient and the constant) by
// least squares; `basis(alpha, shape...)` is the model's nonlinear part. A straight line through
// (basis(α), y) in closed form, about the means: the grid solves it some ten thousand times a
// fit, and a QR factorisation each time was a quarter of a fit's instructions (release build)
// and over half its time under AddressSanitizer.
template <typename Basis>
GridPoint solveSeparable(const Samples& s, const Basis& basis) {
  const int n = s.size();
  std::vector<double> x(n);
  double x_mean = 0, y_mean = 0, x_squares = 0;
  for (int i = 0; i < n; ++i) {
    x[i] = basis(s.alpha_deg[i]);
    x_mean += x[i];
    y_mean += s.y[i];
    x_squares += x[i] * x[i];
  }
  GridPoint g{.parameters = {0.0, 0.0}};
  if (!std::isfinite(x_squares) || !std::isfinite(y_mean)) return g;  // sse = ∞: no start here
  x_mean /= n;
  y_mean /= n;
  double sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    sxx += (x[i] - x_mean) * (x[i] - x_mean);
    sxy += (x[i] - x_mean) * (s.y[i] - y_mean);
  }
  // The basis is a constant when what is left of it beside the constant column is within
  // rounding of its norm (the rank test of a column-pivoted QR on the unit-scaled columns):
  // then the constant alone fits, as a rank-revealing solve would give.
  constexpr double kRankTolerance = 2 * std::numeric_limits<double>::epsilon();
  const bool constant_basis = !(sxx > kRankTolerance * kRankTolerance * x_squares);
  const double slope = constant_basis ? 0.0 : sxy / sxx;
  const double intercept = y_mean - slope * x_mean;
  double sse = 0;
  for (int i = 0; i < n; ++i) {
    const double r = slope * x[i] + intercept - s.y[i];
    sse += r * r;
  }
  g.parameters = {slope, intercept};
  g.sse = std::isfinite(sse) ? sse : std::numeric_limits<double>::infinity();
  return g;
}

Status requirePoints(const Samples& s, int parameters, const char* what) {
  std::set<double> distinct(s.alpha_deg.begin(), s.alpha_deg.end());
  if (static_cast<int>(distinct.size()) < parameters)
    return badInput(fmt::format("{}: {} distinct α values, but the function has {} parameters",
                                what, distinct.size(), parameters));
  return {};
}

}  // namespace

Result<BiquadraticFit> fitBiquadratic(std::span<const double> alpha_deg,
                                      std::span<const double> ln_l) {
  const Samples s{alpha_deg, ln_l};
  GLARECAM_CHECK(requirePoints(s, kBiquadraticParameters, "biquadratic fit"));
  Matrix x(s.size(), kBiquadraticParameters);
  for (int i = 0; i < s.size(); ++i) {
    const double a2 = alpha_deg[i] * alpha_deg[i];
    x.row(i) << a2 * a2, a2, 1.0;
  }
  const Vector y = Eigen::Map<const Vector>(ln_l.data(), s.size());
  const Vector beta = solveLinear(x, y);
  BiquadraticFit fit{.curve = {.a = beta(0), .b = beta(1), .c = beta(2)},
                     .quality = assessFit(s, y - x * beta, x, {beta(0), beta(1), beta(2)})};
  return fit;
}

Result<CosineFit> fitCosine(std::span<const double> alpha_deg, std::span<const double> ln_l) {
  const Samples s{alpha_deg, ln_l};
  GLARECAM_CHECK(requirePoints(s, kCosineParameters, "cosine fit"));
  std::vector<GridPoint> grid;
  const GridAxis powers = logSpacedBothSigns(kCosinePowerMin, kCosinePowerMax, kGridSteps);
  for (std::size_t i = 0; i < powers.values.size(); ++i) {
    const double c = powers.values[i];
    GridPoint g = solveSeparable(s, [c](double alpha) { return cosineLnL(alpha, 0.0, 1.0, c); });
    g.parameters = {g.parameters[1], g.parameters[0], c};  // (a, b, c)
    g.cell = {powers.index[i], 0};
    grid.push_back(std::move(g));
  }
  FitQuality q;
  GLARECAM_ASSIGN(
      q, (multiStart<CosineModel, kCosineParameters>(s, bestDistinct(grid, kRefinedStarts))));
  const auto& p = q.parameters;
  return CosineFit{.curve = {.a = p[0], .b = p[1], .c = p[2]}, .quality = std::move(q)};
}

LogisticFit refineLogistic(std::span<const double> alpha_deg, std::span<const double> y_deg,
                           const LogisticCurve& start) {
  FitQuality q = refine<LogisticModel, kLogisticParameters>({alpha_deg, y_deg},
                                                            {start.a, start.b, start.c, start.d});
  const auto& p = q.parameters;
  return {.curve = {.a = p[0], .b = p[1], .c = p[2], .d = p[3]}, .quality = std::move(q)};
}

Result<LogisticFit> fitLogistic(std::span<const double> alpha_deg, std::span<const double> y_deg) {
  const Samples s{alpha_deg, y_deg};
  GLARECAM_CHECK(requirePoints(s, kLogisticParameters, "logistic fit"));
  const auto [lo, hi] = alphaRange(alpha_deg);
  const double reach = kCentreSearchSpans * (hi - lo);
  std::vector<GridPoint> grid;
  const GridAxis centres = centreCandidates(s, linSpaced(lo - reach, hi + reach, kGridSteps));
  const GridAxis steepness = logSpacedBothSigns(kSteepnessMin, kSteepnessMax, kGridSteps);
  for (std::size_t i = 0; i < centres.values.size(); ++i) {
    for (std::size_t j = 0; j < steepness.values.size(); ++j) {
      const double b = centres.values[i], d = steepness.values[j];
      GridPoint g =
          solveSeparable(s, [b, d](double alpha) { return logistic(alpha, 1.0, b, 0.0, d); });
      g.parameters = {g.parameters[0], b, g.parameters[1], d};  // (a, b, c, d)
      g.cell = {centres.index[i], steepness.index[j]};
      grid.push_back(std::move(g));
    }
  }
  FitQuality q;
  GLARECAM_ASSIGN(
      q, (multiStart<LogisticModel, kLogisticParameters>(s, bestDistinct(grid, kRefinedStarts))));
  const auto& p = q.parameters;
  return LogisticFit{.curve = {.a = p[0], .b = p[1], .c = p[2], .d = p[3]},
                     .quality = std::move(q)};
}

namespace {

// |r| near 1 as "1 − 3.4e-05" rather than a rounded "1.0000"; "n/a" for a singular fit.
std::string correlationText(double r) {
  constexpr double kShowDistanceFromOne = 0.9999;
  if (!std::isfinite(r)) return "n/a";
  if (r >= 1) return "1";
  if (r >= kShowDistanceFromOne) return fmt::format("1 \u2212 {:.1e}", 1 - r);
  return fmt::format("{:.4f}", r);
}

std::string describe(const char* name, const FitQuality& q) {
  if (q.under_determined)
    return fmt::format(
        "{}: under-determined ({} points for {} parameters): no residual degrees of "
        "freedom, so R² does not measure the fit and there are no standard errors",
        name, q.points, q.parameters.size());
  if (q.ill_conditioned)
    return fmt::format(
        "{}: ill-conditioned (condition number {:.2g}, parameter correlation {}): the "
        "parameters trade off against each other and are not individually determined; compare "
        "curves and R², not parameters",
        name, q.condition_number, correlationText(q.max_correlation));
  return {};
}

void noteQuality(std::vector<std::string>& warnings, const char* name, const FitQuality& q) {
  if (std::string text = describe(name, q); !text.empty()) warnings.push_back(std::move(text));
}

// A logistic rises from 12 % to 88 % of its step over 4 / |d| degrees. When that is shorter than
// the gap between the samples it falls in, the data do not resolve the transition: the fit jumps
// between two samples and its values there are a guess. Empty when the transition is resolved.
std::string sharpStep(std::vector<double> alpha, const LogisticCurve& curve) {
  constexpr double kTransitionWidthPerD = 4.0;
  if (curve.d == 0) return {};
  const double width_deg = kTransitionWidthPerD / std::abs(curve.d);
  std::sort(alpha.begin(), alpha.end());
  const auto after = std::upper_bound(alpha.begin(), alpha.end(), curve.b);
  if (after == alpha.begin() || after == alpha.end()) return {};  // a tail: no step inside
  const double gap_deg = *after - *(after - 1);
  if (width_deg >= gap_deg) return {};
  return fmt::format(
      "the logistic steps from one value to another within {:.2g}° at α {:.1f}°, "
      "between samples {:g}° apart: the data do not resolve that transition, and "
      "the function may not suit this axis",
      width_deg, curve.b, gap_deg);
}

AxisFit fitAxis(const SweepTable& table, std::optional<double> SweepRow::*axis, const char* name,
                std::vector<std::string>& warnings) {
  std::vector<double> alpha, y;
  for (const SweepRow& row : table.rows) {
    if (!(row.*axis)) continue;
    alpha.push_back(row.alpha_deg);
    y.push_back(*(row.*axis));
  }
  AxisFit fit{.logistic = std::nullopt, .rows_with_ellipse = static_cast<int>(alpha.size())};
  if (!alpha.empty()) std::tie(fit.alpha_min_deg, fit.alpha_max_deg) = alphaRange(alpha);
  auto logistic = fitLogistic(alpha, y);
  if (!logistic) {
    warnings.push_back(fmt::format("{} logistic not fitted: {} rows with an ellipse ({})", name,
                                   alpha.size(), logistic.error().message));
    return fit;
  }
  noteQuality(warnings, name, logistic->quality);
  if (std::string step = sharpStep(alpha, logistic->curve); !step.empty())
    warnings.push_back(fmt::format("{}: {}", name, step));
  fit.logistic = std::move(*logistic);
  return fit;
}

nlohmann::json qualityJson(const FitQuality& q, std::initializer_list<const char*> names) {
  nlohmann::json j, errors;
  int i = 0;
  for (const char* name : names) {
    j[name] = q.parameters[i];
    errors[name] = jsonOrNull(q.standard_errors[i]);
    ++i;
  }
  j["standard_errors"] = errors;
  j["r2"] = finiteOrNull(q.r2);
  j["rmse"] = q.rmse;
  j["points"] = q.points;
  j["condition_number"] = finiteOrNull(q.condition_number);
  j["under_determined"] = q.under_determined;
  j["ill_conditioned"] = q.ill_conditioned;
  j["max_correlation"] = finiteOrNull(q.max_correlation);
  j["starts"] = q.start_r2.size();
  return j;
}

nlohmann::json axisJson(const AxisFit& axis) {
  return {{"rows_with_ellipse", axis.rows_with_ellipse},
          {"alpha_range_deg", axis.rows_with_ellipse > 0
                                  ? nlohmann::json{axis.alpha_min_deg, axis.alpha_max_deg}
                                  : nlohmann::json(nullptr)},
          {"logistic", axis.logistic ? qualityJson(axis.logistic->quality, {"a", "b", "c", "d"})
                                     : nlohmann::json(nullptr)}};
}

std::string parameterText(const FitQuality& q, std::initializer_list<const char*> names) {
  std::string text;
  int i = 0;
  for (const char* name : names) {
    text += fmt::format("  {} = {:.5g}", name, q.parameters[i]);
    if (q.standard_errors[i]) text += fmt::format(" ± {:.2g}", *q.standard_errors[i]);
    ++i;
  }
  return text;
}

std::string fitLine(const char* label, const char* formula, const FitQuality& q,
                    std::initializer_list<const char*> names, const char* unit) {
  std::string flags;
  if (q.under_determined) flags += "  (under-determined)";
  if (q.ill_conditioned) flags += "  (ill-conditioned)";
  return fmt::format(
      "{:<22}{}\n{:<22}{}\n{:<22}  R² = {:.4f}  RMSE = {:.3g} {}  n = {}  cond = {:.3g}  "
      "max |corr| = {}{}\n",
      label, formula, "", parameterText(q, names), "", q.r2, q.rmse, unit, q.points,
      q.condition_number, correlationText(q.max_correlation), flags);
}

std::string axisReport(const char* label, const AxisFit& axis) {
  if (!axis.logistic)
    return fmt::format("{:<22}not fitted ({} rows with an ellipse)\n", label,
                       axis.rows_with_ellipse);
  return fitLine(label, "y = a / (1 + exp(-(α - b) d)) + c", axis.logistic->quality,
                 {"a", "b", "c", "d"}, "°");
}

}  // namespace

std::string fitsReport(const SweepFits& fits) {
  std::string text = fmt::format("α from {:g}° to {:g}°\n", fits.alpha_min_deg, fits.alpha_max_deg);
  text += fitLine("luminance cos", "ln L = a + b / cos(α)^c", fits.cosine.quality, {"a", "b", "c"},
                  "(ln L)");
  text += fitLine("luminance biquadratic", "ln L = a α⁴ + b α² + c", fits.biquadratic.quality,
                  {"a", "b", "c"}, "(ln L)");
  text += axisReport("vertical logistic", fits.vertical);
  text += axisReport("horizontal logistic", fits.horizontal);
  return text;
}

double SweepFits::lmaxCdM2(double alpha_deg) const {
  return cosineIsBetter() ? cosine.curve(alpha_deg) : biquadratic.curve(alpha_deg);
}

Result<SweepFits> fitSweep(const SweepTable& all, const FitOptions& options) {
  SweepTable table;
  int suspects = 0;
  for (const SweepRow& row : all.rows) {
    if (row.isSuspect() && !options.include_suspect)
      ++suspects;
    else
      table.rows.push_back(row);
  }
  const int rows = static_cast<int>(table.rows.size());
  if (rows < kLogisticParameters) {
    std::string left_out;  // the suspect rows, by α and stack, and how to fit them anyway
    if (suspects > 0) {
      std::vector<std::string> named;
      for (const SweepRow& row : all.rows) {
        if (row.isSuspect())
          named.push_back(fmt::format("\u03b1 {:g}\u00b0 {}", row.alpha_deg,
                                      row.stack_id.empty() ? row.stack : row.stack_id));
      }
      left_out = fmt::format(" of {} ({} suspect left out: {}; --include-suspect fits them)",
                             all.rows.size(), suspects, fmt::join(named, ", "));
    }
    return badInput(
        fmt::format("{} rows{}: the fits need at least {} (the logistic has {} "
                    "parameters)",
                    rows, left_out, kLogisticParameters, kLogisticParameters));
  }
  // Repeated stacks at one α (a rig that does not move) do not make a function of α.
  std::set<long> distinct_alpha;
  for (const SweepRow& row : table.rows)
    distinct_alpha.insert(std::lround(row.alpha_deg / kDistinctAlphaDeg));
  if (static_cast<int>(distinct_alpha.size()) < kLogisticParameters)
    return badInput(fmt::format(
        "{} rows at only {} α {:g}° apart: the fits need at least {} (a function of α needs α "
        "to vary)",
        rows, distinct_alpha.size(), kDistinctAlphaDeg, kLogisticParameters));
  std::vector<double> alpha, ln_l;
  int bounds = 0;
  for (const SweepRow& row : table.rows) {
    if (!row.lmax_bound.empty()) {  // saturated or dark everywhere: not a value to fit
      ++bounds;
      continue;
    }
    alpha.push_back(row.alpha_deg);
    ln_l.push_back(std::log(row.lmax_cd_m2));
  }
  SweepFits fits;
  if (suspects > 0)
    fits.warnings.push_back(
        fmt::format("{} suspect row(s) (suspect: frames that disagree with the merge) left out of "
                    "the fits",
                    suspects));
  for (const SweepRow& row : all.rows) {
    if (!row.isSuspect()) continue;
    fits.warnings.push_back(fmt::format(
        "suspect{}: \u03b1 {:g}\u00b0 {}: {}", options.include_suspect ? " (fitted as asked)" : "",
        row.alpha_deg, row.stack_id.empty() ? row.stack : row.stack_id, row.suspect));
  }
  if (bounds > 0)
    fits.warnings.push_back(fmt::format(
        "luminance: {} row(s) whose Lmax is only a bound (lmax_bound) left out of the fits",
        bounds));
  if (alpha.empty()) return badInput("every row's Lmax is only a bound: nothing to fit");
  std::tie(fits.alpha_min_deg, fits.alpha_max_deg) = alphaRange(alpha);
  GLARECAM_ASSIGN(fits.cosine, fitCosine(alpha, ln_l));
  GLARECAM_ASSIGN(fits.biquadratic, fitBiquadratic(alpha, ln_l));
  noteQuality(fits.warnings, "luminance cos", fits.cosine.quality);
  noteQuality(fits.warnings, "luminance biquadratic", fits.biquadratic.quality);
  fits.vertical = fitAxis(table, &SweepRow::vertical_deg, "vertical", fits.warnings);
  fits.horizontal = fitAxis(table, &SweepRow::horizontal_deg, "horizontal", fits.warnings);
  return fits;
}

nlohmann::json fitsJson(const SweepFits& fits) {
  return {{"schema", kFitsSchema},
          {"alpha_range_deg", {fits.alpha_min_deg, fits.alpha_max_deg}},
          {"luminance",
           {{"cos", qualityJson(fits.cosine.quality, {"a", "b", "c"})},
            {"biquadratic", qualityJson(fits.biquadratic.quality, {"a", "b", "c"})},
            {"best", fits.cosineIsBetter() ? "cos" : "biquadratic"}}},
          {"vertical", axisJson(fits.vertical)},
          {"horizontal", axisJson(fits.horizontal)},
          {"warnings", fits.warnings}};
}

Result<SweepFits> readAndFitSweep(const std::filesystem::path& path, SweepTable& table,
                                  const FitOptions& options) {
  if (path.empty()) return badInput("SWEEP: expected a sweep table (CSV), got an empty string");
  GLARECAM_ASSIGN(table, readSweepTable(path));
  sortByAlpha(table);
  if (const std::string mixed = mixedReferences(table); !mixed.empty()) {
    if (!options.allow_mixed_references)
      return badInput(fmt::format(
          "{}: the rows' luminances are not referred to one illuminance ({}); fit each part on "
          "its own, reprocess with one --reference-illuminance, or give --mixed",
          path.string(), mixed));
    spdlog::warn("{}: rows of different references fitted together (--mixed): {}", path.string(),
                 mixed);
  }
  auto fits = fitSweep(table, options);
  if (!fits) return std::unexpected(withContext(fits.error(), path.string()));
  for (const std::string& warning : fits->warnings) spdlog::warn("{}: {}", path.string(), warning);
  return fits;
}

}  // namespace glarecam::pipeline
