#include "renderer/scene/triangle_file.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/util/error.hpp"

namespace hsr {
namespace {

// A number written so that strtod reads back the same double.
std::string exactly(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string exactly(const dvec3& v) { return exactly(v.x) + " " + exactly(v.y) + " " + exactly(v.z); }

// The file's lines, read one at a time with their numbers, comments and blank lines skipped.
class Lines {
 public:
  Lines(const std::string& text, const std::filesystem::path& file) : input_(text), file_(file.string()) {}

  // The next line's words; false at the end of the file.
  bool next(std::vector<std::string>& words) {
    std::string line;
    while (std::getline(input_, line)) {
      ++number_;
      if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      std::istringstream split(line);
      words.clear();
      for (std::string word; split >> word;) words.push_back(word);
      if (!words.empty()) return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(number_) + ": " + what);
  }
  double number(const std::string& word, const std::string& what, double low, double high) const {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value) || value < low || value > high)
      fail(what + " '" + word + "': expected a number from " + exactly(low) + " to " + exactly(high));
    return value;
  }
  // The line's words after the key, as `count` numbers.
  std::vector<double> numbers(const std::vector<std::string>& words, std::size_t first, std::size_t count, const std::string& what,
                              double low, double high) const {
    if (words.size() != first + count)
      fail(what + ": " + std::to_string(words.size() - first) + " numbers; expected " + std::to_string(count));
    std::vector<double> values;
    for (std::size_t k = first; k < words.size(); ++k) values.push_back(number(words[k], what, low, high));
    return values;
  }

 private:
  std::istringstream input_;
  std::string file_;
  int number_ = 0;
};

}  // namespace

std::string triangleFileText(const PreparedScene& scene) {
  const CameraTransform view = scene.camera();
  const Camera& camera = view.camera();
  const bool perspective = camera.projection == Projection::perspective;
  std::string text = "hsr-triangles 1\n";
  text += "# " + scene.scene().file.filename().string() + ": " + std::to_string(scene.triangleCount()) + " triangles\n";
  text += "size " + std::to_string(scene.width()) + " " + std::to_string(scene.height()) + "\n";
  text += std::string("projection ") + (perspective ? "perspective" : "orthographic") + "\n";
  text += "eye " + exactly(camera.eye) + "\ntarget " + exactly(camera.target) + "\nup " + exactly(camera.up) + "\n";
  text += perspective ? "fov_y " + exactly(camera.fovYDegrees) + "\n" : "height " + exactly(camera.orthoHeight) + "\n";
  text += "near " + exactly(camera.near) + "\nfar " + exactly(camera.far) + "\n";
  const dmat4 clip = view.clipFromWorldMatrix();
  text += "clip_from_world\n";
  for (int row = 0; row < 4; ++row)  // glm is column-major: clip[column][row]
    text += exactly(clip[0][row]) + " " + exactly(clip[1][row]) + " " + exactly(clip[2][row]) + " " + exactly(clip[3][row]) + "\n";
  text += "triangles " + std::to_string(scene.triangleCount()) + "\n";
  for (std::size_t object = 0; object < scene.instances().size(); ++object) {
    const Instance& instance = scene.instances()[object];
    for (std::uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t) {
      const Triangle& triangle = scene.triangles()[t];
      text += exactly(scene.positions()[triangle[0]]) + " " + exactly(scene.positions()[triangle[1]]) + " " +
              exactly(scene.positions()[triangle[2]]) + " " + std::to_string(object + 1) + "\n";
    }
  }
  return text;
}

Scene parseTriangleFile(const std::string& text, const std::filesystem::path& file) {
  Lines lines(text, file);
  std::vector<std::string> words;
  if (!lines.next(words) || words != std::vector<std::string>{"hsr-triangles", "1"})
    lines.fail("expected the first line 'hsr-triangles 1'");

  Scene scene;
  scene.file = file;
  Camera& camera = scene.camera;
  std::map<std::string, bool> seen;
  const auto vector3 = [&](const std::string& key) {
    const std::vector<double> v = lines.numbers(words, 1, 3, key, -kMaxCoordinate, kMaxCoordinate);
    return dvec3(v[0], v[1], v[2]);
  };
  const auto one = [&](const std::string& key, double low, double high) { return lines.numbers(words, 1, 1, key, low, high)[0]; };
  // The header: each key once, in any order, up to the triangles.
  while (true) {
    if (!lines.next(words)) lines.fail("the file ends before its 'triangles T' line");
    const std::string& key = words[0];
    if (key == "triangles") break;
    if (seen[key]) lines.fail(key + ": given twice");
    seen[key] = true;
    if (key == "size") {
      const std::vector<double> size = lines.numbers(words, 1, 2, "size", 1, kMaxImageSide);
      if (size[0] != std::floor(size[0]) || size[1] != std::floor(size[1])) lines.fail("size: expected two whole numbers");
      scene.width = int(size[0]);
      scene.height = int(size[1]);
      checkImageSize(scene.width, scene.height, file.string() + ": size");
    } else if (key == "projection") {
      if (words.size() != 2 || (words[1] != "perspective" && words[1] != "orthographic"))
        lines.fail("projection: expected perspective or orthographic");
      camera.projection = words[1] == "perspective" ? Projection::perspective : Projection::orthographic;
    } else if (key == "eye") {
      camera.eye = vector3(key);
    } else if (key == "target") {
      camera.target = vector3(key);
    } else if (key == "up") {
      camera.up = vector3(key);
    } else if (key == "fov_y") {
      camera.fovYDegrees = one(key, 0.01, 179);
    } else if (key == "height") {
      camera.orthoHeight = one(key, 1e-9, kMaxCoordinate);
    } else if (key == "near") {
      camera.near = one(key, 1e-9, kMaxCoordinate);
    } else if (key == "far") {
      camera.far = one(key, 1e-9, kMaxCoordinate);
    } else if (key == "clip_from_world") {
      for (int row = 0; row < 4; ++row) {  // checked as numbers, not used: the camera's parameters are
        if (!lines.next(words)) lines.fail("clip_from_world: the file ends inside the matrix");
        lines.numbers(words, 0, 4, "clip_from_world row " + std::to_string(row + 1), -HUGE_VAL, HUGE_VAL);
      }
    } else {
      lines.fail("'" + key + "': expected size, projection, eye, target, up, fov_y, height, near, far, clip_from_world or triangles");
    }
  }
  const bool perspective = camera.projection == Projection::perspective;
  for (const char* key : {"size", "projection", "eye", "target", "near", "far", perspective ? "fov_y" : "height"})
    if (!seen[key]) lines.fail(std::string("triangles: the header has no '") + key + "' line");
  if (const CameraProblem problem = cameraProblem(camera)) lines.fail(std::string(problem.key) + " " + problem.must);

  const double count = lines.numbers(words, 1, 1, "triangles", 0, double(kMaxTriangles))[0];
  if (count != std::floor(count)) lines.fail("triangles: expected a whole number");
  // Each run of lines with one object number is an object (the culling stages cull by
  // object); the triangles keep the file's order, so their ids stay the line numbers.
  // Within an object, corners at exactly the same coordinates are one vertex, so faces
  // meet at shared edges as in the scene the file came from (the line algorithms ask
  // which faces meet at an edge).
  std::vector<Mesh> meshes;
  std::map<std::array<double, 3>, std::uint32_t> vertexAt;  // the current object's
  double object = 0;
  for (std::size_t t = 0; t < std::size_t(count); ++t) {
    if (!lines.next(words)) lines.fail("triangles: " + std::to_string(t) + " triangle lines; expected " + std::to_string(std::size_t(count)));
    const std::string what = "triangle " + std::to_string(t + 1);
    if (words.size() != 9 && words.size() != 10)
      lines.fail(what + ": " + std::to_string(words.size()) + " numbers; expected 9 (its corners), and its object's number or not");
    if (words.size() == 10) {
      const double number = lines.number(words[9], what + "'s object", 1, double(kMaxTriangles));
      if (number != std::floor(number)) lines.fail(what + "'s object: expected a whole number");
      if (number != object) {
        meshes.emplace_back();
        vertexAt.clear();
      }
      object = number;
      words.pop_back();
    } else if (meshes.empty()) {
      meshes.emplace_back();
    }
    const std::vector<double> corners = lines.numbers(words, 0, 9, what, -kMaxCoordinate, kMaxCoordinate);
    Mesh& mesh = meshes.back();
    Triangle triangle;
    for (int k = 0; k < 3; ++k) {
      const std::array<double, 3> corner = {corners[3 * k], corners[3 * k + 1], corners[3 * k + 2]};
      const auto [at, added] = vertexAt.emplace(corner, std::uint32_t(mesh.positions.size()));
      if (added) mesh.positions.emplace_back(corner[0], corner[1], corner[2]);
      triangle[std::size_t(k)] = at->second;
    }
    mesh.triangles.push_back(triangle);
  }
  if (lines.next(words)) lines.fail("a line after the last triangle; expected the end of the file");
  for (Mesh& mesh : meshes) {
    SceneObject part;
    part.name = "object" + std::to_string(scene.objects.size() + 1);
    part.mesh = std::make_shared<const Mesh>(std::move(mesh));
    scene.objects.push_back(std::move(part));
  }
  return scene;
}

}  // namespace hsr
