#include "render/number_format.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

namespace glarecam::render {
namespace {

constexpr double kThousand = 1000;

std::string superscriptDigits(int value) {
  static constexpr std::array<const char*, 10> kDigits = {"\u2070", "\u00b9", "\u00b2", "\u00b3",
                                                          "\u2074", "\u2075", "\u2076", "\u2077",
                                                          "\u2078", "\u2079"};
  std::string text = value < 0 ? "\u207b" : "";
  for (const char digit : std::to_string(std::abs(value))) text += kDigits[digit - '0'];
  return text;
}

}  // namespace

std::string formatPlain(double value) { return fmt::format("{:g}", value); }

std::string formatToUncertainty(double value, const std::optional<double>& uncertainty,
                                int default_decimals) {
  constexpr int kMaxDecimals = 6;  // below a micro-unit no instrument of ours resolves
  int decimals = default_decimals;
  if (uncertainty && *uncertainty > 0 && std::isfinite(*uncertainty)) {
    const int exponent = static_cast<int>(std::floor(std::log10(*uncertainty)));
    const double leading = *uncertainty / std::pow(10.0, exponent);
    decimals = std::clamp(-exponent + (leading < 2.0 ? 1 : 0), 0, kMaxDecimals);
  }
  return fmt::format("{:.{}f}", value, decimals);
}

std::string formatSignificant(double value, int digits) {
  return fmt::format("{:.{}g}", value, digits);
}

std::string formatFixed(const std::optional<double>& value, int decimals) {
  return value ? fmt::format("{:.{}f}", *value, decimals) : kNoValue;
}

std::string formatGrouped(double value, int digits) {
  if (!std::isfinite(value)) return kNoValue;
  if (std::abs(value) < kThousand) return formatSignificant(value, digits);
  const double scale = std::pow(10.0, std::floor(std::log10(std::abs(value))) + 1 - digits);
  const std::string whole = fmt::format("{:.0f}", std::round(std::abs(value) / scale) * scale);
  std::string grouped = value < 0 ? "-" : "";
  for (std::size_t i = 0; i < whole.size(); ++i) {
    if (i > 0 && (whole.size() - i) % 3 == 0) grouped += "\u2009";
    grouped += whole[i];
  }
  return grouped;
}

std::string formatPowerOfTen(int exponent) { return "10" + superscriptDigits(exponent); }

std::string formatSiPrefixed(double value) {
  static constexpr std::array<const char*, 5> kPrefixes{"", "k", "M", "G", "T"};
  std::size_t prefix = 0;
  while (value >= kThousand && prefix + 1 < kPrefixes.size()) {
    value /= kThousand;
    ++prefix;
  }
  return value < 1.0 ? fmt::format("{:.2g}{}", value, kPrefixes[prefix])
                     : fmt::format("{:.0f}{}", value, kPrefixes[prefix]);
}

}  // namespace glarecam::render
