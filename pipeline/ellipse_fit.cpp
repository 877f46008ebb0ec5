#include "pipeline/ellipse_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>

namespace glarecam::pipeline {
namespace {

constexpr std::size_t kMinPoints = 5;  // an ellipse has five parameters
constexpr int kMaxIterations = 100;
constexpr double kInitialDamping = 1e-3, kMinDamping = 1e-15, kMaxDamping = 1e12;
// The geometric fit has converged when a step moves the parameters by less than this fraction
// of the axes (far below any contour's noise or interpolation error) or lowers the cost by less
// than this fraction of it.
constexpr double kConvergedStep = 1e-10;
constexpr double kConvergedCost = 1e-12;
// Eigenvalues of the normal matrix below this fraction of the largest are treated as zero:
// the orientation of a circle is undetermined and must not feed the axes' sensitivities.
constexpr double kRelativeRankTolerance = 1e-10;

using Vector5 = Eigen::Matrix<double, 5, 1>;
using Matrix5 = Eigen::Matrix<double, 5, 5>;
enum Parameter { kCx, kCy, kA, kB, kAngle };

double wrapHalfTurn(double angle_rad) {
  constexpr double kPi = std::numbers::pi;
  angle_rad = std::remainder(angle_rad, kPi);  // (-pi/2, pi/2]
  return angle_rad <= -kPi / 2 ? angle_rad + kPi : angle_rad;
}

// Conic A x² + B xy + C y² + D x + E y + F = 0 to centre, semi-axes and angle.
std::optional<Ellipse> conicToEllipse(Eigen::Matrix<double, 6, 1> conic) {
  if (conic[0] + conic[2] < 0) conic = -conic;  // an eigenvector's sign is arbitrary
  const double a = conic[0], b = conic[1], c = conic[2], d = conic[3], e = conic[4], f = conic[5];
  Eigen::Matrix2d quadratic;
  quadratic << a, b / 2, b / 2, c;
  if (!(quadratic.determinant() > 0)) return std::nullopt;
  const Eigen::Vector2d centre = quadratic.ldlt().solve(Eigen::Vector2d(-d / 2, -e / 2));
  const double at_centre = f + (d * centre.x() + e * centre.y()) / 2;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(quadratic);
  const Eigen::Vector2d lambda = eigen.eigenvalues();  // ascending: major axis first
  const double major2 = -at_centre / lambda[0], minor2 = -at_centre / lambda[1];
  if (!(major2 > 0 && minor2 > 0)) return std::nullopt;
  const Eigen::Vector2d major_direction = eigen.eigenvectors().col(0);
  return Ellipse{{centre.x(), centre.y()},
                 std::sqrt(major2),
                 std::sqrt(minor2),
                 wrapHalfTurn(std::atan2(major_direction.y(), major_direction.x()))};
}

// One point's signed orthogonal distance to the ellipse, its gradient with respect to the
// parameters (envelope theorem: the foot point's parameter t is stationary) and the outward
// unit normal at the foot point, which is also the distance's gradient with respect to the point.
struct PointResidual {
  double distance = 0;
  Vector5 gradient;
  Eigen::Vector2d normal;
};

PointResidual pointResidual(const Vector5& p, const Point2& point) {
  const double cos_phi = std::cos(p[kAngle]), sin_phi = std::sin(p[kAngle]);
  const double dx = point.x - p[kCx], dy = point.y - p[kCy];
  const double u = cos_phi * dx + sin_phi * dy, v = -sin_phi * dx + cos_phi * dy;
  const double a = p[kA], b = p[kB];
  // Foot point: Newton on the stationarity condition of the squared distance in t.
  double t = std::atan2(a * v, b * u);
  for (int i = 0; i < 20; ++i) {
    const double st = std::sin(t), ct = std::cos(t);
    const double g = u * a * st - v * b * ct - (a * a - b * b) * st * ct;
    const double dg = u * a * ct + v * b * st - (a * a - b * b) * (ct * ct - st * st);
    if (!(dg > 0)) break;
    const double step = g / dg;
    t -= step;
    if (std::abs(step) < 1e-14) break;
  }
  const double st = std::sin(t), ct = std::cos(t);
  Eigen::Vector2d n(ct / a, st / b);
  n.normalize();
  PointResidual r;
  r.distance = n.x() * (u - a * ct) + n.y() * (v - b * st);
  r.normal = {cos_phi * n.x() - sin_phi * n.y(), sin_phi * n.x() + cos_phi * n.y()};
  r.gradient << -r.normal.x(), -r.normal.y(), -n.x() * ct, -n.y() * st,
      -(n.x() * -b * st + n.y() * a * ct);
  return r;
}

// The cost and the Gauss-Newton normal equations at p, in one pass over the points.
struct NormalEquations {
  double cost = 0;
  Matrix5 normal = Matrix5::Zero();
  Vector5 gradient = Vector5::Zero();
};

NormalEquations normalEquations(const Vector5& p, std::span<const Point2> points) {
  NormalEquations e;
  for (const Point2& point : points) {
    const PointResidual r = pointResidual(p, point);
    e.cost += r.distance * r.distance;
    e.normal.selfadjointView<Eigen::Upper>().rankUpdate(r.gradient);
    e.gradient += r.gradient * r.distance;
  }
  e.normal = e.normal.selfadjointView<Eigen::Upper>();
  return e;
}

// Levenberg–Marquardt on the orthogonal distances.
Vector5 refineGeometric(Vector5 p, std::span<const Point2> points) {
  NormalEquations at_p = normalEquations(p, points);
  double damping = kInitialDamping;
  for (int iteration = 0; iteration < kMaxIterations && damping < kMaxDamping; ++iteration) {
    Matrix5 damped = at_p.normal;
    damped.diagonal() += damping * (at_p.normal.diagonal().array() + 1e-12).matrix();
    const Vector5 step = damped.ldlt().solve(-at_p.gradient);
    const Vector5 candidate = p + step;
    if (!(candidate[kA] > 0 && candidate[kB] > 0)) {
      damping *= 10;
      continue;
    }
    NormalEquations at_candidate = normalEquations(candidate, points);
    if (!(at_candidate.cost <= at_p.cost)) {
      damping *= 10;
      continue;
    }
    const bool converged = step.norm() <= kConvergedStep * (candidate[kA] + candidate[kB]) ||
                           at_p.cost - at_candidate.cost <= kConvergedCost * at_p.cost;
    p = candidate;
    at_p = std::move(at_candidate);
    damping = std::max(damping / 10, kMinDamping);
    if (converged) break;
  }
  return p;
}

Vector5 toParameters(const Ellipse& e) {
  Vector5 p;
  p << e.centre.x, e.centre.y, e.semi_major, e.semi_minor, e.angle_rad;
  return p;
}

Ellipse toEllipse(Vector5 p) {
  if (p[kB] > p[kA]) {
    std::swap(p[kA], p[kB]);
    p[kAngle] += std::numbers::pi / 2;
  }
  return {{p[kCx], p[kCy]}, p[kA], p[kB], wrapHalfTurn(p[kAngle])};
}

// Pseudo-inverse of the (symmetric, positive semi-definite) normal matrix. The eigen
// decompositions here are OpenCV's: Eigen's fixed-size solvers cost a minute of compile time
// per build for two small matrices.
Matrix5 pseudoInverse(const Matrix5& normal) {
  cv::Matx<double, 5, 5> matrix;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) matrix(r, c) = normal(r, c);
  cv::Matx<double, 5, 1> values;
  cv::Matx<double, 5, 5> vectors;  // eigenvectors as rows, eigenvalues descending
  cv::eigen(matrix, values, vectors);
  const double largest = values(0);
  Matrix5 inverse = Matrix5::Zero();
  for (int i = 0; i < 5; ++i) {
    if (!(values(i) > kRelativeRankTolerance * largest)) continue;
    Vector5 v;
    for (int k = 0; k < 5; ++k) v[k] = vectors(i, k);
    inverse += (v * v.transpose()) / values(i);
  }
  return inverse;
}

}  // namespace

Point2 Ellipse::pointAt(double t) const {
  const double u = semi_major * std::cos(t), v = semi_minor * std::sin(t);
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return {centre.x + c * u - s * v, centre.y + s * u + c * v};
}

std::optional<Ellipse> fitEllipseDirect(std::span<const Point2> points) {
  if (points.size() < kMinPoints) return std::nullopt;
  // Centre and scale the data so that the scatter matrices are well conditioned.
  double mx = 0, my = 0;
  for (const Point2& p : points) mx += p.x, my += p.y;
  mx /= static_cast<double>(points.size());
  my /= static_cast<double>(points.size());
  double spread = 0;
  for (const Point2& p : points) spread += (p.x - mx) * (p.x - mx) + (p.y - my) * (p.y - my);
  const double scale = std::sqrt(spread / static_cast<double>(points.size()));
  if (!(scale > 0)) return std::nullopt;
  Eigen::MatrixXd quadratic(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixXd linear(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double x = (points[i].x - mx) / scale, y = (points[i].y - my) / scale;
    const auto row = static_cast<Eigen::Index>(i);
    quadratic.row(row) << x * x, x * y, y * y;
    linear.row(row) << x, y, 1.0;
  }
  const Eigen::Matrix3d s1 = quadratic.transpose() * quadratic;
  const Eigen::Matrix3d s2 = quadratic.transpose() * linear;
  const Eigen::Matrix3d s3 = linear.transpose() * linear;
  const Eigen::FullPivLU<Eigen::Matrix3d> s3_lu(s3);
  if (!s3_lu.isInvertible()) return std::nullopt;
  const Eigen::Matrix3d t = -s3_lu.solve(s2.transpose());
  const Eigen::Matrix3d m = s1 + s2 * t;
  Eigen::Matrix3d reduced;  // C1^-1 M for the ellipse constraint 4ac - b² = 1
  reduced.row(0) = m.row(2) / 2;
  reduced.row(1) = -m.row(1);
  reduced.row(2) = m.row(0) / 2;
  cv::Matx33d reduced_cv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) reduced_cv(r, c) = reduced(r, c);
  cv::Mat values, vectors;  // eigenvectors as rows
  cv::eigenNonSymmetric(reduced_cv, values, vectors);
  for (int i = 0; i < vectors.rows; ++i) {
    const Eigen::Vector3d a1(vectors.at<double>(i, 0), vectors.at<double>(i, 1),
                             vectors.at<double>(i, 2));
    if (!(4 * a1[0] * a1[2] - a1[1] * a1[1] > 0)) continue;
    Eigen::Matrix<double, 6, 1> conic;
    conic << a1, t * a1;
    auto ellipse = conicToEllipse(conic);
    if (!ellipse) continue;
    ellipse->centre = {ellipse->centre.x * scale + mx, ellipse->centre.y * scale + my};
    ellipse->semi_major *= scale;
    ellipse->semi_minor *= scale;
    return ellipse;
  }
  return std::nullopt;
}

std::optional<EllipseFit> fitEllipse(std::span<const Point2> points,
                                     const std::optional<Ellipse>& initial) {
  const auto start = initial ? initial : fitEllipseDirect(points);
  if (!start || points.size() < kMinPoints) return std::nullopt;
  EllipseFit fit;
  fit.ellipse = toEllipse(refineGeometric(toParameters(*start), points));
  const Vector5 p = toParameters(fit.ellipse);
  Matrix5 normal = Matrix5::Zero();
  std::vector<PointResidual> residuals;
  residuals.reserve(points.size());
  double sum_squares = 0;
  for (const Point2& point : points) {
    residuals.push_back(pointResidual(p, point));
    normal += residuals.back().gradient * residuals.back().gradient.transpose();
    fit.residuals.push_back(residuals.back().distance);
    fit.normals.push_back({residuals.back().normal.x(), residuals.back().normal.y()});
    sum_squares += residuals.back().distance * residuals.back().distance;
  }
  fit.rms_residual = std::sqrt(sum_squares / static_cast<double>(points.size()));
  // d theta / d point_i = -(J^T J)^+ J_i^T n_i^T; keep the rows of the semi-axes and the angle
  // (p is the normalised ellipse's: a the semi-major axis, the angle the major axis's).
  const Matrix5 inverse = pseudoInverse(normal);
  for (const PointResidual& r : residuals) {
    const double da = -inverse.row(kA).dot(r.gradient), db = -inverse.row(kB).dot(r.gradient);
    const double dangle = -inverse.row(kAngle).dot(r.gradient);
    fit.axis_sensitivity.push_back(
        {da * r.normal.x(), da * r.normal.y(), db * r.normal.x(), db * r.normal.y()});
    fit.angle_sensitivity.push_back({dangle * r.normal.x(), dangle * r.normal.y()});
  }
  return fit;
}

}  // namespace glarecam::pipeline
