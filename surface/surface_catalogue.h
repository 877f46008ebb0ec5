// Surfaces by name or file (docs/brdf.md, "The surface model"): what `--surface` takes.
//   standard        the microfacet model fitted to the paper's Table III (the standard module),
//                   `glarecam model fit ../shared/data/standard-module-table3.csv` (GGX)
//   glare-reduced   fitted to the paper's Table VI curves of the glare-reduced module,
//                   `glarecam model fit tests/data/glare-reduced-table6-curves.csv
//                   --distribution beckmann` (Beckmann follows its axes better than GGX)
//   gaussian        the analytic Gaussian lobe of the tests (not a physical surface)
//   FILE.toml       a [surface] table: model = "microfacet" (the MicrofacetParameters keys) or
//                   "gaussian" (the GaussianLobeParameters keys); what `model fit --out` writes.
// Both fits treat the unreferred tables as if at 100 klx: the lobe weight carries the day's sun.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "surface/brdf_model.h"

namespace glarecam::surface {

// The parameters of the named microfacet surfaces, with their fits' σ (the test re-fits them).
MicrofacetParameters standardSurface();
MicrofacetParameters glareReducedSurface();

// A surface by name or from a TOML file (a name that is not one and not a file: kBadInput
// listing the names).
Result<std::unique_ptr<BrdfModel>> surfaceModel(std::string_view name_or_file);
std::vector<std::string> surfaceNames();

// A surface file's model (kBadInput naming FILE:LINE and the key).
Result<std::unique_ptr<BrdfModel>> readSurfaceFile(const std::filesystem::path& path);
// The same for a microfacet surface's parameters (a Gaussian one is refused naming the file).
Result<MicrofacetParameters> readMicrofacetFile(const std::filesystem::path& path);

}  // namespace glarecam::surface
