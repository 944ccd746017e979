// OBJ loading. The file is first checked line by line (the statements hsr reads are
// v and f; others are skipped), so that a bad file is rejected with its file:line and
// what was expected, then parsed with tinyobjloader. Polygons are fan-triangulated.
#pragma once

#include <filesystem>
#include <string>

#include "renderer/scene/mesh.hpp"

namespace hsr {

// Throws InputError naming file:line for: a missing or unreadable file, a vertex
// without three finite numbers, a face with fewer than three corners or a corner
// index that is zero, not a number, or out of range, and a file with no faces.
Mesh loadObj(const std::filesystem::path& file);

// The same checks and mesh for OBJ text already in memory; `file` names it in messages.
Mesh parseObj(const std::string& text, const std::filesystem::path& file);

}  // namespace hsr
