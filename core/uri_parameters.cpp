#include "core/uri_parameters.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace glarecam {

Result<double> parseUriNumber(std::string_view text, std::string_view key, std::string_view what) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    return badInput(fmt::format("{} {}='{}' is not a number", what, key, text));
  }
  return value;
}

Status forEachUriParameter(std::string_view list, std::string_view what,
                           const std::function<Status(std::string_view, std::string_view)>& apply) {
  while (!list.empty()) {
    const auto comma = list.find(',');
    const std::string_view item = list.substr(0, comma);
    list = comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 1);
    const auto equals = item.find('=');
    if (equals == std::string_view::npos) {
      return badInput(fmt::format("{} '{}' is not KEY=VALUE", what, item));
    }
    GLARECAM_CHECK(apply(item.substr(0, equals), item.substr(equals + 1)));
  }
  return {};
}

}  // namespace glarecam
