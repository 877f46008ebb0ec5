// Pages written as files: a PDF of several pages, each drawn by its own drawing in order on a
// fresh canvas, written atomically; no pages refused with nothing written; a drawing that fails
// names its page and leaves what was there; an unwritable path a kIo error naming it.
#include "render/page_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "render/canvas.h"
#include "render/colour.h"
#include "render/text.h"
#include "support/test_support.h"

namespace glarecam::render {
namespace {

namespace fs = std::filesystem;

constexpr PageSize kSmallPage{200, 100};

TEST(PageOutput, APdfOfSeveralPagesDrawsEachInOrderOnAFreshCanvas) {
  glarecam::testing::TempDir dir;
  std::vector<int> drawn;
  std::vector<PageDrawing> pages;
  for (int i = 0; i < 3; ++i) {
    pages.push_back([&drawn, i](Canvas& canvas) {
      // A page that left its transformation behind would shift the next page's drawing.
      canvas.translate(50, 50);
      paint(canvas, kWhite);
      drawText(canvas, {10, 20}, "page " + std::to_string(i + 1), {{.size = 12}});
      drawn.push_back(i);
    });
  }
  ASSERT_TRUE(writePdfPages(dir / "doc.pdf", kSmallPage, pages, {"three pages", "test"}));
  EXPECT_EQ(drawn, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(glarecam::testing::readText(dir / "doc.pdf").rfind("%PDF-", 0), 0u);
  EXPECT_EQ(glarecam::testing::pdfPageCount(dir / "doc.pdf"), 3);
  EXPECT_TRUE(glarecam::testing::noTemporaryFiles(dir.path()));
  // One page is a document of one page, as writePdfPage writes it.
  ASSERT_TRUE(writePdfPages(dir / "one.pdf", kSmallPage, {pages[0]}, {}));
  ASSERT_TRUE(writePdfPage(dir / "page.pdf", kSmallPage, pages[0], {}));
  EXPECT_EQ(glarecam::testing::pdfPageCount(dir / "one.pdf"), 1);
  EXPECT_EQ(glarecam::testing::pdfPageCount(dir / "page.pdf"), 1);
}

TEST(PageOutput, NoPagesIsRefusedWithNothingWritten) {
  glarecam::testing::TempDir dir;
  const auto status = writePdfPages(dir / "doc.pdf", kSmallPage, {}, {});
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kBadInput);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(PageOutput, AFailingDrawingNamesItsPageAndLeavesWhatWasThere) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "doc.pdf", "the old document");
  const PageDrawing fine = [](Canvas& canvas) { paint(canvas, kWhite); };
  const PageDrawing broken = [](Canvas& canvas) {
    canvas.scale(0, 0);  // a singular matrix: Cairo's error state
    paint(canvas, kWhite);
  };
  const auto status = writePdfPages(dir / "doc.pdf", kSmallPage, {fine, broken, fine}, {});
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kIo);
  EXPECT_NE(status.error().message.find((dir / "doc.pdf").string()), std::string::npos)
      << status.error().message;
  EXPECT_NE(status.error().message.find("page 2 of 3"), std::string::npos)
      << status.error().message;
  EXPECT_EQ(glarecam::testing::readText(dir / "doc.pdf"), "the old document");
  EXPECT_TRUE(glarecam::testing::noTemporaryFiles(dir.path()));
}

TEST(PageOutput, AnUnwritablePathIsAnErrorNamingIt) {
  glarecam::testing::TempDir dir;
  glarecam::testing::writeText(dir / "file", "not a directory");
  const PageDrawing fine = [](Canvas& canvas) { paint(canvas, kWhite); };
  const auto status = writePdfPages(dir / "file" / "doc.pdf", kSmallPage, {fine}, {});
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().code, ErrorCode::kIo);
  EXPECT_NE(status.error().message.find((dir / "file" / "doc.pdf").string()), std::string::npos)
      << status.error().message;
}

}  // namespace
}  // namespace glarecam::render
