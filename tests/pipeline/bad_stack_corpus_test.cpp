// Every stack under tests/data/bad-stacks/ is refused by `glarecam process`'s library call with
// a kBadInput error: one line, naming a file of the stack, containing the case's expect.txt,
// and no output written. Also run under AddressSanitizer + UBSan (label "sanitized"), so
// "never a crash" is checked, not assumed.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "pipeline/process_stack.h"
#include "support/test_support.h"

namespace glarecam {
namespace {
namespace fs = std::filesystem;

std::vector<fs::path> corpusCases() {
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(testing::testDataDir() / "bad-stacks")) {
    if (entry.is_directory()) cases.push_back(entry.path());
  }
  std::sort(cases.begin(), cases.end());
  return cases;
}

std::string trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

class BadStackCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(BadStackCorpus, IsRefusedWithOneClearLine) {
  const fs::path stack = GetParam();
  const std::string expected = trim(testing::readText(stack / "expect.txt"));
  ASSERT_FALSE(expected.empty()) << stack;
  testing::TempDir out;
  pipeline::ProcessOptions options;
  options.output_directory = out / "result";
  options.show_progress = false;
  auto result = pipeline::processStack(stack, options);
  ASSERT_FALSE(result.has_value()) << stack << " was accepted";
  EXPECT_FALSE(fs::exists(out / "result" / "result.json"));
  const Error& error = result.error();
  EXPECT_EQ(error.code, ErrorCode::kBadInput) << error.message;
  EXPECT_NE(error.message.find(expected), std::string::npos)
      << "message: " << error.message << "\nexpected: " << expected;
  EXPECT_EQ(error.message.find('\n'), std::string::npos) << "not one line: " << error.message;
  EXPECT_NE(error.message.find(stack.filename().string()), std::string::npos)
      << "does not name the stack's file: " << error.message;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadStackCorpus, ::testing::ValuesIn(corpusCases()),
                         [](const ::testing::TestParamInfo<fs::path>& info) {
                           std::string name = info.param.filename().string();
                           std::replace_if(
                               name.begin(), name.end(),
                               [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
                               '_');
                           return name;
                         });

TEST(BadStackCorpus, CoversTheListOfStackFormatMd) {
  // The cases the issue and docs/stack-format.md name; the corpus may hold more.
  const char* required[] = {"missing-manifest",
                            "invalid-json",
                            "wrong-schema",
                            "empty-frame-list",
                            "missing-frame",
                            "truncated-png",
                            "zero-byte-png",
                            "colour-png",
                            "frame-size-mismatch",
                            "exposure-zero",
                            "exposure-not-a-number",
                            "black-at-saturation",
                            "fx-zero",
                            "frame-path-dotdot",
                            "frame-path-absolute",
                            "calibration-path-missing",
                            "flat-field-escapes"};
  for (const char* name : required)
    EXPECT_TRUE(fs::is_directory(testing::testDataDir() / "bad-stacks" / name)) << name;
}

}  // namespace
}  // namespace glarecam
