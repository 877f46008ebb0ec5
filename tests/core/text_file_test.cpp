#include "core/text_file.h"

#include <gtest/gtest.h>

#include <fstream>

#include "support/test_support.h"

namespace glarecam {
namespace {

TEST(TextFile, ReadsAWholeFileAndRefusesWhatItCannot) {
  testing::TempDir dir;
  const auto path = dir / "a.txt";
  {
    std::ofstream out(path, std::ios::binary);
    out << "line one\nline two\r\n" << std::string(3000, 'x');
  }
  auto text = readTextFile(path);
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_EQ(text->size(), 19u + 3000u);
  EXPECT_EQ(text->substr(0, 9), "line one\n");

  // Larger than allowed: the file, its size and what it is, in one line.
  const auto big = readTextFile(path, 1000, "a test file");
  ASSERT_FALSE(big);
  EXPECT_EQ(big.error().code, ErrorCode::kBadInput);
  EXPECT_NE(big.error().message.find("a test file may have"), std::string::npos);
  EXPECT_NE(big.error().message.find(path.string()), std::string::npos);

  for (const auto& bad : {dir / "none.txt", dir.path()}) {
    const auto missing = readTextFile(bad);
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, ErrorCode::kBadInput);
    EXPECT_NE(missing.error().message.find("missing or not a regular file"), std::string::npos);
  }
  std::ofstream(dir / "empty.txt");
  EXPECT_EQ(readTextFile(dir / "empty.txt").value_or("?"), "");
}

}  // namespace
}  // namespace glarecam
