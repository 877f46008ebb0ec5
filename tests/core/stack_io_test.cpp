#include "core/stack_io.h"

#include <gtest/gtest.h>

#include "core/image_io.h"
#include "support/test_support.h"

namespace glarecam {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

TEST(StackIo, WrittenStackReadsBackIdentically) {
  testing::TempDir dir;
  const auto written = testing::writeTestStack(dir / "s");
  auto stack = readStack(dir / "s");
  ASSERT_TRUE(stack) << stack.error().message;
  ASSERT_EQ(stack->frames.size(), written.frames.size());
  for (std::size_t f = 0; f < stack->frames.size(); ++f) {
    ASSERT_EQ(stack->bit_depths[f], 16);
    for (std::size_t i = 0; i < stack->frames[f].pixelCount(); ++i) {
      ASSERT_EQ(stack->frames[f].data()[i], written.frames[f].data()[i]);
    }
    EXPECT_EQ(stack->manifest.frames[f].exposure_us, written.manifest.frames[f].exposure_us);
  }
  EXPECT_EQ(stack->calibration_origin, "inline");
  EXPECT_EQ(stack->manifest.alpha_deg, 40.0);
  EXPECT_TRUE(fs::exists(dir / "s" / "truth.json"));
  EXPECT_EQ(fs::status(dir / "s").permissions() & fs::perms::others_read, fs::perms::others_read);
}

TEST(StackIo, AcceptsTiffAnd8BitFrames) {
  testing::TempDir dir;
  const auto written = testing::writeTestStack(dir / "s");
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  RawFrame eight_bit(written.frames[0].width(), written.frames[0].height(), 200);
  ASSERT_TRUE(writeTiffGray16(dir / "s" / "frame-00.tif", written.frames[0]));
  ASSERT_TRUE(writePngGray(dir / "s" / "frame-01.png", eight_bit, 8));
  manifest["frames"][0]["file"] = "frame-00.tif";
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto stack = readStack(dir / "s");
  ASSERT_TRUE(stack) << stack.error().message;
  EXPECT_EQ(stack->frames[0].data()[5], written.frames[0].data()[5]);
  EXPECT_EQ(stack->bit_depths[1], 8);
  EXPECT_EQ(stack->frames[1].data()[5], 200);
}

TEST(StackIo, CalibrationFromTheCommandLineOverridesPathWhichIsRelativeToTheStack) {
  testing::TempDir dir;
  testing::writeTestStack(dir / "s");
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  json calibration = manifest["calibration"];
  calibration["luminance_factor"] = 111.0;
  fs::create_directories(dir / "calib");
  testing::writeText(dir / "calib" / "rig.json", calibration.dump());
  manifest["calibration"] = "../calib/rig.json";
  testing::writeText(dir / "s" / "stack.json", manifest.dump());

  StackReadOptions manifest_only;
  manifest_only.decode_frames = false;
  auto from_path = readStack(dir / "s", manifest_only);
  ASSERT_TRUE(from_path) << from_path.error().message;
  EXPECT_EQ(from_path->calibration.luminance_factor, 111.0);
  EXPECT_EQ(from_path->calibration_origin, "../calib/rig.json");

  calibration["luminance_factor"] = 222.0;
  testing::writeText(dir / "override.json", calibration.dump());
  StackReadOptions options;
  options.calibration_file = dir / "override.json";
  options.decode_frames = false;
  auto overridden = readStack(dir / "s", options);
  ASSERT_TRUE(overridden) << overridden.error().message;
  EXPECT_EQ(overridden->calibration.luminance_factor, 222.0);
}

TEST(StackIo, FlatFieldIsLoadedRelativeToTheCalibration) {
  testing::TempDir dir;
  const auto written = testing::writeTestStack(dir / "s");
  FloatImage flat(written.frames[0].width(), written.frames[0].height(), 0.8f);
  ASSERT_TRUE(writeExr(dir / "s" / "flat.exr", flat));
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  manifest["calibration"]["flat_field"] = "flat.exr";
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto stack = readStack(dir / "s");
  ASSERT_TRUE(stack) << stack.error().message;
  ASSERT_TRUE(stack->flat_field);
  EXPECT_FLOAT_EQ(stack->flat_field->at(3, 3), 0.8f);
}

// The dark frame and hot-pixel map are read like the flat field; each of another size than the
// frames (another camera or binning), a dark frame with values no sensor gives, or a path that
// escapes, is refused naming the file.
TEST(StackIo, DarkFrameAndHotPixelsAreLoadedAndCheckedAgainstTheFrames) {
  testing::TempDir dir;
  const auto written = testing::writeTestStack(dir / "s");
  const int width = written.frames[0].width(), height = written.frames[0].height();
  FloatImage dark(width, height, 65.5f);
  RawFrame hot(width, height, 0);
  hot.at(2, 3) = 255;
  ASSERT_TRUE(writeExr(dir / "s" / "dark.exr", dark));
  ASSERT_TRUE(writePngGray(dir / "s" / "hot.png", hot, 8));
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  manifest["calibration"]["dark_frame"] = "dark.exr";
  manifest["calibration"]["dark_frame_exposure_us"] = 10000;
  manifest["calibration"]["dark_current_dn_per_us"] = 1e-4;
  manifest["calibration"]["hot_pixels"] = "hot.png";
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto stack = readStack(dir / "s");
  ASSERT_TRUE(stack) << stack.error().message;
  ASSERT_TRUE(stack->dark_frame_dn && stack->hot_pixels);
  EXPECT_FLOAT_EQ(stack->dark_frame_dn->at(3, 3), 65.5f);
  EXPECT_EQ(stack->hot_pixels->at(2, 3), 255);
  EXPECT_EQ(stack->hot_pixels->at(3, 3), 0);
  EXPECT_EQ(stack->calibration.dark_frame_exposure_us, 10000.0);
  EXPECT_EQ(stack->calibration.dark_current_dn_per_us, 1e-4);
  EXPECT_EQ(toJson(stack->calibration)["dark_frame"], "dark.exr");

  const auto refused = [&](const std::string& needle) {
    auto bad = readStack(dir / "s");
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, ErrorCode::kBadInput);
    EXPECT_NE(bad.error().message.find(needle), std::string::npos) << bad.error().message;
  };
  ASSERT_TRUE(writeExr(dir / "s" / "dark.exr", FloatImage(width / 2, height, 65.0f)));
  refused("dark.exr: dark frame is " + std::to_string(width / 2) + "x" + std::to_string(height));
  ASSERT_TRUE(writeExr(dir / "s" / "dark.exr", FloatImage(width, height, -1.0f)));
  refused("dark.exr: dark frame has negative or non-finite values");
  FloatImage stuck = dark;  // a pixel stuck at full scale: the hot-pixel map's business
  stuck.at(1, 1) = 4095.0f;
  ASSERT_TRUE(writeExr(dir / "s" / "dark.exr", stuck));
  EXPECT_TRUE(readStack(dir / "s")) << "a saturated dark pixel is read";
  ASSERT_TRUE(writeExr(dir / "s" / "dark.exr", dark));
  ASSERT_TRUE(writePngGray(dir / "s" / "hot.png", RawFrame(width, height + 2, 0), 8));
  refused("hot.png: hot-pixel map is " + std::to_string(width) + "x" + std::to_string(height + 2));
  manifest["calibration"]["hot_pixels"] = "../hot.png";
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  refused("calibration.hot_pixels \"../hot.png\" escapes");
  manifest["calibration"].erase("hot_pixels");
  manifest["calibration"]["dark_frame_exposure_us"] = 0;
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  refused("calibration.dark_frame_exposure_us must be positive");
}

// Intrinsics are in pixels of the size they were calibrated at: at another size every angle is
// off by the ratio, so a recorded size that differs from the frames' is refused, whatever the
// calibration's origin; one that agrees, or none recorded (older files), is read.
TEST(StackIo, IntrinsicsOfAnotherImageSizeAreRefused) {
  testing::TempDir dir;
  const auto written = testing::writeTestStack(dir / "s");
  const int width = written.frames[0].width(), height = written.frames[0].height();
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  manifest["calibration"]["intrinsics"]["width"] = width;
  manifest["calibration"]["intrinsics"]["height"] = height;
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto same = readStack(dir / "s");
  ASSERT_TRUE(same) << same.error().message;
  EXPECT_EQ(same->calibration.intrinsics.width, width);

  manifest["calibration"]["intrinsics"]["width"] = 2 * width;
  manifest["calibration"]["intrinsics"]["height"] = 2 * height;
  testing::writeText(dir / "calibration.json", manifest["calibration"].dump());
  StackReadOptions options;
  options.calibration_file = dir / "calibration.json";
  auto other = readStack(dir / "s", options);
  ASSERT_FALSE(other);
  EXPECT_EQ(other.error().code, ErrorCode::kBadInput);
  EXPECT_NE(other.error().message.find(
                (dir / "calibration.json").string() + ": intrinsics were calibrated at " +
                std::to_string(2 * width) + "x" + std::to_string(2 * height) + ", frames are " +
                std::to_string(width) + "x" + std::to_string(height)),
            std::string::npos)
      << other.error().message;

  for (const json& bad : {json{{"width", width}}, json{{"width", 0.5}, {"height", height}},
                          json{{"width", "320"}, {"height", height}}}) {
    json calibration = manifest["calibration"];
    calibration["intrinsics"].erase("width");
    calibration["intrinsics"].erase("height");
    calibration["intrinsics"].update(bad);
    testing::writeText(dir / "calibration.json", calibration.dump());
    auto refused = readStack(dir / "s", options);
    ASSERT_FALSE(refused) << bad;
    EXPECT_NE(refused.error().message.find("calibration.intrinsics"), std::string::npos)
        << refused.error().message;
  }
}

TEST(StackIo, FNumberNeedsAReferenceFNumber) {
  testing::TempDir dir;
  testing::writeTestStack(dir / "s");
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  manifest["calibration"].erase("reference_f_number");
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto stack = readStack(dir / "s");
  ASSERT_FALSE(stack);
  EXPECT_NE(stack.error().message.find("no reference_f_number"), std::string::npos)
      << stack.error().message;
}

TEST(StackIo, RewritingPreservesUnknownFieldsAndReplacesAtomically) {
  testing::TempDir dir;
  testing::writeTestStack(dir / "s");
  json document = json::parse(testing::readText(dir / "s" / "stack.json"));
  document["operator_note"] = "cloud at 10:14";
  testing::writeText(dir / "s" / "stack.json", document.dump());
  auto stack = readStack(dir / "s");
  ASSERT_TRUE(stack) << stack.error().message;
  stack->manifest.alpha_deg = 12.5;
  StackWriteRequest request;
  request.manifest = stack->manifest;
  request.frames = stack->frames;
  ASSERT_TRUE(writeStack(dir / "s", request));
  auto reread = readStack(dir / "s");
  ASSERT_TRUE(reread) << reread.error().message;
  EXPECT_EQ(reread->manifest.alpha_deg, 12.5);
  EXPECT_EQ(reread->manifest.source["operator_note"], "cloud at 10:14");
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_FALSE(entry.path().filename().string().starts_with(".tmp-")) << entry.path();
  }
}

}  // namespace
}  // namespace glarecam

namespace glarecam {
namespace {

TEST(StackIo, NeverReplacesSomethingThatIsNotAStack) {
  testing::TempDir dir;
  const auto written = testing::writeTestStack(dir / "s");
  StackWriteRequest request;
  request.manifest = written.manifest;
  request.frames = written.frames;
  // A directory holding someone's files, a plain file, the root: all refused, all untouched.
  fs::create_directories(dir / "thesis");
  testing::writeText(dir / "thesis" / "chapter1.tex", "precious");
  testing::writeText(dir / "notes.txt", "precious");
  for (const fs::path& target : {dir / "thesis", dir / "notes.txt", fs::path("/"), fs::path("")}) {
    auto status = writeStack(target, request);
    ASSERT_FALSE(status) << target;
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput) << status.error().message;
  }
  EXPECT_EQ(testing::readText(dir / "thesis" / "chapter1.tex"), "precious");
  EXPECT_EQ(testing::readText(dir / "notes.txt"), "precious");
  // An existing stack is replaced, also when named with a trailing slash.
  EXPECT_TRUE(writeStack((dir / "s").string() + "/", request));
  EXPECT_TRUE(fs::is_regular_file(dir / "s" / "stack.json"));
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_FALSE(entry.path().filename().string().starts_with(".tmp-")) << entry.path();
  }
}

}  // namespace
}  // namespace glarecam
