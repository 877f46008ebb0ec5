// Numbers as people read them on the pictures and the data sheet: tick labels, table cells and
// values quoted in text. Text is UTF-8: the thin space (U+2009) groups thousands, superscript
// digits write powers of ten, the en dash (U+2013) stands for a missing value.
#pragma once

#include <optional>
#include <string>

namespace glarecam::render {

inline constexpr const char* kNoValue = "\u2013";

// printf's %g: at most six significant digits, no trailing zeros ("10", "0.5", "1e+07").
std::string formatPlain(double value);

// `digits` significant digits, %g style ("1.235", "2.5e-05").
std::string formatSignificant(double value, int digits);

// A measured value to the decimal its standard uncertainty reaches: one significant digit of the
// uncertainty, two when that digit is 1 (u 0.05 -> "4.99", u 0.12 -> "5.00", u 2 -> "5"; GUM
// 7.2.6). Without a usable uncertainty, `default_decimals`.
std::string formatToUncertainty(double value, const std::optional<double>& uncertainty,
                                int default_decimals);

// Fixed-point with `decimals` decimals; kNoValue for none.
std::string formatFixed(const std::optional<double>& value, int decimals);

// Rounded to `digits` significant digits; from 1000 on written out in full, thousands grouped
// by thin spaces ("47 500 000", not "4.75e+07"); below that as formatSignificant. kNoValue for
// NaN and the infinities.
std::string formatGrouped(double value, int digits);

// "10⁵", "10⁻³": a log axis's decade label.
std::string formatPowerOfTen(int exponent);

// With an SI prefix of a thousand's power (k, M, G, T): "500", "20k", "1M"; whole numbers from
// 1 on, two significant digits below ("0.05").
std::string formatSiPrefixed(double value);

}  // namespace glarecam::render
