#include "core/generator.h"

namespace glarecam {

nlohmann::json toJson(const Generator& generator) {
  return {{"name", generator.name}, {"version", generator.version}};
}

Result<Generator> generatorFromJson(const JsonReader& block) {
  GLARECAM_CHECK(block.object());
  Generator generator;
  GLARECAM_ASSIGN(generator.name, block.text("name"));
  GLARECAM_ASSIGN(generator.version, block.text("version"));
  return generator;
}

}  // namespace glarecam
