#include "render/number_format.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace glarecam::render {
namespace {

TEST(NumberFormat, PlainIsPrintfsG) {
  EXPECT_EQ(formatPlain(10), "10");
  EXPECT_EQ(formatPlain(0.5), "0.5");
  EXPECT_EQ(formatPlain(0.15000000000000002), "0.15");
  EXPECT_EQ(formatPlain(1e7), "1e+07");
  EXPECT_EQ(formatPlain(-2.5), "-2.5");
}

TEST(NumberFormat, SignificantDigits) {
  EXPECT_EQ(formatSignificant(1.23456, 4), "1.235");
  EXPECT_EQ(formatSignificant(2.5e-5, 4), "2.5e-05");
  EXPECT_EQ(formatSignificant(0.0123456, 2), "0.012");
}

// GUM 7.2.6: the value to the uncertainty's first significant digit, its second when that is 1.
TEST(NumberFormat, ToItsOwnUncertainty) {
  EXPECT_EQ(formatToUncertainty(4.99985, 0.05, 1), "5.00");
  EXPECT_EQ(formatToUncertainty(4.99985, 0.12, 1), "5.00");
  EXPECT_EQ(formatToUncertainty(4.99985, 0.3, 1), "5.0");
  EXPECT_EQ(formatToUncertainty(42.3456, 0.012, 1), "42.346");
  EXPECT_EQ(formatToUncertainty(42.3456, 2.0, 1), "42");
  EXPECT_EQ(formatToUncertainty(42.3456, 30.0, 1), "42");
  EXPECT_EQ(formatToUncertainty(4.99985, std::nullopt, 1), "5.0");
  EXPECT_EQ(formatToUncertainty(4.99985, 0.0, 1), "5.0");  // no usable uncertainty
  EXPECT_EQ(formatToUncertainty(5.0, std::nan(""), 1), "5.0");
  EXPECT_EQ(formatToUncertainty(5.0, 1e-12, 1), "5.000000");  // capped
}

TEST(NumberFormat, FixedOrNoValue) {
  EXPECT_EQ(formatFixed(4.857826, 2), "4.86");
  EXPECT_EQ(formatFixed(7.0, 1), "7.0");
  EXPECT_EQ(formatFixed(std::nullopt, 2), kNoValue);
  EXPECT_EQ(std::string(kNoValue), "\u2013");
}

TEST(NumberFormat, GroupedWritesLargeValuesOutWithThinSpaces) {
  EXPECT_EQ(formatGrouped(47'500'000, 4), "47\u2009500\u2009000");
  EXPECT_EQ(formatGrouped(59'713'400, 4), "59\u2009710\u2009000");  // four significant digits
  EXPECT_EQ(formatGrouped(30'000, 4), "30\u2009000");
  EXPECT_EQ(formatGrouped(1'000, 4), "1\u2009000");
  EXPECT_EQ(formatGrouped(536'709.5, 4), "536\u2009700");
  EXPECT_EQ(formatGrouped(-1'234, 4), "-1\u2009234");
  EXPECT_EQ(formatGrouped(123'456, 2), "120\u2009000");
}

TEST(NumberFormat, GroupedSmallValuesAndMissingOnes) {
  EXPECT_EQ(formatGrouped(999, 4), "999");
  EXPECT_EQ(formatGrouped(0.5, 4), "0.5");
  EXPECT_EQ(formatGrouped(12.3456, 4), "12.35");
  EXPECT_EQ(formatGrouped(std::numeric_limits<double>::quiet_NaN(), 4), kNoValue);
  EXPECT_EQ(formatGrouped(std::numeric_limits<double>::infinity(), 4), kNoValue);
  EXPECT_EQ(formatGrouped(-std::numeric_limits<double>::infinity(), 4), kNoValue);
}

TEST(NumberFormat, PowersOfTenInSuperscript) {
  EXPECT_EQ(formatPowerOfTen(0), "10\u2070");
  EXPECT_EQ(formatPowerOfTen(5), "10\u2075");
  EXPECT_EQ(formatPowerOfTen(12), "10\u00b9\u00b2");
  EXPECT_EQ(formatPowerOfTen(-3), "10\u207b\u00b3");
}

TEST(NumberFormat, SiPrefixes) {
  EXPECT_EQ(formatSiPrefixed(1), "1");
  EXPECT_EQ(formatSiPrefixed(500), "500");
  EXPECT_EQ(formatSiPrefixed(1'000), "1k");
  EXPECT_EQ(formatSiPrefixed(20'000), "20k");
  EXPECT_EQ(formatSiPrefixed(1'600), "2k");
  EXPECT_EQ(formatSiPrefixed(1e6), "1M");
  EXPECT_EQ(formatSiPrefixed(5e9), "5G");
  EXPECT_EQ(formatSiPrefixed(2e12), "2T");
  EXPECT_EQ(formatSiPrefixed(5e15), "5000T");  // no prefix beyond T
  EXPECT_EQ(formatSiPrefixed(0.05), "0.05");
  EXPECT_EQ(formatSiPrefixed(0.2), "0.2");
  EXPECT_EQ(formatSiPrefixed(1e-5), "1e-05");
}

}  // namespace
}  // namespace glarecam::render
