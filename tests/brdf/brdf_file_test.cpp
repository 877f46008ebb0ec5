#include "brdf/brdf_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "brdf/simulated_goniophotometer.h"
#include "surface/brdf_model.h"
#include "tests/support/test_support.h"

namespace glarecam::brdf {
namespace {

const surface::GaussianLobeBrdf kFileLobe({.peak_brdf_sr = 60,
                                           .sigma_horizontal_deg = 2,
                                           .sigma_vertical_deg = 1.5,
                                           .floor_brdf_sr = 0.05});

GoniophotometerOptions quickOptions() {
  GoniophotometerOptions o;
  o.alphas_deg = {10, 40};
  o.fine_step_deg = 0.25;
  o.medium_radius_deg = 20;
  o.relative_noise = 0;
  return o;
}

TEST(PabOptoFile, WrittenAndReadBackIsTheSameMeasurement) {
  const BrdfMeasurement m = simulateMeasurement(kFileLobe, 40, quickOptions(), "a40.dat");
  const auto read = parseBrdfText(formatPabOpto(m), "a40.dat");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->size(), 1u);
  const BrdfMeasurement& r = read->front();
  EXPECT_EQ(r.format, BrdfFileFormat::kPabOpto);
  EXPECT_EQ(r.sample_name, "simulated");
  EXPECT_DOUBLE_EQ(r.incident_theta_deg, 40);
  ASSERT_EQ(r.samples.size(), m.samples.size());
  for (std::size_t i = 0; i < m.samples.size(); i += 97) {
    // Written with 8 significant digits.
    EXPECT_NEAR(r.samples[i].theta_deg, m.samples[i].theta_deg, 1e-6);
    EXPECT_NEAR(r.samples[i].brdf_sr, m.samples[i].brdf_sr, 1e-7 * m.samples[i].brdf_sr);
    EXPECT_GT(r.samples[i].line, 0);
  }
}

TEST(PabOptoFile, DsfIsTheBsdfTimesTheCosine) {
  const std::string text = "#format: theta phi DSF\n#intheta 20\n#inphi 0\n0 0 0.5\n60 90 0.5\n";
  const auto read = parseBrdfText(text, "dsf.dat");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_NEAR(read->front().samples[0].brdf_sr, 0.5, 1e-12);
  EXPECT_NEAR(read->front().samples[1].brdf_sr, 1.0, 1e-12);  // 0.5 / cos 60°
}

TEST(PabOptoFile, IncidentAngleAndRadianceKeysAreRead) {
  const std::string text =
      "#sample_name \"AR glass\"\n#format: theta phi BSDF\n#incident_angle 30 45\n"
      "#upphi 90\n#colorimetry: CIE-Y\n#relative_noise 0.02\n1 2 3\n";
  const auto read = parseBrdfText(text, "k.dat");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->front().sample_name, "AR glass");
  EXPECT_DOUBLE_EQ(read->front().incident_theta_deg, 30);
  EXPECT_DOUBLE_EQ(read->front().incident_phi_deg, 45);
  EXPECT_DOUBLE_EQ(*read->front().relative_noise, 0.02);
}

TEST(ZemaxFile, WrittenAndReadBackHoldsEveryAngleAndMirrorsTheHalfPlane) {
  const ZemaxTable table = simulateZemaxTable(kFileLobe, quickOptions());
  const auto read = parseBrdfText(formatZemaxBsdf(table), "s.bsdf");
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_EQ(read->size(), 2u);
  for (const BrdfMeasurement& m : *read) {
    EXPECT_EQ(m.format, BrdfFileFormat::kZemax);
    // Every value the model gives at its direction (no noise): the angles map back exactly.
    const auto incident = surface::sampleDirection(m.incident_theta_deg, m.incident_phi_deg);
    for (std::size_t i = 0; i < m.samples.size(); i += 53) {
      const BrdfSample& s = m.samples[i];
      const double f = kFileLobe.brdfSr(incident, surface::sampleDirection(s.theta_deg, s.phi_deg));
      EXPECT_NEAR(s.brdf_sr, f, 1e-6 * f) << "θ " << s.theta_deg << " φ " << s.phi_deg;
    }
  }
  // A plane-symmetric half (0-180°) fills both sides: a sample at +x and its mirror at -x.
  const surface::SpecularFrame frame(10, 0);
  bool plus = false, minus = false;
  for (const BrdfSample& s : read->front().samples) {
    const auto p = frame.toPlane(s.theta_deg, s.phi_deg);
    plus = plus || p.x_deg > 1;
    minus = minus || p.x_deg < -1;
  }
  EXPECT_TRUE(plus && minus);
}

struct BadFile {
  std::string name, text, message;  // the message must contain this
};

class BadBrdfFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadBrdfFile, IsRefusedNamingTheFileAndLine) {
  const auto read = parseBrdfText(GetParam().text, "bad.dat");
  ASSERT_FALSE(read) << GetParam().name;
  EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
  EXPECT_NE(read.error().message.find(GetParam().message), std::string::npos)
      << read.error().message;
  EXPECT_EQ(read.error().message.rfind("bad.dat", 0), 0u) << read.error().message;
}

const std::string kZemaxHeader =
    "Source Measured\nSymmetry PlaneSymmetrical\nSpectralContent Monochrome\n"
    "ScatterType BRDF\nSampleRotation 1\n0\nAngleOfIncidence 1\n10\nScatterAzimuth 2\n0 180\n"
    "ScatterRadial 2\n0 1\nMonochrome\nDataBegin\nTIS 0.5\n";

INSTANTIATE_TEST_SUITE_P(
    Formats, BadBrdfFile,
    ::testing::Values(
        BadFile{"unknown", "hello world\n1 2 3\n", "bad.dat:1: unknown BRDF format"},
        BadFile{"klems", "<?xml version=\"1.0\"?>\n<WindowElement>LBNL/Klems Full", "Klems basis"},
        BadFile{"btdf", "#format: theta phi BTDF\n#intheta 10\n#inphi 0\n", "bad.dat:1: BTDF"},
        BadFile{"behind", "#format: theta phi BSDF\n#intheta 10\n#inphi 0\n120 0 1\n",
                "bad.dat:4: θ 120° lies behind the sample"},
        BadFile{"negative", "#format: theta phi BSDF\n#intheta 10\n#inphi 0\n1 0 1\n2 0 -3\n",
                "bad.dat:5: negative value -3"},
        BadFile{"nan", "#format: theta phi BSDF\n#intheta 10\n#inphi 0\n1 0 nan\n",
                "bad.dat:4: nan is not finite"},
        BadFile{"incidence", "#format: theta phi BSDF\n#intheta 95\n#inphi 0\n1 0 1\n",
                "angle of incidence 95° is outside"},
        BadFile{"no angle", "#format: theta phi BSDF\n1 0 1\n", "bad.dat:2: data before the angle"},
        BadFile{"fields", "#format: theta phi BSDF\n#intheta 1\n#inphi 0\n1 0\n",
                "bad.dat:4: a sample row is \"theta phi value\", this one has 2 fields"},
        BadFile{"colour", "#format: theta phi BSDF\n#colorimetry: CIE-X\n#intheta 1\n#inphi 0\n",
                "bad.dat:2: #colorimetry CIE-X"},
        BadFile{"conflicting incidence",
                "#format: theta phi BSDF\n#intheta 30\n#inphi 0\n#incident_angle 40 0\n1 0 1\n",
                "bad.dat:4: #incident_angle gives θ_i 40°, an earlier header 30°"},
        BadFile{"extra word", "#format: theta phi BSDF\n#intheta 30 40\n",
                "bad.dat:2: #intheta takes 1 number"},
        BadFile{"nul byte",
                std::string("#format: theta phi BSDF\n#intheta 3\n#inphi 0\n1 0 1") + '\0' + "x\n",
                "bad.dat:4: \"1?x\" is not a number"},
        BadFile{"zemax btdf", "Symmetry PlaneSymmetrical\nScatterType BTDF\n",
                "bad.dat:2: ScatterType BTDF"},
        BadFile{"zemax radial",
                "Symmetry PlaneSymmetrical\nScatterType BRDF\nAngleOfIncidence 1\n10\n"
                "ScatterRadial 2\n0 95\n",
                "bad.dat:6: ScatterRadial 95° is outside [0, 90]°"},
        BadFile{"zemax short", kZemaxHeader + "1 2\n3\nDataEnd\n", "bad.dat:18: a BRDF value"},
        BadFile{"zemax negative", kZemaxHeader + "1 2\n-3 4\nDataEnd\n",
                "bad.dat:17: negative value -3"},
        BadFile{"zemax long", kZemaxHeader + "1 2\n3 4 5\nDataEnd\n",
                "bad.dat:17: expected DataEnd"},
        BadFile{"zemax keyword", "Symmetry PlaneSymmetrical\nScatterTipe BRDF\n",
                "bad.dat:2: unknown keyword \"ScatterTipe\""}),
    [](const auto& info) {
      std::string name = info.param.name;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(ZemaxFile, ASecondLobeAtGrazingAnglesStaysFinite) {
  // The second lobe's 1/cos θ_o once diverged at the Zemax grid's 90° directions (a simulated
  // file its own reader then refused): shadowed now, and nothing measured beyond 89°.
  surface::MicrofacetParameters p;
  p.distribution = surface::SlopeDistribution::kBeckmann;
  p.width_x_deg = 1.2;
  p.width_y_deg = 2;
  p.second_lobe_weight = 0.05;
  const surface::MicrofacetBrdf model(p);
  GoniophotometerOptions o;
  o.alphas_deg = {60, 70};
  const auto read = parseBrdfText(formatZemaxBsdf(simulateZemaxTable(model, o)), "s.bsdf");
  ASSERT_TRUE(read) << read.error().message;
  for (const BrdfMeasurement& m : *read) {
    for (const BrdfSample& s : m.samples) ASSERT_LT(s.brdf_sr, 1e3) << s.theta_deg;
    EXPECT_TRUE(checkSampling(m)) << m.incident_theta_deg;
  }
}

TEST(BrdfFile, AMissingFileOrADirectoryIsBadInput) {
  const glarecam::testing::TempDir dir;
  for (const auto& path : {dir / "missing.dat", dir.path()}) {
    const auto read = readBrdfFile(path);
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
    EXPECT_NE(read.error().message.find(path.string()), std::string::npos);
  }
}

}  // namespace
}  // namespace glarecam::brdf
