// Publishing a sweep: the data sheet (datasheet.pdf/.svg/.png, datasheet.h) and the machine-
// readable glare profile (glare-profile.json, glare_profile.h) of one fitted sweep table, written
// together into one directory, each file atomically. `glarecam datasheet` and glarecamd's per-day
// sheets both publish through here.
#pragma once

#include <filesystem>

#include "core/error.h"
#include "pipeline/glare_profile.h"
#include "pipeline/render/datasheet.h"

namespace glarecam::pipeline {

// `content` names the table and its fits; `source` is the sweep table's path (in the profile).
Status publishDatasheet(const DatasheetContent& content, const std::string& source,
                        const std::filesystem::path& directory);

}  // namespace glarecam::pipeline
