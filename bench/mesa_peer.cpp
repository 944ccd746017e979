// The peer benchmark: the same scene, size, depth test (32-bit float, "less") and thread
// count in hsr's full-frame z-buffer and in Mesa's software OpenGL (OSMesa on llvmpipe),
// timed in one run, interleaved, and compared pixel by pixel on visible triangle ids.
//
//   build/bench/mesa_peer --threads 2 [--runs 15] [counters city dragons ...]
//
// hsr is timed three times: by the textbook loop (path=scalar) and by the fast path
// (path=simd, algorithms/zbuffer/fast_path.hpp), which draw the same ids and keep their
// depth buffer for whoever asks for distances (as Mesa's stays in its framebuffer); and
// by the fast path asked for ids alone (FullFrameOptions::keepDepth off), which is all
// this comparison reads, and which keeps nothing.
//
// Both draw ids, not shading: Mesa gets every triangle's id as a flat vertex colour.
// OSMesa's own depth buffer stops at 24 bits, so Mesa draws into a framebuffer object
// with a GL_DEPTH_COMPONENT32F attachment. llvmpipe's threads are set with
// LP_NUM_THREADS before the context exists: 0 for one thread (everything on the
// calling thread), N for N rasterizer threads.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "peer_timing.hpp"
#include "renderer/util/memory.hpp"

namespace {

constexpr int kWidth = 1280, kHeight = 720;

using hsr::bench::millisecondsOf;
using hsr::bench::Timing;

// Mesa's side: a framebuffer object with RGBA8 colour and float32 depth, and the scene's
// triangles unindexed in one vertex buffer, each corner carrying its triangle's id + 1.
class MesaRenderer {
 public:
  explicit MesaRenderer(const hsr::PreparedScene& scene) {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    backing_.resize(std::size_t(kWidth) * kHeight * 4);
    if (!context_ || !OSMesaMakeCurrent(context_, backing_.data(), GL_UNSIGNED_BYTE, kWidth, kHeight)) {
      std::fprintf(stderr, "mesa_peer: cannot create an OSMesa context\n");
      std::exit(1);
    }
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glGenRenderbuffers(2, renderbuffers_);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kWidth, kHeight);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers_[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers_[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, kWidth, kHeight);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers_[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      std::fprintf(stderr, "mesa_peer: the float32 depth framebuffer is not complete\n");
      std::exit(1);
    }

    struct Vertex {
      float position[3];
      std::uint8_t color[4];
    };
    std::vector<Vertex> vertices;
    vertices.reserve(scene.triangleCount() * 3);
    for (std::uint32_t i = 0; i < scene.triangleCount(); ++i) {
      const std::uint32_t id = i + 1;
      for (std::uint32_t corner : scene.triangles()[i]) {
        const hsr::dvec3& p = scene.positions()[corner];
        vertices.push_back({{float(p.x), float(p.y), float(p.z)},
                            {std::uint8_t(id >> 16), std::uint8_t(id >> 8), std::uint8_t(id), 255}});
      }
    }
    vertexCount_ = static_cast<GLsizei>(vertices.size());
    glGenBuffers(1, &buffer_);
    glBindBuffer(GL_ARRAY_BUFFER, buffer_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), GL_STATIC_DRAW);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, sizeof(Vertex), nullptr);
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex), reinterpret_cast<const void*>(offsetof(Vertex, color)));

    // The same camera as hsr's: right-handed, looking down -z, the same frustum.
    const hsr::Camera& camera = scene.scene().camera;
    const glm::mat4 projection = glm::perspective(float(glm::radians(camera.fovYDegrees)), float(kWidth) / kHeight,
                                                  float(camera.near), float(camera.far));
    const glm::mat4 view = glm::mat4(glm::lookAt(camera.eye, camera.target, camera.up));
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixf(glm::value_ptr(projection));
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixf(glm::value_ptr(view));
    glViewport(0, 0, kWidth, kHeight);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_DITHER);  // ids must arrive as written
    glShadeModel(GL_FLAT);
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
  }
  ~MesaRenderer() { OSMesaDestroyContext(context_); }

  void draw() {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, vertexCount_);
    glFinish();
  }

  // Ids in hsr's layout: row 0 at the top (OpenGL's row 0 is the bottom).
  std::vector<std::uint32_t> ids() {
    std::vector<std::uint8_t> rgba(std::size_t(kWidth) * kHeight * 4);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    std::vector<std::uint32_t> result(std::size_t(kWidth) * kHeight);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        result[std::size_t((kHeight - 1 - y) * kWidth + x)] = hsr::idFromRgb(&rgba[std::size_t(y * kWidth + x) * 4]);
    return result;
  }

 private:
  OSMesaContext context_ = nullptr;
  std::vector<std::uint8_t> backing_;
  GLuint framebuffer_ = 0, renderbuffers_[2] = {}, buffer_ = 0;
  GLsizei vertexCount_ = 0;
};

// Where the two disagree, and why.
void compareIds(std::span<const std::uint32_t> ours, std::span<const std::uint32_t> mesa) {
  long covered = 0, agree = 0, silhouette = 0, sharedEdge = 0, other = 0;
  const auto neighbourHolds = [&](std::span<const std::uint32_t> image, int x, int y, std::uint32_t id) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx >= 0 && ny >= 0 && nx < kWidth && ny < kHeight && image[std::size_t(ny * kWidth + nx)] == id) return true;
      }
    return false;
  };
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t p = std::size_t(y * kWidth + x);
      if (ours[p] == 0 && mesa[p] == 0) continue;
      ++covered;
      if (ours[p] == mesa[p])
        ++agree;
      else if (ours[p] == 0 || mesa[p] == 0)
        ++silhouette;  // the object's outline: a center on or next to an edge, decided differently
      else if (neighbourHolds(ours, x, y, mesa[p]) && neighbourHolds(mesa, x, y, ours[p]))
        ++sharedEdge;  // two neighbouring triangles: an edge through (or next to) the center
      else
        ++other;  // depth: Mesa interpolates z its own way; near-ties can go either way
    }
  std::printf("  covered pixels %ld, same triangle %.4f%%\n", covered, 100.0 * double(agree) / double(std::max(1L, covered)));
  std::printf("  disagreeing: silhouette edge %ld, edge shared by neighbours %ld, other (depth) %ld\n", silhouette,
              sharedEdge, other);
}

}  // namespace

int main(int argc, char** argv) try {
  int threads = 2, runs = 15;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--threads" && i + 1 < argc)
      threads = std::atoi(argv[++i]);
    else if (argument == "--runs" && i + 1 < argc)
      runs = std::max(3, std::atoi(argv[++i]));
    else if (!argument.empty() && argument[0] != '-')
      scenes.push_back(argument);
    else {
      std::fprintf(stderr, "usage: mesa_peer [--threads N] [--runs R] [scene ...]\n");
      return 2;
    }
  }
  if (scenes.empty()) scenes = {"counters", "city", "dragons"};
  hsr::keepFreedMemoryForReuse();
  setenv("LP_NUM_THREADS", std::to_string(threads <= 1 ? 0 : threads).c_str(), 1);

  std::printf("hsr full-frame z-buffer (float32) vs Mesa %s (OSMesa, llvmpipe), %dx%d, %d thread(s), %d runs after 2 warm-ups\n",
              "22.3", kWidth, kHeight, threads, runs);
  for (const std::string& name : scenes) {
    const hsr::Scene scene = hsr::loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/" + name + ".toml");
    hsr::PreparedScene prepared(scene);
    prepared.setSize(kWidth, kHeight);
    MesaRenderer mesa(prepared);

    // Reused, as Mesa reuses its framebuffer (both clear it every frame) and the memory it
    // bins triangles into.
    hsr::Frame frame(kWidth, kHeight);
    hsr::ScreenGeometry geometry{prepared.camera(), {}, {}};
    const auto hsrVisibility = [&](hsr::zbuffer::Path path, bool keepDepth) {
      hsr::Stats stats;
      hsr::buildScreenTriangles(prepared, prepared.camera(), {}, threads, stats, geometry);
      hsr::zbuffer::renderFullFrame(geometry, hsr::DepthFormat::float32, threads, frame, stats, {.path = path, .keepDepth = keepDepth});
    };
    Timing scalar, simd, idsOnly, theirs;
    for (int run = 0; run < runs + 2; ++run) {  // interleaved, so all four see the same machine load
      const double a = millisecondsOf([&] { hsrVisibility(hsr::zbuffer::Path::scalar, true); });
      const double b = millisecondsOf([&] { hsrVisibility(hsr::zbuffer::Path::simd, true); });
      const double c = millisecondsOf([&] { hsrVisibility(hsr::zbuffer::Path::simd, false); });
      const double d = millisecondsOf([&] { mesa.draw(); });
      if (run >= 2) {
        scalar.milliseconds.push_back(a);
        simd.milliseconds.push_back(b);
        idsOnly.milliseconds.push_back(c);
        theirs.milliseconds.push_back(d);
      }
    }
    std::printf("%s (%zu triangles)\n", name.c_str(), prepared.triangleCount());
    std::printf("  hsr scalar median %7.2f ms (min %7.2f, max %7.2f)\n", scalar.median(), scalar.min(), scalar.max());
    std::printf("  hsr simd   median %7.2f ms (min %7.2f, max %7.2f)\n", simd.median(), simd.min(), simd.max());
    std::printf("  ids only   median %7.2f ms (min %7.2f, max %7.2f)\n", idsOnly.median(), idsOnly.min(), idsOnly.max());
    std::printf("  Mesa       median %7.2f ms (min %7.2f, max %7.2f)\n", theirs.median(), theirs.min(), theirs.max());
    std::printf("  ratio hsr/Mesa (medians): scalar %.2f, simd %.2f, simd ids only %.2f\n", scalar.median() / theirs.median(),
                simd.median() / theirs.median(), idsOnly.median() / theirs.median());
    compareIds(frame.ids, mesa.ids());
  }
  return 0;
} catch (const hsr::InputError& error) {
  std::fprintf(stderr, "mesa_peer: %s\n", error.what());
  return 2;
}
