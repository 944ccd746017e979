// The z-buffer's visibility pass (the geometry stage, then the chosen variant: the full
// frame's loop is textbook.hpp, its machinery full_frame.cpp; the one-scanline variant
// scanline.cpp), the pictures both variants' steps show, and the registry's entry.
#include "algorithms/zbuffer/zbuffer.hpp"

#include <optional>

#include "renderer/raster/screen_triangles.hpp"

namespace hsr::zbuffer {
Image buffersPicture(const Recording& recording, const CameraTransform& view, std::span<const std::uint32_t> ids,
                     std::span<const float> depth, int width, int height, std::span<const std::uint32_t> justDrawn) {
  Image surfaces = surfacePicture(recording.scene, view, ids, width, height);
  drawWireframe(surfaces, recording.scene, view, justDrawn, kHighlight);
  return besideEachOther({surfaces, depthPicture(depth, width, height)});
}

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  const bool clipFar = clipsFarPlane(knobs.depthFormat, request.view.camera().projection);
  const ScreenGeometry geometry =
      buildScreenTriangles(request.scene, request.view, {.clipFar = clipFar, .submitted = request.triangles}, request.threads, request.stats);
  std::optional<Recording> recording;
  if (request.steps) recording.emplace(Recording{*request.steps, request.scene});
  const Recording* steps = recording ? &*recording : nullptr;
  if (knobs.variant == Variant::full)
    renderFullFrame(geometry, knobs.depthFormat, request.threads, visibility.frame, request.stats,
                    {knobs.depthTest, knobs.path, steps, request.why});
  else
    renderScanline(geometry, knobs.depthFormat, request.threads, visibility.frame, request.stats, knobs.depthTest, steps, request.why);
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "zbuffer";
  entry.summary = "per-pixel depth test (Catmull 1974): full-frame or one-scanline buffer";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"screen triangles", "fragments tested", "fragments written", "fragments skipped by block depth"};
  entry.studyConfigurations = {{}, {{"path", "scalar"}}, {{"variant", "scanline"}}, {{"depth-format", "unorm24"}}, {{"depth-format", "unorm16"}}};
  entry.takesTriangleSubsets = true;
  entry.answersWhy = true;
  entry.depthFormat = [](const KnobValues& knobs) { return knobs.as<Knobs>().depthFormat; };
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::zbuffer
