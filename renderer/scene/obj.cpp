#include "renderer/scene/obj.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string_view>
#include <vector>

// tinyobjloader's parser, compiled here (the same source on every target) in its double
// build: hsr keeps OBJ coordinates as doubles.
#define TINYOBJLOADER_IMPLEMENTATION
#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>

#include "renderer/util/error.hpp"
#include "renderer/util/portable_math.hpp"
#include "renderer/util/text_numbers.hpp"

namespace hsr {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, long line, const std::string& what) {
  throw InputError(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string_view nextToken(std::string_view& rest) {
  const auto begin = rest.find_first_not_of(" \t");
  if (begin == std::string_view::npos) {
    rest = {};
    return {};
  }
  rest.remove_prefix(begin);
  const auto end = rest.find_first_of(" \t");
  const std::string_view token = rest.substr(0, end);
  rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
  return token;
}

// What the strict pass read: every v and vn value, correctly rounded to the nearest
// double (parseDouble), with the line each statement stands on.
struct ObjNumbers {
  std::vector<dvec3> positions, normals;
  std::vector<long> positionLines, normalLines;
  double statedRounding = 0;  // Mesh::statedRounding: the largest decimalRounding of a coordinate
};

// How far the number a token names may lie from the value its writer meant: half a unit
// in its last written digit when it has six or more significant digits (what exporters
// write: %g gives six, %.6f six decimals), else 0. A shorter number ("1", "0.25",
// "1.5e-3") is taken as written exactly: nobody rounds to fewer than six digits.
// "1.000000" is rounded at 5e-7, "123456" at 0.5, "1.2345678e-3" at 5e-11.
double decimalRounding(std::string_view token) {
  const std::size_t exponentAt = token.find_first_of("eE");
  const std::string_view mantissa = token.substr(0, exponentAt);
  long exponent = 0;
  if (exponentAt != std::string_view::npos) {
    std::string_view digits = token.substr(exponentAt + 1);
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    std::from_chars(digits.data(), digits.data() + digits.size(), exponent);
  }
  const std::size_t point = mantissa.find('.');
  const long decimals = point == std::string_view::npos ? 0 : long(mantissa.size() - point - 1);
  int significant = 0;
  bool leading = true;
  for (const char c : mantissa) {
    if (c < '0' || c > '9') continue;
    leading = leading && c == '0';
    significant += !leading;
  }
  if (significant < 6) return 0;
  return 0.5 * portable::powerOfTen(exponent - decimals);
}

// Three numbers of a v or vn statement, each correctly rounded; fails naming the line
// unless each is a finite number of at most kMaxCoordinate in size.
dvec3 readTriple(std::string_view rest, const std::filesystem::path& file, long lineNumber, const std::string& text,
                 bool isNormal, double* statedRounding) {
  dvec3 values;
  for (int axis = 0; axis < 3; ++axis) {
    const std::string_view token = nextToken(rest);
    const std::optional<double> parsed = parseDouble(token);
    const bool number = parsed.has_value();
    const double value = parsed.value_or(0);
    if (isNormal && (!number || !std::isfinite(value) || std::abs(value) > kMaxCoordinate))
      fail(file, lineNumber, "normal needs three finite numbers x y z of at most 1e12 in size, got '" + text + "'");
    if (!number) fail(file, lineNumber, "vertex needs three numbers x y z, got '" + text + "'");
    if (!std::isfinite(value))
      fail(file, lineNumber, "vertex coordinate is not finite (NaN or Inf), got '" + std::string(token) + "'");
    if (std::abs(value) > kMaxCoordinate)
      fail(file, lineNumber, "vertex coordinate " + std::string(token) + " is out of range; expected at most 1e12 in size");
    if (statedRounding) *statedRounding = std::max(*statedRounding, decimalRounding(token));
    values[axis] = value;
  }
  return values;
}

// The strict pass: checks every v, vn and f statement and reads the numbers, so that
// face indices (1-based, or negative = relative to the vertices so far) can be
// range-checked where they stand. tinyobjloader would accept "v 1 abc" as (1, 0, 0).
ObjNumbers checkObjText(const std::filesystem::path& file, std::istream& in) {
  std::string text;
  long lineNumber = 0;
  long faces = 0;
  ObjNumbers numbers;
  while (std::getline(in, text)) {
    ++lineNumber;
    std::string_view rest = text;
    const std::string_view keyword = nextToken(rest);
    if (keyword == "v") {
      numbers.positions.push_back(readTriple(rest, file, lineNumber, text, false, &numbers.statedRounding));
      numbers.positionLines.push_back(lineNumber);
    } else if (keyword == "vn") {
      numbers.normals.push_back(readTriple(rest, file, lineNumber, text, true, nullptr));
      numbers.normalLines.push_back(lineNumber);
    } else if (keyword == "f") {
      const auto vertices = static_cast<long>(numbers.positions.size());
      const auto normals = static_cast<long>(numbers.normals.size());
      int corners = 0;
      for (std::string_view corner = nextToken(rest); !corner.empty(); corner = nextToken(rest)) {
        const std::string_view position = corner.substr(0, corner.find('/'));
        long index = 0;
        const auto [end, error] = std::from_chars(position.data(), position.data() + position.size(), index);
        if (position.empty() || error != std::errc() || end != position.data() + position.size() || index == 0)
          fail(file, lineNumber, "face corner '" + std::string(corner) + "' is not a vertex index (1-based, or negative relative)");
        const long resolved = index > 0 ? index : vertices + 1 + index;
        if (resolved < 1 || resolved > vertices)
          fail(file, lineNumber, "face index " + std::to_string(index) + " is out of range: " +
                                     std::to_string(vertices) + " vertices are defined before this line");
        // v/vt/vn or v//vn: the normal's index, when given, must name a vn line above.
        const std::size_t firstSlash = corner.find('/');
        const std::size_t secondSlash = firstSlash == std::string_view::npos ? firstSlash : corner.find('/', firstSlash + 1);
        if (secondSlash != std::string_view::npos) {
          const std::string_view normal = corner.substr(secondSlash + 1);
          long normalIndex = 0;
          const auto [normalEnd, normalError] = std::from_chars(normal.data(), normal.data() + normal.size(), normalIndex);
          const long normalResolved = normalIndex > 0 ? normalIndex : normals + 1 + normalIndex;
          if (normal.empty() || normalError != std::errc() || normalEnd != normal.data() + normal.size() || normalIndex == 0 ||
              normalResolved < 1 || normalResolved > normals)
            fail(file, lineNumber, "face corner '" + std::string(corner) + "' names normal " + std::string(normal) + ", but " +
                                       std::to_string(normals) + " normals (vn) are defined before this line");
        }
        ++corners;
      }
      if (corners < 3) fail(file, lineNumber, "face needs at least 3 corners, got " + std::to_string(corners));
      ++faces;
    }
  }
  if (faces == 0) fail(file, lineNumber, "no faces (f statements) in the file");
  return numbers;
}

// tinyobjloader reads the file's structure (faces, their corners and normal indices);
// the numbers hsr keeps are the strict pass's, correctly rounded. tinyobjloader's own
// parser, even in its double build, is off by up to four units in the last place on
// about half the values of the bunny and the dragon (and reads -9.75702e+06 as
// -9757019.9999999981). Its values must still agree with the strict pass's to far
// better than a float, or the two passes did not read the same statement: "0e669798"
// is 0 to std::from_chars and 0 x Inf = NaN to tinyobjloader (the OBJ fuzz target found it).
void checkSameStatements(const std::filesystem::path& file, const std::vector<tinyobj::real_t>& parsed,
                         const std::vector<dvec3>& numbers, const std::vector<long>& lines, const char* what) {
  if (parsed.size() != 3 * numbers.size())
    fail(file, lines.empty() ? 0 : lines.back(),
         std::string("tinyobjloader read ") + std::to_string(parsed.size() / 3) + " " + what + " statements, hsr " +
             std::to_string(numbers.size()) + "; expected plain v and vn lines");
  for (std::size_t i = 0; i < parsed.size(); ++i) {
    const double exact = numbers[i / 3][int(i % 3)];
    if (!(std::abs(parsed[i] - exact) <= 1e-12 * std::abs(exact) + 1e-300))
      fail(file, lines[i / 3], std::string(what) + " reads as " + std::to_string(parsed[i]) + " to tinyobjloader and " +
                                   std::to_string(exact) + " to hsr; expected plain decimal numbers");
  }
}

}  // namespace

Mesh loadObj(const std::filesystem::path& file) { return parseObj(readInputFile(file, "OBJ"), file); }

Mesh parseObj(const std::string& original, const std::filesystem::path& file) {
  // Lines end at \n, \r\n or a lone \r, as tinyobjloader reads them: both passes must
  // see the same lines (the OBJ fuzz target found "f 2 2\r3", three corners to the
  // check and a two-corner face to tinyobjloader).
  std::string text;
  text.reserve(original.size());
  for (std::size_t i = 0; i < original.size(); ++i)
    if (original[i] != '\r') text += original[i];
    else if (i + 1 == original.size() || original[i + 1] != '\n') text += '\n';
  std::istringstream lines(text);
  const ObjNumbers numbers = checkObjText(file, lines);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // fan-triangulated below, so a face keeps its corner order
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // No material text: hsr reads no materials, and a mtllib line then opens no file.
  if (!reader.ParseFromString(text, "", config))
    throw InputError(file.string() + ": " + reader.Error());
  checkSameStatements(file, reader.GetAttrib().vertices, numbers.positions, numbers.positionLines, "vertex");
  checkSameStatements(file, reader.GetAttrib().normals, numbers.normals, numbers.normalLines, "normal");

  Mesh mesh;
  mesh.positions = numbers.positions;
  mesh.statedRounding = numbers.statedRounding;
  const bool withNormals = !numbers.normals.empty();
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t corner = 0;
    for (const unsigned char faceSize : shape.mesh.num_face_vertices) {
      const auto index = [&](std::size_t k) {
        return static_cast<std::uint32_t>(shape.mesh.indices[corner + k].vertex_index);
      };
      // A corner without a normal (or with a zero one) gets a computed normal.
      const auto normal = [&](std::size_t k) {
        const int n = shape.mesh.indices[corner + k].normal_index;
        return n < 0 ? dvec3(0) : numbers.normals[std::size_t(n)];
      };
      for (std::size_t k = 1; k + 1 < faceSize; ++k) {
        mesh.triangles.push_back({index(0), index(k), index(k + 1)});
        if (withNormals) mesh.cornerNormals.push_back({normal(0), normal(k), normal(k + 1)});
      }
      corner += faceSize;
    }
  }
  return mesh;
}

}  // namespace hsr
