#include "renderer/obj.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <string_view>
#include <vector>

#include <tiny_obj_loader.h>

#include "renderer/error.hpp"

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

// Where each v and vn statement stands, so that a value tinyobjloader reads differently
// from the check below can still be reported at its line.
struct StatementLines {
  std::vector<long> vertices, normals;
};

// The strict pass: checks every v and f statement and counts vertices, so that face
// indices (1-based, or negative = relative to the vertices so far) can be range-checked
// where they stand. tinyobjloader would accept "v 1 abc" as (1, 0, 0) and keep going.
StatementLines checkObjText(const std::filesystem::path& file, std::istream& in) {
  std::string text;
  long lineNumber = 0;
  long vertices = 0;
  long normals = 0;
  long faces = 0;
  StatementLines lines;
  while (std::getline(in, text)) {
    ++lineNumber;
    std::string_view rest = text;
    const std::string_view keyword = nextToken(rest);
    if (keyword == "v") {
      for (int axis = 0; axis < 3; ++axis) {
        const std::string_view token = nextToken(rest);
        double value = 0;
        const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (token.empty() || error != std::errc() || end != token.data() + token.size())
          fail(file, lineNumber, "vertex needs three numbers x y z, got '" + text + "'");
        if (!std::isfinite(value))
          fail(file, lineNumber, "vertex coordinate is not finite (NaN or Inf), got '" + std::string(token) + "'");
        if (std::abs(value) > kMaxCoordinate)
          fail(file, lineNumber, "vertex coordinate " + std::string(token) + " is out of range; expected at most 1e12 in size");
      }
      ++vertices;
      lines.vertices.push_back(lineNumber);
    } else if (keyword == "vn") {
      for (int axis = 0; axis < 3; ++axis) {
        const std::string_view token = nextToken(rest);
        double value = 0;
        const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (token.empty() || error != std::errc() || end != token.data() + token.size() || !std::isfinite(value) ||
            std::abs(value) > kMaxCoordinate)
          fail(file, lineNumber, "normal needs three finite numbers x y z of at most 1e12 in size, got '" + text + "'");
      }
      ++normals;
      lines.normals.push_back(lineNumber);
    } else if (keyword == "f") {
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
  return lines;
}

// tinyobjloader parses numbers its own way and stores floats: "0e669798", which the check
// reads as 0, becomes NaN (the OBJ fuzz target found it). Each value it stored must be
// finite and in range, or the statement's line is reported.
void checkStoredValues(const std::filesystem::path& file, const std::vector<float>& values, const std::vector<long>& lines,
                       const char* what) {
  for (std::size_t i = 0; i < values.size() && i / 3 < lines.size(); ++i)
    if (!std::isfinite(values[i]) || std::abs(values[i]) > kMaxCoordinate)
      fail(file, lines[i / 3], std::string(what) + " reads as " + std::to_string(values[i]) +
                                   " to tinyobjloader; expected plain decimal numbers of at most 1e12 in size");
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
  const StatementLines statements = checkObjText(file, lines);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // fan-triangulated below, so a face keeps its corner order
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // No material text: hsr reads no materials, and a mtllib line then opens no file.
  if (!reader.ParseFromString(text, "", config))
    throw InputError(file.string() + ": " + reader.Error());

  checkStoredValues(file, reader.GetAttrib().vertices, statements.vertices, "vertex");
  checkStoredValues(file, reader.GetAttrib().normals, statements.normals, "normal");

  Mesh mesh;
  const auto& positions = reader.GetAttrib().vertices;
  mesh.positions.reserve(positions.size() / 3);
  for (std::size_t i = 0; i + 2 < positions.size(); i += 3)
    mesh.positions.push_back({positions[i], positions[i + 1], positions[i + 2]});
  const auto& normals = reader.GetAttrib().normals;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t corner = 0;
    for (const unsigned char faceSize : shape.mesh.num_face_vertices) {
      const auto index = [&](std::size_t k) {
        return static_cast<std::uint32_t>(shape.mesh.indices[corner + k].vertex_index);
      };
      // A corner without a normal (or with a zero one) gets a computed normal.
      const auto normal = [&](std::size_t k) {
        const int n = shape.mesh.indices[corner + k].normal_index;
        return n < 0 ? dvec3(0) : dvec3(normals[3 * std::size_t(n)], normals[3 * std::size_t(n) + 1], normals[3 * std::size_t(n) + 2]);
      };
      for (std::size_t k = 1; k + 1 < faceSize; ++k) {
        mesh.triangles.push_back({index(0), index(k), index(k + 1)});
        if (!normals.empty()) mesh.cornerNormals.push_back({normal(0), normal(k), normal(k + 1)});
      }
      corner += faceSize;
    }
  }
  return mesh;
}

}  // namespace hsr
