// libcamera's pure logic through its seam: frames matched to a bracket's steps by their metadata,
// gains in decibels, the tested version, raw layouts and unpacking.
#include "capture/libcamera/request_matching.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace glarecam::capture::libcam {
namespace {

constexpr int kMaxRetries = 3;

// Two steps a factor of four apart, as a bracket would ask; gains at 0 dB.
std::vector<ExposureRequest> twoSteps() { return {{1000.0, 0.0}, {4000.0, 0.0}}; }

FrameMeta frame(double exposure_us, std::optional<double> gain_db = 0.0, std::uint32_t seq = 0) {
  return {exposure_us, gain_db, seq};
}

// Queues every step once, as the backend does when it starts a bracket.
BracketMatcher startedMatcher(std::vector<ExposureRequest> steps, MatchRule rule = {}) {
  BracketMatcher matcher(std::move(steps), rule, kMaxRetries);
  while (const auto step = matcher.nextStep()) matcher.onQueued(*step);
  return matcher;
}

std::optional<std::size_t> filledBy(BracketMatcher& matcher, std::size_t queued_for,
                                    const FrameMeta& meta) {
  auto result = matcher.onFrame(queued_for, meta);
  EXPECT_TRUE(result) << result.error().message;
  return result ? *result : std::nullopt;
}

TEST(BracketMatcher, DiscardsAndCountsFramesStillCarryingTheOldExposure) {
  BracketMatcher matcher = startedMatcher(twoSteps());
  // The sensor applies controls two frames late: both first frames carry the previous 250 µs.
  EXPECT_EQ(filledBy(matcher, 0, frame(250)), std::nullopt);
  EXPECT_EQ(matcher.nextStep(), 0u);  // requeued for the step it was meant for
  matcher.onQueued(0);
  EXPECT_EQ(filledBy(matcher, 1, frame(250)), std::nullopt);
  EXPECT_EQ(matcher.nextStep(), 1u);
  matcher.onQueued(1);
  EXPECT_EQ(filledBy(matcher, 0, frame(1000)), 0u);
  EXPECT_FALSE(matcher.complete());
  EXPECT_EQ(filledBy(matcher, 1, frame(4000)), 1u);
  EXPECT_TRUE(matcher.complete());
  EXPECT_EQ(matcher.retries(0), 1);
  EXPECT_EQ(matcher.retries(1), 1);
}

TEST(BracketMatcher, MatchesByMetadataNotByQueueOrder) {
  BracketMatcher matcher = startedMatcher(twoSteps());
  // The request queued for step 0 came back with step 1's exposure, and the other way round.
  EXPECT_EQ(filledBy(matcher, 0, frame(4000)), 1u);
  EXPECT_EQ(matcher.nextStep(), 0u);  // step 0 is open and nothing is in flight for it
  EXPECT_EQ(filledBy(matcher, 1, frame(1000)), 0u);
  EXPECT_TRUE(matcher.complete());
  EXPECT_EQ(matcher.retries(0), 0);
  EXPECT_EQ(matcher.retries(1), 0);
}

TEST(BracketMatcher, AFilledStepIsNotFilledTwice) {
  BracketMatcher matcher = startedMatcher(twoSteps());
  EXPECT_EQ(filledBy(matcher, 0, frame(1000)), 0u);
  // A second 1000 µs frame (the control not yet switched to 4000 µs) is stale for step 1.
  EXPECT_EQ(filledBy(matcher, 1, frame(1000)), std::nullopt);
  EXPECT_EQ(matcher.retries(1), 1);
  EXPECT_FALSE(matcher.complete());
}

TEST(BracketMatcher, FailsWhenAStepNeverMatchesWithinTheRetryBound) {
  BracketMatcher matcher = startedMatcher({{1000.0, 0.0}});
  for (int i = 0; i < kMaxRetries; ++i) {
    ASSERT_TRUE(matcher.onFrame(0, frame(250, 0.0, 10 + i)));
    matcher.onQueued(0);
  }
  const auto result = matcher.onFrame(0, frame(250, 0.0, 13));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::kHardware);
  EXPECT_NE(result.error().message.find("bracket step 1 of 1 (1000 µs"), std::string::npos)
      << result.error().message;
  EXPECT_NE(result.error().message.find("frame 13 carried 250 µs"), std::string::npos)
      << result.error().message;
}

TEST(BracketMatcher, CancelledOrFailedRequestsCountAgainstTheSameBound) {
  BracketMatcher matcher = startedMatcher({{1000.0, 0.0}});
  for (int i = 0; i < kMaxRetries; ++i) {
    ASSERT_TRUE(matcher.onFailure(0, "request cancelled"));
    EXPECT_EQ(matcher.nextStep(), 0u);
    matcher.onQueued(0);
  }
  EXPECT_EQ(matcher.retries(0), kMaxRetries);
  const auto status = matcher.onFailure(0, "request cancelled");
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().message.find("request cancelled"), std::string::npos);
}

TEST(BracketMatcher, FrameWithoutExposureMetadataIsAnError) {
  BracketMatcher matcher = startedMatcher(twoSteps());
  const auto result = matcher.onFrame(0, {std::nullopt, 0.0, 7});
  ASSERT_FALSE(result);
  EXPECT_NE(result.error().message.find("no ExposureTime"), std::string::npos);
}

TEST(BracketMatcher, AcceptsTheSensorsRounding) {
  // A 30 µs line period: 100 µs requested comes back as 120 µs (four lines).
  MatchRule rule;
  rule.exposure_rounding_us = 30.0;
  EXPECT_TRUE(rule.exposureMatches(100.0, 120.0));
  EXPECT_TRUE(rule.exposureMatches(100.0, 70.0));
  EXPECT_FALSE(rule.exposureMatches(100.0, 135.0));
  // Long exposures: 1 % of the request, here 1 000 µs of 100 000 µs.
  EXPECT_TRUE(rule.exposureMatches(100000.0, 100990.0));
  EXPECT_FALSE(rule.exposureMatches(100000.0, 101500.0));

  BracketMatcher matcher = startedMatcher({{100.0, 0.0}, {400.0, 0.0}}, rule);
  EXPECT_EQ(filledBy(matcher, 0, frame(120)), 0u);
  EXPECT_EQ(filledBy(matcher, 1, frame(390)), 1u);
  EXPECT_TRUE(matcher.complete());
}

TEST(BracketMatcher, AFrameFittingTwoStepsFillsTheNearest) {
  MatchRule rule;
  rule.exposure_rounding_us = 100.0;  // coarse enough that 150 µs fits both 100 and 200 µs
  BracketMatcher matcher = startedMatcher({{100.0, 0.0}, {180.0, 0.0}}, rule);
  // Queued for step 0 but it does fit step 0: the step it was queued for wins.
  EXPECT_EQ(filledBy(matcher, 0, frame(150)), 0u);
  BracketMatcher other = startedMatcher({{100.0, 0.0}, {180.0, 0.0}, {1000.0, 0.0}}, rule);
  // Queued for step 2, which it does not fit: the nearer of steps 0 and 1 in log ratio.
  EXPECT_EQ(filledBy(other, 2, frame(150)), 1u);
}

TEST(BracketMatcher, GainMustMatchWhenTheFrameReportsIt) {
  BracketMatcher matcher = startedMatcher({{1000.0, 12.0}});
  EXPECT_EQ(filledBy(matcher, 0, frame(1000, 0.0)), std::nullopt);  // old gain: stale
  matcher.onQueued(0);
  EXPECT_EQ(filledBy(matcher, 0, frame(1000, 11.6)), 0u);  // gain-code rounding
  BracketMatcher unreported = startedMatcher({{1000.0, 12.0}});
  EXPECT_EQ(filledBy(unreported, 0, frame(1000, std::nullopt)), 0u);
}

TEST(Gain, DecibelsAreAmplitudeDecibels) {
  EXPECT_DOUBLE_EQ(gainDbToLinear(0.0), 1.0);
  EXPECT_NEAR(gainDbToLinear(20.0), 10.0, 1e-12);
  EXPECT_NEAR(gainDbToLinear(6.020599913), 2.0, 1e-9);
  EXPECT_NEAR(gainLinearToDb(4.0), 12.041199827, 1e-9);
  EXPECT_NEAR(gainLinearToDb(gainDbToLinear(-3.5)), -3.5, 1e-12);
}

TEST(LibcameraVersion, AcceptsTheTestedVersionAsDebianReportsIt) {
  EXPECT_TRUE(checkLibcameraVersion("0.0.3"));
  EXPECT_TRUE(checkLibcameraVersion("v0.0.3"));  // what Debian bookworm's 0.0.3-6 reports
  EXPECT_TRUE(checkLibcameraVersion("v0.0.3+65-1a2b3c4d"));
  EXPECT_TRUE(checkLibcameraVersion("0.0.3-6"));
  const auto parsed = parseLibcameraVersion("v0.0.3+65-1a2b3c4d-dirty");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(*parsed, (LibcameraVersion{0, 0, 3}));
}

TEST(LibcameraVersion, RefusesUntestedAndUnreadableVersions) {
  const auto newer = checkLibcameraVersion("v0.1.0");
  ASSERT_FALSE(newer);
  EXPECT_EQ(newer.error().message, "libcamera v0.1.0 is not a tested version (tested: 0.0.3)");
  EXPECT_FALSE(checkLibcameraVersion("0.0.4"));
  for (const char* garbage : {"", "v", "abc", "0.0", "0.0.", "0..3", "0.0.3x", "1.2.3.4", "-0.0.3",
                              "0.-0.3", "v 0.0.3", "0.0.-3"}) {
    EXPECT_FALSE(parseLibcameraVersion(garbage)) << garbage;
    EXPECT_FALSE(checkLibcameraVersion(garbage)) << garbage;
  }
}

TEST(RawLayout, ParsesLibcameraFormatNames) {
  const auto mono10 = parseRawLayout("R10_CSI2P");
  ASSERT_TRUE(mono10);
  EXPECT_EQ(mono10->packing, Packing::kCsi2Packed);
  EXPECT_EQ(mono10->depth_bits, 10);
  EXPECT_EQ(mono10->genicamName(), "Mono10");
  const auto bayer12 = parseRawLayout("SRGGB12");
  ASSERT_TRUE(bayer12);
  EXPECT_EQ(bayer12->packing, Packing::kLittleEndian16);
  EXPECT_EQ(bayer12->genicamName(), "BayerRG12");
  EXPECT_EQ(parseRawLayout("R8")->packing, Packing::k8Bit);
  EXPECT_EQ(parseRawLayout("SBGGR12_CSI2P")->genicamName(), "BayerBG12");
  EXPECT_EQ(parseRawLayout("SGRBG16")->depth_bits, 16);
  for (const char* unsupported : {"SBGGR10_IPU3", "YUYV", "R14_CSI2P", "R8_CSI2P", "R", "SXXXX10",
                                  "R10x", "NV12", "R16_CSI2P"}) {
    EXPECT_FALSE(parseRawLayout(unsupported)) << unsupported;
  }
  // Deeper first, mono before Bayer at equal depth.
  EXPECT_GT(parseRawLayout("SRGGB12")->preference(), parseRawLayout("R10")->preference());
  EXPECT_GT(parseRawLayout("R12_CSI2P")->preference(), parseRawLayout("SRGGB12")->preference());
}

TEST(Unpack, Csi2Raw10FourPixelsInFiveBytes) {
  // Pixels 0x201, 0x0FE, 0x3FF, 0x000: MSBs 0x80 0x3F 0xFF 0x00, then LSBs 01 10 11 00 packed
  // from bit 0 up: 0b00'11'10'01 = 0x39.
  const std::array<std::uint8_t, 5> bytes{0x80, 0x3F, 0xFF, 0x00, 0x39};
  const auto image = unpackRaw(bytes, 4, 1, bytes.size(), *parseRawLayout("R10_CSI2P"));
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->at(0, 0), 0x201);
  EXPECT_EQ(image->at(1, 0), 0x0FE);
  EXPECT_EQ(image->at(2, 0), 0x3FF);
  EXPECT_EQ(image->at(3, 0), 0x000);
}

TEST(Unpack, Csi2Raw10PartialGroupAndPaddedStride) {
  // Width 5: two groups (10 bytes) per row, stride 12; second row pixel 4 = 0x155
  // (MSBs 0x55, LSBs 01 in bits 1:0 of the second group's fifth byte).
  std::vector<std::uint8_t> bytes(12 + 10, 0);
  bytes[12 + 5] = 0x55;
  bytes[12 + 9] = 0x01;
  const auto image = unpackRaw(bytes, 5, 2, 12, *parseRawLayout("SRGGB10_CSI2P"));
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->at(4, 1), 0x155);
  EXPECT_EQ(image->at(0, 1), 0);
}

TEST(Unpack, Csi2Raw12TwoPixelsInThreeBytes) {
  // Pixels 0xABC, 0x123: MSBs 0xAB 0x12, then LSBs 0xC (bits 3:0) and 0x3 (bits 7:4) = 0x3C.
  // Second row (stride 4, one pad byte): 0xFFF, 0x001 -> 0xFF 0x00 0x1F.
  const std::array<std::uint8_t, 7> bytes{0xAB, 0x12, 0x3C, 0xEE, 0xFF, 0x00, 0x1F};
  const auto image = unpackRaw(bytes, 2, 2, 4, *parseRawLayout("R12_CSI2P"));
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->at(0, 0), 0xABC);
  EXPECT_EQ(image->at(1, 0), 0x123);
  EXPECT_EQ(image->at(0, 1), 0xFFF);
  EXPECT_EQ(image->at(1, 1), 0x001);
}

TEST(Unpack, LittleEndianContainersAndEightBit) {
  // R12 in 16-bit little-endian containers: 0x0ABC; stray high bits above bit 11 are masked.
  const std::array<std::uint8_t, 4> le{0xBC, 0x0A, 0x34, 0xF2};
  const auto deep = unpackRaw(le, 2, 1, 4, *parseRawLayout("R12"));
  ASSERT_TRUE(deep);
  EXPECT_EQ(deep->at(0, 0), 0x0ABC);
  EXPECT_EQ(deep->at(1, 0), 0x0234);
  const std::array<std::uint8_t, 2> eight{0x07, 0xF0};
  const auto shallow = unpackRaw(eight, 2, 1, 2, *parseRawLayout("R8"));
  ASSERT_TRUE(shallow);
  EXPECT_EQ(shallow->at(1, 0), 0xF0);
}

TEST(Unpack, RefusesShortBuffersAndStrides) {
  const std::array<std::uint8_t, 4> bytes{};
  EXPECT_FALSE(unpackRaw(bytes, 4, 1, 5, *parseRawLayout("R10_CSI2P")));  // needs 5 bytes
  EXPECT_FALSE(unpackRaw(bytes, 4, 1, 4, *parseRawLayout("R10_CSI2P")));  // stride < row
  EXPECT_FALSE(unpackRaw(bytes, 0, 1, 4, *parseRawLayout("R8")));
}

}  // namespace
}  // namespace glarecam::capture::libcam
