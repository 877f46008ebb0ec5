#include "core/config_table.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace glarecam {

namespace {

Status checkSections(const std::filesystem::path& file, const toml::table& root,
                     std::span<const std::string_view> sections) {
  for (auto&& [key, node] : root) {
    if (!node.is_table() ||
        std::find(sections.begin(), sections.end(), key.str()) != sections.end())
      continue;
    std::vector<std::string_view> known(sections.begin(), sections.end());
    std::sort(known.begin(), known.end());
    return badInput(fmt::format("{}:{}: unknown section [{}] (known: {})", file.string(),
                                node.source().begin.line, key.str(), fmt::join(known, ", ")));
  }
  return {};
}

}  // namespace

Result<toml::table> readConfigFile(const std::filesystem::path& path,
                                   std::span<const std::string_view> sections) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return badInput(path.string() + ": " +
                    (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file"));
  toml::table root;
  try {
    root = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    return badInput(
        fmt::format("{}:{}: {}", path.string(), e.source().begin.line, e.description()));
  }
  GLARECAM_CHECK(checkSections(path, root, sections));
  return root;
}

const toml::node* TableReader::node(const char* key) {
  used_.insert(key);
  return table_.get(key);
}

Result<std::optional<double>> TableReader::number(const char* key, double min, double max) {
  const toml::node* value_node = node(key);
  if (!value_node) return std::nullopt;
  const std::optional<double> value = value_node->value<double>();
  if (!value_node->is_number() || !value || !std::isfinite(*value))
    return error(*value_node, fmt::format("{} must be a number", qualified(key)));
  if (*value < min || *value > max)
    return error(*value_node, fmt::format("{} = {:g} is outside [{:g}, {:g}]", qualified(key),
                                          *value, min, max));
  return value;
}

Result<double> TableReader::requiredNumber(const char* key, double min, double max) {
  std::optional<double> value;
  GLARECAM_ASSIGN(value, number(key, min, max));
  if (!value) return missing(key);
  return *value;
}

Result<std::optional<std::int64_t>> TableReader::integer(const char* key, std::int64_t min,
                                                         std::int64_t max) {
  const toml::node* value_node = node(key);
  if (!value_node) return std::nullopt;
  if (!value_node->is_integer())
    return error(*value_node, fmt::format("{} must be a whole number", qualified(key)));
  const std::int64_t value = *value_node->value<std::int64_t>();
  if (value < min || value > max)
    return error(*value_node,
                 fmt::format("{} = {} is outside [{}, {}]", qualified(key), value, min, max));
  return value;
}

Result<std::optional<bool>> TableReader::boolean(const char* key) {
  const toml::node* value_node = node(key);
  if (!value_node) return std::nullopt;
  if (!value_node->is_boolean())
    return error(*value_node, fmt::format("{} must be true or false", qualified(key)));
  return value_node->value<bool>();
}

Result<std::optional<std::string>> TableReader::string(const char* key) {
  const toml::node* value_node = node(key);
  if (!value_node) return std::nullopt;
  const std::optional<std::string> value = value_node->value<std::string>();
  if (!value_node->is_string() || !value || value->empty())
    return error(*value_node, fmt::format("{} must be a non-empty string", qualified(key)));
  return value;
}

Result<std::string> TableReader::requiredString(const char* key) {
  std::optional<std::string> value;
  GLARECAM_ASSIGN(value, string(key));
  if (!value) return missing(key);
  return *value;
}

Result<std::optional<std::string>> TableReader::choice(
    const char* key, std::initializer_list<std::string_view> choices) {
  std::optional<std::string> value;
  GLARECAM_ASSIGN(value, string(key));
  if (!value) return std::nullopt;
  std::string known;
  for (std::string_view c : choices) {
    if (*value == c) return value;
    known += fmt::format("{}\"{}\"", known.empty() ? "" : ", ", c);
  }
  return error(*table_.get(key),
               fmt::format("{} = \"{}\" is not one of {}", qualified(key), *value, known));
}

Result<std::optional<std::vector<double>>> TableReader::numberList(const char* key, double min,
                                                                   double max,
                                                                   std::size_t min_count,
                                                                   std::size_t max_count) {
  const toml::node* value_node = node(key);
  if (!value_node) return std::nullopt;
  const toml::array* array = value_node->as_array();
  if (!array)
    return error(*value_node, fmt::format("{} must be an array of numbers", qualified(key)));
  if (array->size() < min_count || array->size() > max_count)
    return error(*value_node, fmt::format("{} must have {} to {} elements, not {}", qualified(key),
                                          min_count, max_count, array->size()));
  std::vector<double> values;
  for (const toml::node& element : *array) {
    const std::optional<double> value = element.value<double>();
    if (!element.is_number() || !value || !std::isfinite(*value))
      return error(element, fmt::format("{} must hold numbers only", qualified(key)));
    if (*value < min || *value > max)
      return error(element, fmt::format("{} holds {:g}, outside [{:g}, {:g}]", qualified(key),
                                        *value, min, max));
    values.push_back(*value);
  }
  return values;
}

std::unexpected<Error> TableReader::tableError(const std::string& message) const {
  return badInput(fmt::format("{}:{}: [{}] {}", file_.string(), line(table_), name_, message));
}

std::unexpected<Error> TableReader::error(const toml::node& node,
                                          const std::string& message) const {
  return badInput(fmt::format("{}:{}: {}", file_.string(), line(node), message));
}

Status TableReader::checkNoUnknownKeys() const {
  for (auto&& [key, node] : table_) {
    if (used_.count(std::string(key.str())) || node.is_table()) continue;
    std::string known;
    for (const std::string& k : used_) known += (known.empty() ? "" : ", ") + k;
    return error(node, fmt::format("unknown key {} (known: {})", qualified(key.str()), known));
  }
  return {};
}

std::string TableReader::qualified(std::string_view key) const {
  return name_.empty() ? std::string(key) : name_ + "." + std::string(key);
}

std::unexpected<Error> TableReader::missing(const char* key) const {
  return tableError(fmt::format("needs {}", key));
}

}  // namespace glarecam
