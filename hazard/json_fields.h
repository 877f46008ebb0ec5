// Reading the fields of a JSON input file (a hazard scene, a glare profile) with one-line errors
// that name the file and the field: "scene.json: arrays[1].vertices_m[2][0] is not a number".
// `where` is the field's path so far ("arrays[1]"); `file` the file's name for messages.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/error.h"

namespace glarecam::hazard {

class JsonFields {
 public:
  explicit JsonFields(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }

  // "FILE: FIELD PROBLEM" as kBadInput.
  std::unexpected<Error> fail(const std::string& field, const std::string& problem) const;

  // The child path "parent.key" or "key" and "parent[i]".
  static std::string child(const std::string& parent, const std::string& key);
  static std::string element(const std::string& parent, std::size_t index);

  // A required member of `object` (itself named `where`).
  Result<const nlohmann::json*> member(const nlohmann::json& object, const std::string& where,
                                       const std::string& key) const;
  // Present and not null, or nullptr.
  static const nlohmann::json* optionalMember(const nlohmann::json& object, const std::string& key);

  Result<double> number(const nlohmann::json& value, const std::string& field) const;
  Result<double> numberIn(const nlohmann::json& value, const std::string& field, double low,
                          double high, const char* unit) const;
  Result<std::string> text(const nlohmann::json& value, const std::string& field) const;
  Status object(const nlohmann::json& value, const std::string& field) const;
  Status array(const nlohmann::json& value, const std::string& field) const;

 private:
  std::string file_;
};

}  // namespace glarecam::hazard
