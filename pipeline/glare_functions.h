// The empirical glare functions of docs/method.md ("Across angles"), as plain value types that
// evaluate at an angle of incidence alpha in degrees (from the module normal):
//   cosine       ln L = a + b / cos(alpha)^c
//   biquadratic  ln L = a alpha^4 + b alpha^2 + c
//   logistic     y = a / (1 + exp(-(alpha - b) d)) + c   (an ellipse axis, degrees)
// The formulas are templates on the parameter type so that the fits (glare_fits.h) differentiate
// the very expressions the curves evaluate.
#pragma once

#include <cmath>

#include "core/angles.h"

namespace glarecam::pipeline {

template <typename T>
T cosineLnL(double alpha_deg, const T& a, const T& b, const T& c) {
  using std::exp;
  return a + b * exp(-c * std::log(std::cos(radians(alpha_deg))));
}

template <typename T>
T biquadraticLnL(double alpha_deg, const T& a, const T& b, const T& c) {
  const double a2 = alpha_deg * alpha_deg;
  return a * (a2 * a2) + b * a2 + c;
}

// Evaluated without overflow for any sign of (alpha - b) d.
template <typename T>
T logistic(double alpha_deg, const T& a, const T& b, const T& c, const T& d) {
  using std::exp;
  const T z = (alpha_deg - b) * d;
  if (z >= T(0)) return a / (1.0 + exp(-z)) + c;
  const T e = exp(z);
  return a * e / (1.0 + e) + c;
}

struct CosineLnCurve {
  double a = 0, b = 0, c = 0;
  double lnLuminance(double alpha_deg) const { return cosineLnL(alpha_deg, a, b, c); }
  double operator()(double alpha_deg) const { return std::exp(lnLuminance(alpha_deg)); }  // cd/m²
};

struct BiquadraticLnCurve {
  double a = 0, b = 0, c = 0;
  double lnLuminance(double alpha_deg) const { return biquadraticLnL(alpha_deg, a, b, c); }
  double operator()(double alpha_deg) const { return std::exp(lnLuminance(alpha_deg)); }  // cd/m²
};

struct LogisticCurve {
  double a = 0, b = 0, c = 0, d = 0;
  double operator()(double alpha_deg) const { return logistic(alpha_deg, a, b, c, d); }
};

}  // namespace glarecam::pipeline
