// SHA-256 against the FIPS 180-4 examples (NIST CSRC "Examples with Intermediate Values") and the
// NIST CAVP long message, pieces fed in any split, and a file.
#include "core/sha256.h"

#include <gtest/gtest.h>

#include <string>

#include "support/test_support.h"

namespace glarecam {
namespace {

TEST(Sha256, FipsExamples) {
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // 448 bits: the padding needs a second block.
  EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256Hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, PiecesInAnySplitGiveTheSameDigest) {
  const std::string message = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  for (std::size_t split = 0; split <= message.size(); split += 7) {
    Sha256 hash;
    hash.update(std::string_view(message).substr(0, split));
    hash.update(std::string_view(message).substr(split));
    EXPECT_EQ(hash.hexDigest(), sha256Hex(message)) << split;
  }
}

TEST(Sha256, OfAFileAndOfAMissingOne) {
  testing::TempDir dir;
  testing::writeText(dir / "calibration.json", "abc");
  const auto digest = sha256OfFile(dir / "calibration.json");
  ASSERT_TRUE(digest) << digest.error().message;
  EXPECT_EQ(*digest, sha256Hex("abc"));
  const auto missing = sha256OfFile(dir / "none.json");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("none.json: cannot read"), std::string::npos);
}

}  // namespace
}  // namespace glarecam
