// The empirical fits of docs/method.md over a sweep table: the cosine and biquadratic functions
// of ln Lmax, and a logistic function of each limit-ellipse axis (rows without an ellipse left
// out). The nonlinear fits (cosine, logistic) are separable: for fixed shape parameters the model
// is linear in the rest, so a grid of shapes is solved by linear least squares and the best
// starts are refined with Ceres (Levenberg–Marquardt on all parameters). Each fit reports its
// parameters, standard errors from the Jacobian at the optimum, R² (on ln L for luminance, on
// degrees for axes), RMSE and the number of points, and says when it is under-determined or
// ill-conditioned.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "pipeline/glare_functions.h"
#include "pipeline/sweep_table.h"

namespace glarecam::pipeline {

struct FitQuality {
  std::vector<double> parameters;
  std::vector<std::optional<double>> standard_errors;  // empty where not determined
  double r2 = 0;
  double rmse = 0;  // on the fitted quantity (ln L or degrees)
  int points = 0;
  double condition_number = 0;    // of the Jacobian at the optimum (scaled columns)
  double max_correlation = 0;     // largest |correlation| between two parameters\' estimates
  bool under_determined = false;  // no residual degrees of freedom
  bool ill_conditioned = false;   // parameters not individually determined
  std::vector<double> start_r2;   // R² reached from every start refined (multi-start)
};

struct CosineFit {
  CosineLnCurve curve;
  FitQuality quality;
};
struct BiquadraticFit {
  BiquadraticLnCurve curve;
  FitQuality quality;
};
struct LogisticFit {
  LogisticCurve curve;
  FitQuality quality;
};

// The fits on raw samples. alpha in degrees; y = ln L or an axis in degrees. Each needs at
// least as many points as parameters (kBadInput otherwise).
Result<CosineFit> fitCosine(std::span<const double> alpha_deg, std::span<const double> ln_l);
Result<BiquadraticFit> fitBiquadratic(std::span<const double> alpha_deg,
                                      std::span<const double> ln_l);
Result<LogisticFit> fitLogistic(std::span<const double> alpha_deg, std::span<const double> y_deg);
// One Levenberg–Marquardt refinement of the logistic from a given start (what multi-start runs
// from each start; public so that tests can try their own).
LogisticFit refineLogistic(std::span<const double> alpha_deg, std::span<const double> y_deg,
                           const LogisticCurve& start);

inline constexpr int kCosineParameters = 3;
inline constexpr int kBiquadraticParameters = 3;
inline constexpr int kLogisticParameters = 4;
// α values closer than this count as one for the fits (the paper sweeps in 5° steps).
inline constexpr double kDistinctAlphaDeg = 1.0;

struct AxisFit {
  std::optional<LogisticFit> logistic;  // none: fewer rows with an ellipse than parameters
  int rows_with_ellipse = 0;
  double alpha_min_deg = 0, alpha_max_deg = 0;  // the α range of those rows
};

struct SweepFits {
  CosineFit cosine;
  BiquadraticFit biquadratic;
  AxisFit vertical, horizontal;
  double alpha_min_deg = 0, alpha_max_deg = 0;  // the measured range
  std::vector<std::string> warnings;            // under-determined, ill-conditioned, skipped
  // The luminance fit with the higher R² (the data sheet's profile uses it).
  bool cosineIsBetter() const { return cosine.quality.r2 > biquadratic.quality.r2; }
  double lmaxCdM2(double alpha_deg) const;
};

struct FitOptions {
  // Fit the suspect rows too (SweepRow::suspect: frames that disagree with the merge). By default
  // they are left out, with a warning naming how many, as rows whose Lmax is only a bound are.
  bool include_suspect = false;
  // Fit rows referred to different reference illuminances, or referred and unreferred rows,
  // together (--mixed; mixedReferences()). By default readAndFitSweep refuses them, naming the
  // rows: their luminances are not on one scale.
  bool allow_mixed_references = false;
};

// All four fits of a sweep table. kBadInput when the table has fewer rows (after leaving out the
// suspect ones) than the logistic needs parameters; an axis with too few ellipses is left
// unfitted with a warning.
Result<SweepFits> fitSweep(const SweepTable& table, const FitOptions& options = {});

// The sweep table at `path` into `table` (sorted by α) and its fits, the fits' warnings logged;
// errors name the file. `glarecam fit` and `glarecam datasheet` read a sweep this way.
Result<SweepFits> readAndFitSweep(const std::filesystem::path& path, SweepTable& table,
                                  const FitOptions& options = {});

inline constexpr std::string_view kFitsSchema = "glarecam.fits/1";

// The fits as `glarecam fit --json` and fits.json give them (kFitsSchema, docs/sweep.md):
// {"luminance": {"cos": {a,b,c,r2,...}, "biquadratic": {...}}, "vertical": {"logistic": {...}},
//  "horizontal": {...}, "warnings": [...]}.
nlohmann::json fitsJson(const SweepFits& fits);

// The fits as a short human-readable report (parameters ± standard errors, R², RMSE, points).
std::string fitsReport(const SweepFits& fits);

}  // namespace glarecam::pipeline
