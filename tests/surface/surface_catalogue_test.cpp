#include "surface/surface_catalogue.h"

#include <gtest/gtest.h>

#include "tests/support/test_support.h"

namespace glarecam::surface {
namespace {

using glarecam::testing::TempDir;
using glarecam::testing::writeText;

TEST(SurfaceCatalogue, NamesGiveTheirModels) {
  for (const std::string& name : surfaceNames()) {
    const auto model = surfaceModel(name);
    ASSERT_TRUE(model) << name;
    EXPECT_GT((*model)->brdfSr(20, 0, 20, 180), 0) << name;
  }
  const auto unknown = surfaceModel("standrad");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("standard, glare-reduced, gaussian"), std::string::npos);
}

TEST(SurfaceCatalogue, AFileGivesItsParametersAndRefusesMistakesByLine) {
  const TempDir dir;
  writeText(dir / "ar.toml",
            "# a coated glass\n[surface]\nmodel = \"microfacet\"\ndistribution = \"beckmann\"\n"
            "width_x_deg = 2\nwidth_y_deg = 3\ncoating_index = 1.27\ncoating_thickness_nm = 108\n");
  const auto model = surfaceModel((dir / "ar.toml").string());
  ASSERT_TRUE(model) << model.error().message;
  const auto* microfacet = dynamic_cast<const MicrofacetBrdf*>(model->get());
  ASSERT_NE(microfacet, nullptr);
  EXPECT_EQ(microfacet->parameters().distribution, SlopeDistribution::kBeckmann);
  EXPECT_DOUBLE_EQ(*microfacet->parameters().coating_index, 1.27);

  writeText(dir / "typo.toml", "[surface]\nwidth_x_deg = 2\nwidth_y_deg = 3\nwidht = 4\n");
  const auto typo = surfaceModel((dir / "typo.toml").string());
  ASSERT_FALSE(typo);
  EXPECT_NE(typo.error().message.find("typo.toml:4: unknown key surface.widht"), std::string::npos)
      << typo.error().message;

  writeText(dir / "wide.toml", "[surface]\nwidth_x_deg = 90\nwidth_y_deg = 3\n");
  const auto wide = surfaceModel((dir / "wide.toml").string());
  ASSERT_FALSE(wide);
  EXPECT_NE(wide.error().message.find("wide.toml:2:"), std::string::npos) << wide.error().message;

  const auto missing = surfaceModel((dir / "missing.toml").string());
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().code, ErrorCode::kBadInput);
}

}  // namespace
}  // namespace glarecam::surface
