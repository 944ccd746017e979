#include "renderer/obj.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include <tiny_obj_loader.h>

#include "renderer/error.hpp"

namespace hsr {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, long line, const std::string& what) {
  throw InputError(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string_view nextToken(std::string_view& rest) {
  const auto begin = rest.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos) {
    rest = {};
    return {};
  }
  rest.remove_prefix(begin);
  const auto end = rest.find_first_of(" \t\r");
  const std::string_view token = rest.substr(0, end);
  rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
  return token;
}

// The strict pass: checks every v and f statement and counts vertices, so that face
// indices (1-based, or negative = relative to the vertices so far) can be range-checked
// where they stand. tinyobjloader would accept "v 1 abc" as (1, 0, 0) and keep going.
void checkObjText(const std::filesystem::path& file, std::istream& in) {
  std::string text;
  long lineNumber = 0;
  long vertices = 0;
  long faces = 0;
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
      }
      ++vertices;
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
        ++corners;
      }
      if (corners < 3) fail(file, lineNumber, "face needs at least 3 corners, got " + std::to_string(corners));
      ++faces;
    }
  }
  if (faces == 0) fail(file, lineNumber, "no faces (f statements) in the file");
}

}  // namespace

Mesh loadObj(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open the OBJ file (missing or unreadable)");
  checkObjText(file, in);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // fan-triangulated below, so a face keeps its corner order
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(file.string(), config))
    throw InputError(file.string() + ": " + reader.Error());

  Mesh mesh;
  const auto& positions = reader.GetAttrib().vertices;
  mesh.positions.reserve(positions.size() / 3);
  for (std::size_t i = 0; i + 2 < positions.size(); i += 3)
    mesh.positions.push_back({positions[i], positions[i + 1], positions[i + 2]});
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t corner = 0;
    for (const unsigned char faceSize : shape.mesh.num_face_vertices) {
      const auto index = [&](std::size_t k) {
        return static_cast<std::uint32_t>(shape.mesh.indices[corner + k].vertex_index);
      };
      for (std::size_t k = 1; k + 1 < faceSize; ++k) mesh.triangles.push_back({index(0), index(k), index(k + 1)});
      corner += faceSize;
    }
  }
  return mesh;
}

}  // namespace hsr
