// JSON documents in and out: parsing text and files (depth-guarded), writing the text every file
// and stdout gets (atomically for files), and one reader of typed fields whose every error names
// the file and the field.
//
// The field is named by its path from the document's root, spelled the way the docs' field tables
// spell it: "calibration.intrinsics.fx", "arrays[1].vertices_m[2][0]" (the JSON pointer
// /arrays/1/vertices_m/2/0 in words people read); the root itself is "the document". Every error
// is kBadInput and reads "FILE: FIELD PROBLEM", for example
//   scene.json: arrays[1].vertices_m[2][0] must be a number, not "east"
//   stack.json: frames[0].exposure_us is missing
//   profile.json: profile[3].vertical_deg 190° is outside [0, 180]
// Absent and null are the same to the reader: an optional field may be written as null.
#pragma once

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace glarecam {

// Deepest nesting accepted in a JSON document (manifests need 4): deeper ones are refused while
// parsing, since copying or printing them recurses once per level.
inline constexpr int kMaxJsonDepth = 64;

// Parses JSON text; the error names `where` and the parser's line and column.
Result<nlohmann::json> parseJsonText(std::string_view text, const std::string& where);
// Reads and parses a JSON file; a missing file is kBadInput, a failed read kIo.
Result<nlohmann::json> readJsonFile(const std::filesystem::path& path);

// A document as written to files and stdout: two-space indent, a final newline, and any string
// that is not valid UTF-8 (a directory name, say) with U+FFFD in place of its bad bytes instead
// of an exception.
std::string jsonText(const nlohmann::json& document);
// Writes jsonText(document) to `path` atomically (core/atomic_file.h).
Status writeJsonFile(const std::filesystem::path& path, const nlohmann::json& document);

// An optional value as JSON: the value, or null.
template <typename T>
nlohmann::json jsonOrNull(const std::optional<T>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}
// A number as JSON, null when there is none or it is not finite (JSON has no NaN or infinity).
nlohmann::json finiteOrNull(std::optional<double> value);

// A value as an error message shows it: compact JSON, at most 40 characters.
std::string jsonSnippet(const nlohmann::json& value);

// A JSON value in a document, with where it is. Cheap to copy (a reference to the value and its
// names); the document must outlive it. Member and element readers give the child's reader, so
// that nested blocks are read with their full path in every message.
class JsonReader {
 public:
  // Null, of no file: a reader to assign a member's to.
  JsonReader();
  // The root of a document read from `file` (the name messages give).
  JsonReader(const nlohmann::json& value, std::string file);
  // A block of it at `path` ("calibration"), read on its own.
  JsonReader(const nlohmann::json& value, std::string file, std::string path);

  const nlohmann::json& value() const { return *value_; }
  const std::string& file() const { return file_; }
  // The field's path ("arrays[1].name"); empty at the root.
  const std::string& path() const { return path_; }
  // The path as messages give it: "the document" at the root.
  std::string name() const;

  // "FILE: FIELD PROBLEM" (kBadInput), about this value or one of its members.
  std::unexpected<Error> fail(std::string_view problem) const;
  std::unexpected<Error> fail(std::string_view key, std::string_view problem) const;

  bool isNull() const { return value_->is_null(); }
  // Present and not null (false when this value is not an object).
  bool has(std::string_view key) const;
  // A required member: "is missing" when absent or null; "must be an object" when this value is
  // not one.
  Result<JsonReader> member(std::string_view key) const;
  // A member that may be absent or null.
  Result<std::optional<JsonReader>> optionalMember(std::string_view key) const;
  // A required member that is an object (or an array); an optional one (absent or null: none).
  Result<JsonReader> objectMember(std::string_view key) const;
  Result<JsonReader> arrayMember(std::string_view key) const;
  Result<std::optional<JsonReader>> optionalObject(std::string_view key) const;
  Result<std::optional<JsonReader>> optionalArray(std::string_view key) const;
  // Elements of an array (call array() first): element(i) for i < size().
  std::size_t size() const { return value_->size(); }
  JsonReader element(std::size_t index) const;

  // This value as a type: "must be an object", "must be a number, not "x"", ...
  Status object() const;
  Status array() const;
  Result<double> number() const;  // finite
  Result<double> positive() const;
  Result<double> nonNegative() const;
  // In [low, high]; `unit` follows the numbers in the message ("°", " cd/m²").
  Result<double> numberIn(double low, double high, std::string_view unit = "") const;
  // A whole number in [low, high].
  Result<long long> integer(long long low, long long high) const;
  Result<std::string> text() const;
  Result<bool> boolean() const;

  // Members as types; optional*: absent or null gives nullopt.
  Result<double> number(std::string_view key) const;
  Result<std::optional<double>> optionalNumber(std::string_view key) const;
  Result<double> positive(std::string_view key) const;
  Result<std::optional<double>> optionalPositive(std::string_view key) const;
  Result<double> nonNegative(std::string_view key) const;
  Result<std::optional<double>> optionalNonNegative(std::string_view key) const;
  Result<double> numberIn(std::string_view key, double low, double high,
                          std::string_view unit = "") const;
  Result<std::optional<double>> optionalNumberIn(std::string_view key, double low, double high,
                                                 std::string_view unit = "") const;
  Result<long long> integer(std::string_view key, long long low, long long high) const;
  Result<std::string> text(std::string_view key) const;
  Result<std::optional<std::string>> optionalText(std::string_view key) const;
  Result<bool> boolean(std::string_view key) const;
  Result<std::optional<bool>> optionalBoolean(std::string_view key) const;
  // Text that is one of `words`: "\"x\" is not a, b or c" otherwise.
  Result<std::string> word(std::string_view key,
                           std::initializer_list<std::string_view> words) const;
  Result<std::optional<std::string>> optionalWord(
      std::string_view key, std::initializer_list<std::string_view> words) const;

  // Refuses a member whose key is not among `known` (call object() first), since a misspelt
  // optional key would otherwise be read as absent: "FILE: PATH has an unknown key "profil" (did
  // you mean "profile"?)", or the known keys listed when none is close (core/spelling.h).
  Status onlyKeys(std::initializer_list<std::string_view> known) const;

  // The document's "schema": `expected`, or one of the older `accepted` ones. `what` names the
  // kind of document in the message ("a glare profile").
  Result<std::string> schema(std::string_view expected, std::string_view what,
                             std::initializer_list<std::string_view> accepted = {}) const;

 private:
  std::string childPath(std::string_view key) const;

  const nlohmann::json* value_;
  std::string file_;
  std::string path_;
};

// Each element of an array, read by `read` (a function of a JsonReader giving a Result<T>); the
// first failure is the result.
template <typename T, typename Read>
Result<std::vector<T>> readEach(const JsonReader& list, Read&& read) {
  GLARECAM_CHECK(list.array());
  std::vector<T> values;
  values.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    Result<T> value = read(list.element(i));
    if (!value) return std::unexpected(value.error());
    values.push_back(std::move(*value));
  }
  return values;
}

}  // namespace glarecam
