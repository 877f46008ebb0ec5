#include "core/json.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "core/spelling.h"
#include "core/text_file.h"

namespace glarecam {

using nlohmann::json;

Result<json> parseJsonText(std::string_view text, const std::string& where) {
  const json::parser_callback_t depth_guard = [](int depth, json::parse_event_t, json&) {
    if (depth >= kMaxJsonDepth)
      throw std::length_error("nesting deeper than " + std::to_string(kMaxJsonDepth));
    return true;
  };
  try {
    return json::parse(text, depth_guard);
  } catch (const json::exception& e) {
    std::string message = e.what();
    // "[json.exception.parse_error.101] parse error at line 3, ..." -> keep the readable part.
    if (auto pos = message.find("] "); pos != std::string::npos) message = message.substr(pos + 2);
    // The parser quotes the offending bytes: keep the line printable when they are binary.
    for (char& c : message) {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f) c = '?';
    }
    return badInput(where + ": invalid JSON: " + message);
  } catch (const std::length_error& e) {
    return badInput(where + ": invalid JSON: " + e.what());
  }
}

Result<json> readJsonFile(const std::filesystem::path& path) {
  std::string text;
  GLARECAM_ASSIGN(text, readTextFile(path));
  return parseJsonText(text, path.string());
}

std::string jsonText(const json& document) {
  constexpr int kIndent = 2;
  return document.dump(kIndent, ' ', false, json::error_handler_t::replace) + "\n";
}

Status writeJsonFile(const std::filesystem::path& path, const json& document) {
  return writeFileAtomic(path, jsonText(document));
}

json finiteOrNull(std::optional<double> value) {
  return value && std::isfinite(*value) ? json(*value) : json(nullptr);
}

std::string jsonSnippet(const json& value) {
  constexpr std::size_t kMaxChars = 40;
  std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  return text.size() > kMaxChars ? text.substr(0, kMaxChars - 3) + "..." : text;
}

namespace {

// A number in a message: %g, as the reader's ranges are written in the docs.
std::string shortNumber(double value) { return fmt::format("{:g}", value); }

}  // namespace

JsonReader::JsonReader() {
  static const json kNull;
  value_ = &kNull;
}

JsonReader::JsonReader(const json& value, std::string file)
    : value_(&value), file_(std::move(file)) {}

JsonReader::JsonReader(const json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

std::string JsonReader::name() const { return path_.empty() ? "the document" : path_; }

std::string JsonReader::childPath(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::unexpected<Error> JsonReader::fail(std::string_view problem) const {
  return badInput(file_ + ": " + name() + " " + std::string(problem));
}

std::unexpected<Error> JsonReader::fail(std::string_view key, std::string_view problem) const {
  return badInput(file_ + ": " + childPath(key) + " " + std::string(problem));
}

bool JsonReader::has(std::string_view key) const {
  if (!value_->is_object()) return false;
  const auto it = value_->find(key);
  return it != value_->end() && !it->is_null();
}

Result<JsonReader> JsonReader::member(std::string_view key) const {
  std::optional<JsonReader> child;
  GLARECAM_ASSIGN(child, optionalMember(key));
  if (!child) return fail(key, "is missing");
  return *child;
}

Result<std::optional<JsonReader>> JsonReader::optionalMember(std::string_view key) const {
  GLARECAM_CHECK(object());
  const auto it = value_->find(key);
  if (it == value_->end() || it->is_null()) return std::optional<JsonReader>{};
  return std::optional<JsonReader>(JsonReader(*it, file_, childPath(key)));
}

Status JsonReader::onlyKeys(std::initializer_list<std::string_view> known) const {
  GLARECAM_CHECK(object());
  for (const auto& [key, value] : value_->items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const std::vector<std::string> candidates(known.begin(), known.end());
    const std::optional<std::string> suggestion = closestSpelling(key, candidates);
    const std::string hint = suggestion
                                 ? " (did you mean " + jsonSnippet(*suggestion) + "?)"
                                 : " (known: " + fmt::format("{}", fmt::join(known, ", ")) + ")";
    return fail("has an unknown key " + jsonSnippet(key) + hint);
  }
  return {};
}

Result<JsonReader> JsonReader::objectMember(std::string_view key) const {
  JsonReader child = *this;
  GLARECAM_ASSIGN(child, member(key));
  GLARECAM_CHECK(child.object());
  return child;
}

Result<JsonReader> JsonReader::arrayMember(std::string_view key) const {
  JsonReader child = *this;
  GLARECAM_ASSIGN(child, member(key));
  GLARECAM_CHECK(child.array());
  return child;
}

Result<std::optional<JsonReader>> JsonReader::optionalObject(std::string_view key) const {
  std::optional<JsonReader> child;
  GLARECAM_ASSIGN(child, optionalMember(key));
  if (child) GLARECAM_CHECK(child->object());
  return child;
}

Result<std::optional<JsonReader>> JsonReader::optionalArray(std::string_view key) const {
  std::optional<JsonReader> child;
  GLARECAM_ASSIGN(child, optionalMember(key));
  if (child) GLARECAM_CHECK(child->array());
  return child;
}

JsonReader JsonReader::element(std::size_t index) const {
  return JsonReader((*value_)[index], file_, path_ + "[" + std::to_string(index) + "]");
}

Status JsonReader::object() const {
  if (!value_->is_object()) return fail("must be an object, not " + jsonSnippet(*value_));
  return {};
}

Status JsonReader::array() const {
  if (!value_->is_array()) return fail("must be an array, not " + jsonSnippet(*value_));
  return {};
}

Result<double> JsonReader::number() const {
  if (!value_->is_number()) return fail("must be a number, not " + jsonSnippet(*value_));
  const double x = value_->get<double>();
  if (!std::isfinite(x)) return fail("must be finite");
  return x;
}

Result<double> JsonReader::positive() const {
  double x = 0;
  GLARECAM_ASSIGN(x, number());
  if (!(x > 0)) return fail("must be positive, not " + jsonSnippet(*value_));
  return x;
}

Result<double> JsonReader::nonNegative() const {
  double x = 0;
  GLARECAM_ASSIGN(x, number());
  if (x < 0) return fail("must not be negative, not " + jsonSnippet(*value_));
  return x;
}

Result<double> JsonReader::numberIn(double low, double high, std::string_view unit) const {
  double x = 0;
  GLARECAM_ASSIGN(x, number());
  if (x < low || x > high) {
    return fail(shortNumber(x) + std::string(unit) + " is outside [" + shortNumber(low) + ", " +
                shortNumber(high) + "]");
  }
  return x;
}

Result<long long> JsonReader::integer(long long low, long long high) const {
  double x = 0;
  GLARECAM_ASSIGN(x, number());
  if (x != std::floor(x) || x < static_cast<double>(low) || x > static_cast<double>(high)) {
    return fail(
        fmt::format("must be a whole number in [{}, {}], not {}", low, high, jsonSnippet(*value_)));
  }
  return static_cast<long long>(x);
}

Result<std::string> JsonReader::text() const {
  if (!value_->is_string()) return fail("must be a string, not " + jsonSnippet(*value_));
  return value_->get<std::string>();
}

Result<bool> JsonReader::boolean() const {
  if (!value_->is_boolean()) return fail("must be true or false, not " + jsonSnippet(*value_));
  return value_->get<bool>();
}

namespace {

// A required member read as a type by `read` (a JsonReader member function).
template <typename T, typename Read>
Result<T> required(const JsonReader& reader, std::string_view key, Read read) {
  JsonReader child = reader;
  GLARECAM_ASSIGN(child, reader.member(key));
  return read(child);
}

// An optional member read as a type by `read`.
template <typename T, typename Read>
Result<std::optional<T>> optional(const JsonReader& reader, std::string_view key, Read read) {
  std::optional<JsonReader> child;
  GLARECAM_ASSIGN(child, reader.optionalMember(key));
  if (!child) return std::optional<T>{};
  T value{};
  GLARECAM_ASSIGN(value, read(*child));
  return std::optional<T>(std::move(value));
}

}  // namespace

Result<double> JsonReader::number(std::string_view key) const {
  return required<double>(*this, key, [](const JsonReader& r) { return r.number(); });
}
Result<std::optional<double>> JsonReader::optionalNumber(std::string_view key) const {
  return optional<double>(*this, key, [](const JsonReader& r) { return r.number(); });
}
Result<double> JsonReader::positive(std::string_view key) const {
  return required<double>(*this, key, [](const JsonReader& r) { return r.positive(); });
}
Result<std::optional<double>> JsonReader::optionalPositive(std::string_view key) const {
  return optional<double>(*this, key, [](const JsonReader& r) { return r.positive(); });
}
Result<double> JsonReader::nonNegative(std::string_view key) const {
  return required<double>(*this, key, [](const JsonReader& r) { return r.nonNegative(); });
}
Result<std::optional<double>> JsonReader::optionalNonNegative(std::string_view key) const {
  return optional<double>(*this, key, [](const JsonReader& r) { return r.nonNegative(); });
}
Result<double> JsonReader::numberIn(std::string_view key, double low, double high,
                                    std::string_view unit) const {
  return required<double>(*this, key,
                          [&](const JsonReader& r) { return r.numberIn(low, high, unit); });
}
Result<std::optional<double>> JsonReader::optionalNumberIn(std::string_view key, double low,
                                                           double high,
                                                           std::string_view unit) const {
  return optional<double>(*this, key,
                          [&](const JsonReader& r) { return r.numberIn(low, high, unit); });
}
Result<long long> JsonReader::integer(std::string_view key, long long low, long long high) const {
  return required<long long>(*this, key, [&](const JsonReader& r) { return r.integer(low, high); });
}
Result<std::string> JsonReader::text(std::string_view key) const {
  return required<std::string>(*this, key, [](const JsonReader& r) { return r.text(); });
}
Result<std::optional<std::string>> JsonReader::optionalText(std::string_view key) const {
  return optional<std::string>(*this, key, [](const JsonReader& r) { return r.text(); });
}
Result<bool> JsonReader::boolean(std::string_view key) const {
  return required<bool>(*this, key, [](const JsonReader& r) { return r.boolean(); });
}
Result<std::optional<bool>> JsonReader::optionalBoolean(std::string_view key) const {
  return optional<bool>(*this, key, [](const JsonReader& r) { return r.boolean(); });
}

namespace {

// "a, b or c".
std::string alternatives(std::initializer_list<std::string_view> words) {
  std::string text;
  std::size_t i = 0;
  for (std::string_view word : words) {
    text += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + std::string(word);
    ++i;
  }
  return text;
}

}  // namespace

Result<std::optional<std::string>> JsonReader::optionalWord(
    std::string_view key, std::initializer_list<std::string_view> words) const {
  std::optional<std::string> text;
  GLARECAM_ASSIGN(text, optionalText(key));
  if (text && std::find(words.begin(), words.end(), *text) == words.end())
    return fail(key, "\"" + *text + "\" is not " + alternatives(words));
  return text;
}

Result<std::string> JsonReader::word(std::string_view key,
                                     std::initializer_list<std::string_view> words) const {
  std::optional<std::string> text;
  GLARECAM_ASSIGN(text, optionalWord(key, words));
  if (!text) return fail(key, "is missing (" + alternatives(words) + ")");
  return *text;
}

Result<std::string> JsonReader::schema(std::string_view expected, std::string_view what,
                                       std::initializer_list<std::string_view> accepted) const {
  GLARECAM_CHECK(object());
  if (!has("schema"))
    return fail("schema", fmt::format("is missing ({}'s is \"{}\")", what, expected));
  const json& value = value_->at("schema");
  if (value.is_string()) {
    const std::string schema = value.get<std::string>();
    if (schema == expected) return schema;
    for (std::string_view old : accepted) {
      if (schema == old) return schema;
    }
  }
  std::string readable = "\"" + std::string(expected) + "\"";
  for (std::string_view old : accepted) {
    if (old != expected) readable += " or \"" + std::string(old) + "\"";
  }
  return fail("schema",
              fmt::format("{} is not supported ({}'s is {})", jsonSnippet(value), what, readable));
}

}  // namespace glarecam
