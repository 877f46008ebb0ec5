#include "surface/surface_catalogue.h"

#include <fmt/format.h>

#include "core/config_table.h"

namespace glarecam::surface {

MicrofacetParameters standardSurface() {
  // `glarecam model fit ../shared/data/standard-module-table3.csv`: widths 0.672 ± 0.040° and
  // 0.821 ± 0.063°, lobe weight 0.295 ± 0.027; R² 0.934 (ln Lmax), 0.924 (vertical), 0.859
  // (horizontal). Lmax at 70–80° reads half the table's (docs/brdf.md, "Where the model stops").
  MicrofacetParameters p;
  p.distribution = SlopeDistribution::kGgx;
  p.width_x_deg = 0.6722;
  p.width_y_deg = 0.8211;
  p.lobe_weight = 0.2949;
  return p;
}

MicrofacetParameters glareReducedSurface() {
  // `glarecam model fit tests/data/glare-reduced-table6-curves.csv --distribution beckmann`:
  // widths 3.82 ± 0.17° and 5.96 ± 0.34°, lobe weight 0.605 ± 0.015; R² 0.962 (ln Lmax), 0.925
  // (vertical), -0.22 (horizontal: the model's horizontal axis shrinks at 70° where the curve's
  // keeps growing).
  MicrofacetParameters p;
  p.distribution = SlopeDistribution::kBeckmann;
  p.width_x_deg = 3.815;
  p.width_y_deg = 5.957;
  p.lobe_weight = 0.6047;
  return p;
}

std::vector<std::string> surfaceNames() { return {"standard", "glare-reduced", "gaussian"}; }

Result<std::unique_ptr<BrdfModel>> readSurfaceFile(const std::filesystem::path& path) {
  constexpr std::string_view kSections[] = {"surface"};
  toml::table root;
  GLARECAM_ASSIGN(root, readConfigFile(path, kSections));
  const toml::table* table = root["surface"].as_table();
  if (!table)
    return badInput(path.string() + ": no [surface] table (docs/brdf.md, \"The surface model\")");
  TableReader reader(path, *table, "surface");
  std::optional<std::string> model;
  GLARECAM_ASSIGN(model, reader.choice("model", {"microfacet", "gaussian"}));
  std::unique_ptr<BrdfModel> out;
  if (model.value_or("microfacet") == "gaussian") {
    GaussianLobeParameters g;
    GLARECAM_ASSIGN(g.peak_brdf_sr, reader.requiredNumber("peak_brdf_sr", 1e-9, 1e9));
    GLARECAM_ASSIGN(g.sigma_horizontal_deg,
                    reader.requiredNumber("sigma_horizontal_deg", 1e-3, 30));
    GLARECAM_ASSIGN(g.sigma_vertical_deg, reader.requiredNumber("sigma_vertical_deg", 1e-3, 30));
    std::optional<double> floor;
    GLARECAM_ASSIGN(floor, reader.number("floor_brdf_sr", 0, 1e9));
    g.floor_brdf_sr = floor.value_or(0);
    if (const Status valid = g.validate(); !valid) return reader.tableError(valid.error().message);
    out = std::make_unique<GaussianLobeBrdf>(g);
  } else {
    MicrofacetParameters p;
    std::optional<std::string> distribution;
    GLARECAM_ASSIGN(distribution, reader.choice("distribution", {"ggx", "beckmann"}));
    if (distribution) p.distribution = *slopeDistributionFromString(*distribution);
    GLARECAM_ASSIGN(p.width_x_deg, reader.requiredNumber("width_x_deg", 1e-3, 45));
    GLARECAM_ASSIGN(p.width_y_deg, reader.requiredNumber("width_y_deg", 1e-3, 45));
    const auto optional = [&](const char* key, double low, double high, double& target) -> Status {
      std::optional<double> value;
      GLARECAM_ASSIGN(value, reader.number(key, low, high));
      if (value) target = *value;
      return {};
    };
    GLARECAM_CHECK(optional("lobe_weight", 1e-6, 100, p.lobe_weight));
    GLARECAM_CHECK(optional("refractive_index", 1.01, 3, p.refractive_index));
    double coating_index = 0;
    GLARECAM_CHECK(optional("coating_index", 1.01, 3, coating_index));
    if (coating_index > 0) p.coating_index = coating_index;
    GLARECAM_CHECK(optional("coating_thickness_nm", 0, 10'000, p.coating_thickness_nm));
    GLARECAM_CHECK(optional("second_lobe_weight", 0, 1, p.second_lobe_weight));
    GLARECAM_CHECK(optional("second_lobe_width_deg", 1e-3, 45, p.second_lobe_width_deg));
    GLARECAM_CHECK(optional("diffuse_reflectance", 0, 1, p.diffuse_reflectance));
    if (p.coating_index.has_value() != (p.coating_thickness_nm > 0))
      return reader.tableError("coating_index and coating_thickness_nm go together");
    if (const Status valid = p.validate(); !valid) return reader.tableError(valid.error().message);
    out = std::make_unique<MicrofacetBrdf>(p);
  }
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  return out;
}

Result<MicrofacetParameters> readMicrofacetFile(const std::filesystem::path& path) {
  std::unique_ptr<BrdfModel> model;
  GLARECAM_ASSIGN(model, readSurfaceFile(path));
  const auto* microfacet = dynamic_cast<const MicrofacetBrdf*>(model.get());
  if (!microfacet)
    return badInput(path.string() + ": not a microfacet surface (model = \"microfacet\")");
  return microfacet->parameters();
}

Result<std::unique_ptr<BrdfModel>> surfaceModel(std::string_view name_or_file) {
  if (name_or_file == "standard") return std::make_unique<MicrofacetBrdf>(standardSurface());
  if (name_or_file == "glare-reduced")
    return std::make_unique<MicrofacetBrdf>(glareReducedSurface());
  if (name_or_file == "gaussian")
    return std::make_unique<GaussianLobeBrdf>(GaussianLobeParameters{});
  const std::filesystem::path path(name_or_file);
  std::error_code ec;
  if (path.extension() == ".toml" || std::filesystem::exists(path, ec))
    return readSurfaceFile(path);
  std::string names;
  for (const std::string& n : surfaceNames()) names += (names.empty() ? "" : ", ") + n;
  return badInput(fmt::format("--surface: \"{}\" is neither a surface ({}) nor a .toml file",
                              name_or_file, names));
}

}  // namespace glarecam::surface
