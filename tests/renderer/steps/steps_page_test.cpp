// The steps page (renderer/steps/steps_page.hpp): the code shown beside a step is the
// statement that recorded it, found from what SourceLocation captured, and the
// page holds any caption as text.
#include <gtest/gtest.h>

#include <string>

#include "renderer/steps/steps_page.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

// A recording call as algorithms write one: over several lines, its arguments holding
// ";" and "//" in strings, a comment at the end of one line.
SourceLocation recordedHere(const std::string&, int, SourceLocation where = SourceLocation::current()) { return where; }

SourceLocation aCallOverThreeLines() {
  const int unused = 0;  // a statement before it, ending with ";" then a comment
  return recordedHere("step 2; a caption with a semicolon // and slashes, "
                      "over two lines",  // a comment
                      unused);
}

TEST(StepsPage, TheExcerptMarksTheWholeRecordingStatementFromTheTopOfItsFunction) {
  const SourceLocation where = aCallOverThreeLines();
  const SourceExcerpt excerpt = sourceExcerpt(where);
  EXPECT_EQ(excerpt.file, "tests/renderer/steps/steps_page_test.cpp");
  ASSERT_FALSE(excerpt.lines.empty());
  const auto lineAt = [&](int number) { return excerpt.lines.at(std::size_t(number - excerpt.firstLine)); };
  // From the function's first line to the end of the statement and two lines more.
  EXPECT_EQ(lineAt(excerpt.firstLine), "SourceLocation aCallOverThreeLines() {");
  EXPECT_EQ(lineAt(excerpt.line).find("return recordedHere("), 2u) << lineAt(excerpt.line);
  EXPECT_EQ(excerpt.markedTo, excerpt.line + 2);
  EXPECT_NE(lineAt(excerpt.markedTo).find("unused);"), std::string::npos);
  EXPECT_EQ(excerpt.firstLine + int(excerpt.lines.size()) - 1, excerpt.markedTo + 2);
  EXPECT_NE(excerpt.function.find("aCallOverThreeLines"), std::string::npos) << excerpt.function;
}

TEST(StepsPage, ACallFarIntoALongFunctionShowsAtMostTheLinesBeforeIt) {
  // This test's body is long enough: its own call is more than kLinesBefore lines down.
  int a = 0;
  a += 1;
  a += 2;
  a += 3;
  a += 4;
  a += 5;
  a += 6;
  a += 7;
  a += 8;
  a += 9;
  a += 10;
  a += 11;
  a += 12;
  a += 13;
  a += 14;
  a += 15;
  a += 16;
  a += 17;
  a += 18;
  a += 19;
  a += 20;
  a += 21;
  a += 22;
  a += 23;
  const SourceExcerpt excerpt = sourceExcerpt(recordedHere("caption", a));
  EXPECT_EQ(excerpt.line - excerpt.firstLine, kLinesBefore);
  EXPECT_EQ(excerpt.markedTo, excerpt.line);
}

TEST(StepsPage, AFileThatIsNotThereIsNamedWithoutLines) {
  const SourceExcerpt moved = sourceExcerpt(SourceLocation::current(), test::outputPath("no-such-folder"));
  EXPECT_TRUE(moved.lines.empty());
  EXPECT_NE(moved.file.find("steps_page_test.cpp"), std::string::npos);
  EXPECT_GT(moved.line, 0);
}

TEST(StepsPage, CaptionsAndCodeWithMarkupStayText) {
  SourceExcerpt source = sourceExcerpt(SourceLocation::current());
  source.lines.push_back("  const char* s = \"</script><b>\";");
  const std::string page = stepsPage("hsr render a<b>.toml", {{"step-0001.png", "caption </script><script>alert(1)</script> & \"quotes\"", source}},
                                     {"hsr why a</script>.toml", 64, 48});
  // The one script of the page's own and its three JSON blocks, nothing more closed early.
  std::size_t closings = 0;
  for (std::size_t at = page.find("</script>"); at != std::string::npos; at = page.find("</script>", at + 1)) ++closings;
  EXPECT_EQ(closings, 4u);
  EXPECT_NE(page.find(R"({"command":"hsr why a\u003c/script>.toml","width":64,"height":48,"panelGap":6})"), std::string::npos);
  EXPECT_NE(page.find(R"(caption \u003c/script>\u003cscript>alert(1)\u003c/script> & \"quotes\")"), std::string::npos);
  EXPECT_NE(page.find("<title>Steps: hsr render a&lt;b&gt;.toml</title>"), std::string::npos);
}

}  // namespace
}  // namespace hsr
