#include "studies/report.hpp"

#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "renderer/image/frame.hpp"
#include "renderer/util/markup.hpp"
#include "studies/report_gallery.hpp"
#include "studies/results.hpp"

namespace hsr::studies {
namespace {

// The rows of a CSV as results.cpp writes it: fields separated by commas, a field with a
// comma, quote or line break in double quotes, a quote inside doubled.
std::vector<std::vector<std::string>> parsedCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(std::move(field));
      field.clear();
    } else if (c == '\n') {
      row.push_back(std::move(field));
      field.clear();
      rows.push_back(std::move(row));
      row.clear();
    } else {
      field += c;
    }
  }
  if (!field.empty() || !row.empty()) row.push_back(std::move(field)), rows.push_back(std::move(row));
  return rows;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// A CSV as a table. hsr compare's and hsr sweep's (`explained`: their columns are
// results.hpp's) lead with the columns a reader compares first (algorithm, knobs,
// visibility time, error, wrong pixels; a sweep's knobs): the others are folded until
// asked for, each heading says what its column means when pointed at, and a list under
// the table says it for every column. A study's columns are its own.
std::string tableHtml(const std::vector<std::vector<std::string>>& rows, bool explained) {
  if (rows.empty()) return "<p>(empty)</p>\n";
  const std::vector<std::string>& columns = rows.front();
  const auto meaningOf = [&](const std::string& name) { return explained ? columnMeaning(name) : nullptr; };
  std::vector<bool> folded;
  for (const std::string& name : columns) folded.push_back(meaningOf(name) && !meaningOf(name)->key);
  const auto cellClass = [&](std::size_t c) { return c < folded.size() && folded[c] ? std::string(" class=\"more\"") : std::string(); };
  const std::size_t foldedCount = std::size_t(std::count(folded.begin(), folded.end(), true));
  std::string html;
  if (foldedCount > 0)
    html += "<label class=\"columns\"><input type=\"checkbox\" onchange=\"this.parentNode.nextElementSibling.firstChild.classList.toggle('all', this.checked)\"> "
            "show the other " + std::to_string(foldedCount) + " columns</label>\n";
  html += "<div class=\"scroll\"><table class=\"sortable\">\n<thead><tr>";
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const ColumnMeaning* meaning = meaningOf(columns[c]);
    html += "<th" + cellClass(c) + " title=\"" + escapedMarkup(meaning ? meaning->meaning + " (click to sort)" : "sort by " + columns[c]) + "\">" +
            escapedMarkup(columns[c]) + "</th>";
  }
  html += "</tr></thead>\n<tbody>\n";
  for (std::size_t r = 1; r < rows.size(); ++r) {
    html += "<tr>";
    for (std::size_t c = 0; c < rows[r].size(); ++c) html += "<td" + cellClass(c) + ">" + escapedMarkup(rows[r][c]) + "</td>";
    html += "</tr>\n";
  }
  html += "</tbody></table></div>\n";
  if (!explained) return html;
  html += "<details class=\"meanings\"><summary>What the columns mean</summary><dl>\n";
  for (const std::string& name : columns)
    if (const ColumnMeaning* meaning = meaningOf(name)) html += "<dt>" + escapedMarkup(name) + "</dt><dd>" + escapedMarkup(meaning->meaning) + "</dd>\n";
  return html + "</dl></details>\n";
}

// Sorting: a click on a column's heading sorts its table by it, ascending then
// descending; numbers as numbers, the rest as text. "#sort=COLUMN" (or
// "#sort=COLUMN:desc") in the address sorts every table with that column on load.
constexpr const char* kScript = R"(
function sortTable(table, column, descending) {
  const body = table.tBodies[0];
  const rows = Array.from(body.rows);
  const key = row => row.cells[column] ? row.cells[column].textContent : "";
  const number = text => text.trim() !== "" && !isNaN(Number(text)) ? Number(text) : null;
  rows.sort((a, b) => {
    const x = key(a), y = key(b), nx = number(x), ny = number(y);
    const order = nx !== null && ny !== null ? nx - ny : x.localeCompare(y);
    return descending ? -order : order;
  });
  rows.forEach(row => body.appendChild(row));
  Array.from(table.tHead.rows[0].cells).forEach((cell, c) =>
    cell.setAttribute("aria-sort", c === column ? (descending ? "descending" : "ascending") : "none"));
}
document.querySelectorAll("table.sortable").forEach(table => {
  Array.from(table.tHead.rows[0].cells).forEach((cell, column) => cell.addEventListener("click", () =>
    sortTable(table, column, cell.getAttribute("aria-sort") === "ascending")));
});
const wanted = decodeURIComponent(location.hash).match(/^#sort=([^:]+)(:desc)?$/);
if (wanted) document.querySelectorAll("table.sortable").forEach(table => {
  const column = Array.from(table.tHead.rows[0].cells).findIndex(cell => cell.textContent === wanted[1]);
  if (column >= 0) sortTable(table, column, wanted[2] === ":desc");
});
)";

constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.4em; } h2 { font-size: 1.15em; margin-top: 1.6em; }
code { background: #f3f3f3; padding: 0.1em 0.3em; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; text-align: left; white-space: nowrap; }
th { background: #eee; cursor: pointer; }
th[aria-sort="ascending"]::after { content: " \25B2"; } th[aria-sort="descending"]::after { content: " \25BC"; }
tbody tr:nth-child(even) { background: #fafafa; }
table:not(.all) .more { display: none; }
label.columns { display: block; margin: 0.4em 0; font-size: 0.9em; }
details.meanings { font-size: 0.85em; margin: 0.5em 0 1em; } details.meanings dl { margin: 0.5em 0; }
figure { margin: 1em 0; } img { max-width: 100%; border: 1px solid #ddd; }
dl { display: grid; grid-template-columns: max-content auto; gap: 0.2em 1em; } dt { font-weight: bold; }
)";

std::string utcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

}  // namespace

std::string machineDescription() {
  std::string processor = "unknown processor";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      processor = line.substr(line.find(':') + 2);
      break;
    }
  utsname system{};
  const std::string kernel = uname(&system) == 0 ? std::string(system.sysname) + " " + system.release + ", " + system.machine : "";
  return processor + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores available" +
         (kernel.empty() ? "" : "; " + kernel);
}

void writeReport(const std::filesystem::path& folder, const std::string& title, const Invocation& invocation,
                 std::filesystem::file_time_type runStart) {
  std::vector<std::filesystem::path> written;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && entry.last_write_time() >= runStart && entry.path().filename() != "report.html")
      written.push_back(entry.path().filename());
  std::sort(written.begin(), written.end());
  const auto wrote = [&](const std::filesystem::path& name) { return std::find(written.begin(), written.end(), name) != written.end(); };
  std::vector<std::filesystem::path> tables, pictures;
  for (const std::filesystem::path& file : written) {
    const std::string extension = file.extension().string();
    if (extension == ".csv") tables.push_back(file);
    // A plot's PNG beside its SVG is the same picture; a gallery shows the contact
    // sheet's pictures one by one, each at its own size.
    if (extension == ".svg" || (extension == ".png" && !wrote(std::filesystem::path(file).replace_extension(".svg")) &&
                                !(file == "contact_sheet.png" && wrote("gallery.json"))))
      pictures.push_back(file);
  }
  std::string html = "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escapedMarkup(title) +
                     "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" + escapedMarkup(title) + "</h1>\n<dl>\n";
  html += "<dt>command</dt><dd><code>" + escapedMarkup(invocation.commandLine) + "</code></dd>\n";
  html += "<dt>hsr</dt><dd>" + escapedMarkup(invocation.version) + "</dd>\n";
  html += "<dt>machine</dt><dd>" + escapedMarkup(machineDescription()) + "</dd>\n";
  html += "<dt>written</dt><dd>" + utcNow() + "</dd>\n</dl>\n";
  if (wrote("gallery.json")) html += galleryHtml(readText(folder / "gallery.json"));
  html += "<p>Point at a column's heading for what it means; click it to sort by it.</p>\n";
  for (const std::filesystem::path& table : tables)
    html += "<h2>" + escapedMarkup(table.string()) + "</h2>\n" +
            tableHtml(parsedCsv(readText(folder / table)), table == "results.csv" || table == "sweep.csv");
  for (const std::filesystem::path& picture : pictures) {
    const std::string name = escapedMarkup(picture.string());
    html += "<h2>" + name + "</h2>\n<figure><a href=\"" + name + "\"><img src=\"" + name + "\" alt=\"" + name +
            "\"></a><figcaption>click for full size</figcaption></figure>\n";
  }
  html += "<h2>Files</h2>\n<ul>\n";
  for (const std::filesystem::path& file : written) html += "<li><a href=\"" + escapedMarkup(file.string()) + "\">" + escapedMarkup(file.string()) + "</a></li>\n";
  html += "</ul>\n<script>" + std::string(kScript) + "</script>\n</body>\n</html>\n";
  OutputFiles files;
  files.addText(folder / "report.html", html);
  files.commit();
}

}  // namespace hsr::studies
