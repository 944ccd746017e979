// The reports of a grading: Gradescope's results.json (its autograder specification:
// score, and per test name, score, max_score, output, visibility), JUnit XML for CI
// systems and GitHub Classroom, a page for the student, and the terminal's table.
#include <cstdio>

#include "grading/grading.hpp"
#include "renderer/util/markup.hpp"

namespace hsr::grading {
namespace {

std::string points(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string seconds(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}

std::string title(const GradeReport& report) {
  return "hsr grade: exercise " + std::to_string(report.exercise) + ", " + report.submission;
}

}  // namespace

std::string gradescopeJson(const GradeReport& report) {
  std::string json = "{\n  \"score\": " + points(report.score()) + ",\n";
  json += "  \"output\": " + jsonString(summary(report)) + ",\n";
  json += "  \"visibility\": \"visible\",\n  \"stdout_visibility\": \"hidden\",\n  \"tests\": [\n";
  json += "    {\"name\": \"make build\", \"score\": 0, \"max_score\": 0, \"status\": " +
          std::string(report.built ? "\"passed\"" : "\"failed\"") + ", \"output\": " + jsonString(report.buildOutput) +
          ", \"visibility\": \"visible\"}";
  for (const TestResult& test : report.tests) {
    json += ",\n    {\"name\": " + jsonString(test.name) + ", \"score\": " + points(test.score) +
            ", \"max_score\": " + points(test.maxScore) + ", \"status\": " + (test.passed ? "\"passed\"" : "\"failed\"") +
            ", \"output\": " + jsonString(test.output) + ", \"visibility\": " +
            // Hidden tests' results show once the instructor publishes the grades.
            (test.hidden ? "\"after_published\"" : "\"visible\"") + "}";
  }
  return json + "\n  ]\n}\n";
}

std::string junitXml(const GradeReport& report) {
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += "<testsuite name=\"" + escapedMarkup(title(report)) + "\" tests=\"" + std::to_string(report.tests.size()) +
         "\" failures=\"" + std::to_string(report.failed()) + "\">\n";
  for (const TestResult& test : report.tests) {
    xml += "  <testcase classname=\"exercise" + std::to_string(report.exercise) + "." + escapedMarkup(test.skill) + "\" name=\"" +
           escapedMarkup(test.name) + "\" time=\"" + seconds(test.seconds) + "\">";
    if (!test.passed) {
      const std::string firstLine = test.output.substr(0, test.output.find('\n'));
      xml += "\n    <failure message=\"" + escapedMarkup(firstLine) + "\">" + escapedMarkup(test.output) + "</failure>\n  ";
    }
    xml += "</testcase>\n";
  }
  return xml + "</testsuite>\n";
}

std::string feedbackPage(const GradeReport& report) {
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" + escapedMarkup(title(report)) +
                     "</title>\n<style>\nbody{font:15px/1.45 system-ui,sans-serif;margin:2em auto;max-width:60em;padding:0 1em}\n"
                     "table{border-collapse:collapse}td,th{padding:.2em .6em;text-align:left;border-bottom:1px solid #ddd}\n"
                     ".passed{color:#15703a}.failed{color:#b3261e}pre{white-space:pre-wrap;background:#f6f6f6;padding:.6em}\n"
                     "img{image-rendering:pixelated;width:min(100%,640px);border:1px solid #ccc}\n</style></head><body>\n";
  html += "<h1>" + escapedMarkup(title(report)) + "</h1>\n<p id=\"score\">Score: " + points(report.score()) + " of " +
          points(report.maxScore()) + "; " + std::to_string(report.failed()) + " of " + std::to_string(report.tests.size()) +
          " tests failed.</p>\n";
  html += "<table><thead><tr><th>test</th><th>hard case</th><th>result</th><th>score</th></tr></thead><tbody>\n";
  for (const TestResult& test : report.tests)
    html += "<tr><td><a href=\"#" + escapedMarkup(test.name) + "\">" + escapedMarkup(test.name) + "</a></td><td>" +
            escapedMarkup(test.skill) + "</td><td class=\"" + (test.passed ? "passed\">passed" : "failed\">failed") + "</td><td>" +
            points(test.score) + " / " + points(test.maxScore) + "</td></tr>\n";
  html += "</tbody></table>\n<h2>make build</h2>\n<pre>" + escapedMarkup(report.buildOutput) + "</pre>\n";
  for (const TestResult& test : report.tests) {
    html += "<h2 id=\"" + escapedMarkup(test.name) + "\" class=\"" + (test.passed ? "passed" : "failed") + "\">" +
            escapedMarkup(test.name) + ": " + (test.passed ? "passed" : "failed") + "</h2>\n<pre>" + escapedMarkup(test.output) +
            "</pre>\n";
    if (!test.heatMap.empty())
      html += "<img src=\"" + escapedMarkup(test.heatMap) + "\" alt=\"where " + escapedMarkup(test.name) +
              " is wrong: wrong pixels red, within the tolerances yellow, certified ties blue\">\n";
  }
  return html + "</body></html>\n";
}

std::string summary(const GradeReport& report) {
  if (!report.built)
    return report.buildOutput + "score 0 of " + points(report.maxScore()) + ": the submission did not build, so no test ran\n";
  std::string text;
  for (const TestResult& test : report.tests) {
    char line[160];
    std::snprintf(line, sizeof line, "%-6s %-36s %s / %s  %s\n", test.passed ? "passed" : "FAILED", test.name.c_str(),
                  points(test.score).c_str(), points(test.maxScore).c_str(), test.output.substr(0, test.output.find('\n')).c_str());
    text += line;
  }
  text += "score " + points(report.score()) + " of " + points(report.maxScore()) + "\n";
  return text;
}

}  // namespace hsr::grading
