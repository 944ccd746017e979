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
  EXPECT_NE(page.find(R"({"command":"hsr why a\u003c/script>.toml","width":64,"height":48,"panelGap":6,"host":false})"), std::string::npos);
  EXPECT_NE(page.find(R"(caption \u003c/script>\u003cscript>alert(1)\u003c/script> & \"quotes\")"), std::string::npos);
  EXPECT_NE(page.find("<title>Steps: hsr render a&lt;b&gt;.toml</title>"), std::string::npos);
}

// Inside the browser edition's page, which answers a click itself: no links to files the
// page does not have, and the click is posted to the page around it, not made a command.
TEST(StepsPage, InsideTheBrowserEditionAClickIsAnsweredByThePageAroundIt) {
  const SourceExcerpt source = sourceExcerpt(SourceLocation::current());
  const std::vector<PageStep> steps{{"blob:step-1", "a step", source}};
  const std::string written = stepsPage("t", steps, {"hsr why t.toml", 64, 48});
  const std::string hosted = stepsPage("t", steps, {"hsr why", 64, 48, true});
  EXPECT_NE(written.find("href=\"steps.gif\""), std::string::npos);
  EXPECT_EQ(hosted.find("href=\"steps.gif\""), std::string::npos);
  EXPECT_EQ(hosted.find("captions.txt"), std::string::npos);
  EXPECT_NE(hosted.find(R"("host":true})"), std::string::npos);
  EXPECT_NE(hosted.find("click a pixel for its history up to the step."), std::string::npos);
  EXPECT_NE(written.find("click a pixel for the command that shows its history up to the step."), std::string::npos);
}

// The page's steps share one excerpt per recording place, read once.
TEST(StepsPage, StepsRecordedAtOnePlaceShareItsExcerpt) {
  const SourceLocation here = SourceLocation::current();
  const SourceLocation there = SourceLocation::current();
  const std::vector<PageStep> steps = pageSteps({{"first", here}, {"second", here}, {"third", there}}, {"a.png", "b.png", "c.png"});
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[1].picture, "b.png");
  EXPECT_EQ(steps[2].caption, "third");
  EXPECT_EQ(steps[0].source.line, steps[1].source.line);
  EXPECT_EQ(steps[2].source.line, steps[0].source.line + 1);
  EXPECT_FALSE(steps[0].source.lines.empty());
}

// A header included through a build folder's view of the sources (cmake/layers.cmake) is
// the suite's own file, where the view's links cannot be followed too (the browser
// edition's file system holds none): BUILD/include-views/TARGET/PATH is PATH.
TEST(StepsPage, AHeaderSeenThroughAViewIsTheSuitesFile) {
#line 1 "/nowhere/include-views/hsr_renderer_steps/renderer/steps/steps.hpp"
  const SourceLocation inView = SourceLocation::current();
#line 127 "tests/renderer/steps/steps_page_test.cpp"
  const SourceExcerpt excerpt = sourceExcerpt(inView);
  EXPECT_EQ(excerpt.file, "renderer/steps/steps.hpp");
  ASSERT_FALSE(excerpt.lines.empty());
  EXPECT_EQ(excerpt.lines[0].rfind("// Steps:", 0), 0u) << excerpt.lines[0];
}

}  // namespace
}  // namespace hsr
