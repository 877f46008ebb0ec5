#include "pipeline/datasheet_publish.h"

#include "core/atomic_file.h"
#include "core/stack_manifest.h"

namespace glarecam::pipeline {

Status publishDatasheet(const DatasheetContent& content, const std::string& source,
                        const std::filesystem::path& directory) {
  GLARECAM_CHECK(writeDatasheet(content, directory));
  const nlohmann::json profile =
      glareProfileJson({.module = content.module, .date = content.date, .source = source},
                       *content.table, *content.fits, content.limit);
  return writeFileAtomic(directory / kGlareProfileFileName, jsonText(profile));
}

}  // namespace glarecam::pipeline
