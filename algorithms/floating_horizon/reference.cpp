// The exact drawing the floating horizon is measured against: the same curves of the same
// function, each sampled every kReferenceSpacingPixels or finer, on a lattice whose lines
// include every curve (with the mesh option, fine in both directions, so the surface
// between curves is the function too), with the same holes and jumps left open. Which
// parts are visible is decided by the exact line reference (renderer/reference/line_reference),
// which shares no code with the algorithm: what the two share is only the problem (the
// curves, where f is defined, where it jumps).
#include <algorithm>
#include <cmath>

#include "algorithms/floating_horizon/curves.hpp"
#include "algorithms/floating_horizon/floating_horizon.hpp"
#include "renderer/reference/line_reference.hpp"

namespace hsr::floating_horizon {

namespace {

// Fine samples across an axis: about one per kReferenceSpacingPixels of the image's
// larger side (the footprint is seldom larger on screen), within a budget: a mesh needs
// the lattice fine in both directions, a drawing of rows only along them.
int fineCount(const PreparedScene& scene, bool mesh) {
  const double pixels = std::max(scene.width(), scene.height()) / kReferenceSpacingPixels;
  return static_cast<int>(std::clamp(std::ceil(pixels), 64.0, mesh ? 1024.0 : 4096.0));
}

std::size_t indexOf(const std::vector<double>& sorted, double value) {
  return static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), value) - sorted.begin());
}

}  // namespace

ExactDrawing exactDrawing(const PreparedScene& scene, bool mesh, int threads, Stats& stats) {
  const PhaseTimer timer(stats, "floating horizon reference");
  const SurfaceView view(scene);
  const CurveLayout layout = view.layout(mesh);
  const int rowAxis = layout.rows.fixedAxis, runAxis = 1 - rowAxis;
  const dvec2 half = view.halfFootprint();
  const int fine = fineCount(scene, mesh);

  // The lattice: along the rows, fine (and through every cross curve); across them, the
  // rows themselves (and, for a mesh, fine between them).
  std::vector<double> coordinates[2];
  coordinates[runAxis] = coordinatesAcross(half[runAxis], fine, layout.cross.positions);
  coordinates[rowAxis] = mesh ? coordinatesAcross(half[rowAxis], fine, layout.rows.positions) : layout.rows.positions;
  std::sort(coordinates[rowAxis].begin(), coordinates[rowAxis].end());
  const std::vector<double>&us = coordinates[0], &vs = coordinates[1];
  const auto height = [&](double u, double v) { return view.height({u, v}); };
  const auto broken = [&](dvec2 p, dvec2 q) { return view.breaksBetween(p, q); };
  Lattice lattice = makeLattice(us, vs, height, broken);
  stats.add("reference lattice triangles", static_cast<std::int64_t>(lattice.mesh.triangles.size()));

  // The same scene with the lattice in place of the height field's own mesh.
  Scene latticeScene = scene.scene();
  SceneObject& object = latticeScene.objects[scene.instances()[0].object];
  object.mesh = std::make_shared<const Mesh>(std::move(lattice.mesh));
  object.instancing = Instancing{};
  PreparedScene prepared(latticeScene);
  prepared.setSize(scene.width(), scene.height());

  // Each curve's edges run between consecutive lattice points on its line, taken from the
  // prepared scene, so they lie exactly on the lattice's triangles.
  ExactDrawing exact;
  exact.lines.width = scene.width();
  exact.lines.height = scene.height();
  const CameraTransform& camera = view.camera();
  const auto addCurve = [&](const CurveFamily& family, std::uint32_t curve, double position) {
    const int along = 1 - family.fixedAxis;
    const std::vector<double>& running = coordinates[along];
    const std::size_t fixedIndex = indexOf(coordinates[family.fixedAxis], position);
    const auto vertex = [&](std::size_t i) {
      const std::size_t u = along == 0 ? i : fixedIndex, v = along == 0 ? fixedIndex : i;
      return lattice.vertexAt[v * us.size() + u];
    };
    for (std::size_t i = 0; i + 1 < running.size(); ++i) {
      const std::uint32_t a = vertex(i), b = vertex(i + 1);
      if (a == Lattice::kNoVertex || b == Lattice::kNoVertex ||
          view.breaksBetween(SurfaceView::ground(family, position, running[i]),
                             SurfaceView::ground(family, position, running[i + 1])))
        continue;
      FeatureEdge edge = projectEdge(camera, prepared.positions()[a], prepared.positions()[b], EdgeKind::curve);
      edge.vertexFrom = a;
      edge.vertexTo = b;
      exact.lines.edges.push_back(edge);
      exact.lines.curvePlaces.push_back({curve, running[i], running[i + 1]});
    }
  };
  for (std::size_t r = 0; r < layout.rows.positions.size(); ++r)
    addCurve(layout.rows, static_cast<std::uint32_t>(r), layout.rows.positions[r]);
  for (std::size_t c = 0; c < layout.cross.positions.size(); ++c)
    addCurve(layout.cross, static_cast<std::uint32_t>(layout.rows.positions.size() + c), layout.cross.positions[c]);

  exact.visibility = traceLineReference(prepared, exact.lines.edges, threads, stats);
  for (std::uint32_t e = 0; e < exact.lines.edges.size(); ++e) appendPieces(exact.lines, e, exact.visibility[e].visible);
  return exact;
}

}  // namespace hsr::floating_horizon
