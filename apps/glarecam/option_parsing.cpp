#include "apps/glarecam/option_parsing.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace glarecam::apps {
namespace {

template <typename T>
bool parseWhole(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

}  // namespace

Result<std::uint64_t> parseUnsigned(const std::string& text, const std::string& option) {
  std::uint64_t value = 0;
  if (!parseWhole(text, value))
    return badInput(option + ": expected a whole number >= 0, got \"" + text + "\"");
  return value;
}

Status requireNonEmptyPath(const std::optional<std::string>& value, const std::string& option) {
  if (value && value->empty()) return badInput(option + ": expected a path, got an empty string");
  return {};
}

Result<std::pair<int, int>> parseSize(const std::string& text, const std::string& option) {
  const auto x = text.find('x');
  int width = 0, height = 0;
  if (x == std::string::npos || !parseWhole(text.substr(0, x), width) ||
      !parseWhole(text.substr(x + 1), height)) {
    return badInput(option + ": expected WIDTHxHEIGHT, got \"" + text + "\"");
  }
  return std::pair{width, height};
}

Result<std::vector<double>> parseNumberList(const std::string& text, const std::string& option,
                                            std::size_t min_count, std::size_t max_count) {
  std::vector<double> values;
  const std::string expected =
      max_count == 1 ? "one number" : "comma-separated numbers (no thousands separators)";
  if (text.empty() || text.back() == ',') {
    return badInput(option + ": expected " + expected + ", got \"" + text + "\"");
  }
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    double value = 0;
    if (!parseWhole(item, value) || !std::isfinite(value)) {
      return badInput(option + ": \"" + item + "\" is not a finite number");
    }
    values.push_back(value);
  }
  if (values.size() < min_count || values.size() > max_count) {
    if (max_count == 1) return badInput(option + ": expected one number, got \"" + text + "\"");
    return badInput(option + ": expected " + std::to_string(min_count) +
                    (max_count != min_count ? " to " + std::to_string(max_count) : "") +
                    " comma-separated numbers, got " + std::to_string(values.size()));
  }
  return values;
}

Result<std::optional<double>> parseOptionalNumber(const std::optional<std::string>& text,
                                                  const std::string& option) {
  if (!text) return std::nullopt;
  auto values = parseNumberList(*text, option, 1, 1);
  if (!values) return std::unexpected(values.error());
  return values->front();
}

Result<std::optional<SourceIlluminance>> parseOptionalSourceIlluminance(
    const std::optional<std::string>& text, const std::string& option) {
  if (!text) return std::nullopt;
  return parseGivenIlluminance(*text, option);
}

Result<double> parseReferenceIlluminance(const std::optional<std::string>& text,
                                         const std::string& option) {
  std::optional<double> value;
  GLARECAM_ASSIGN(value, parseOptionalNumber(text, option));
  if (!value) return kDefaultReferenceIlluminanceLx;
  GLARECAM_CHECK(checkReferenceIlluminance(*value, option));
  return *value;
}

Result<std::optional<double>> parseOptionalLuminance(const std::optional<std::string>& text,
                                                     const std::string& option) {
  auto value = parseOptionalNumber(text, option);
  if (value && *value && !(**value > 0))
    return badInput(option + ": expected a positive luminance in cd/m²");
  return value;
}

}  // namespace glarecam::apps
