#include "hazard/json_fields.h"

#include <cmath>
#include <cstdio>

namespace glarecam::hazard {
namespace {

std::string formatValue(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

std::unexpected<Error> JsonFields::fail(const std::string& field,
                                        const std::string& problem) const {
  return badInput(file_ + ": " + field + " " + problem);
}

std::string JsonFields::child(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string JsonFields::element(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

Result<const nlohmann::json*> JsonFields::member(const nlohmann::json& object,
                                                 const std::string& where,
                                                 const std::string& key) const {
  if (!object.is_object()) return fail(where.empty() ? "the document" : where, "is not an object");
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return fail(child(where, key), "is missing");
  return &*it;
}

const nlohmann::json* JsonFields::optionalMember(const nlohmann::json& object,
                                                 const std::string& key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() || it->is_null() ? nullptr : &*it;
}

Result<double> JsonFields::number(const nlohmann::json& value, const std::string& field) const {
  if (!value.is_number()) return fail(field, "is not a number");
  const double x = value.get<double>();
  if (!std::isfinite(x)) return fail(field, "is not finite");
  return x;
}

Result<double> JsonFields::numberIn(const nlohmann::json& value, const std::string& field,
                                    double low, double high, const char* unit) const {
  double x = 0;
  GLARECAM_ASSIGN(x, number(value, field));
  if (x < low || x > high) {
    return fail(field, formatValue(x) + unit + " is outside [" + formatValue(low) + ", " +
                           formatValue(high) + "]");
  }
  return x;
}

Result<std::string> JsonFields::text(const nlohmann::json& value, const std::string& field) const {
  if (!value.is_string()) return fail(field, "is not a string");
  return value.get<std::string>();
}

Status JsonFields::object(const nlohmann::json& value, const std::string& field) const {
  if (!value.is_object()) return fail(field, "is not an object");
  return {};
}

Status JsonFields::array(const nlohmann::json& value, const std::string& field) const {
  if (!value.is_array()) return fail(field, "is not an array");
  return {};
}

}  // namespace glarecam::hazard
