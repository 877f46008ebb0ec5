// The program that wrote a document, as every glarecam document records it:
// "generator": {"name": "glarecam", "version": "0.1.0"}.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "core/json.h"
#include "core/version.h"

namespace glarecam {

struct Generator {
  std::string name = "glarecam";
  std::string version = kVersion;  // this build's
  bool operator==(const Generator&) const = default;
};

nlohmann::json toJson(const Generator& generator);
// The block `generator` of a document (name and version required, both text).
Result<Generator> generatorFromJson(const JsonReader& block);

}  // namespace glarecam
