// The hidden-line peer: Open CASCADE's polygonal hidden-line removal (HLRBRep_PolyAlgo)
// beside hsr's Appel, on the same mesh, camera and image, compared edge by edge and
// judged by hsr's exact line reference.
//
//   build/bench/occt_peer [--crease DEGREES] [--size WxH] [--out DIR] [SCENE]
//
// SCENE defaults to scenes/dragon.toml (99,784 triangles). Open CASCADE gets the mesh as
// a B-rep: one planar face per triangle, its edges shared between neighbours, the edges
// whose faces meet flatter than the crease angle marked smooth, so that its sharp and
// outline edges are hsr's feature edges (boundaries, contours, creases sharper than
// --crease, default 30 degrees). It is given the mesh mapped into a parallel view of
// hsr's perspective one (parallelViewOf), so its 2D output is hsr's image plane exactly.
// hsr draws with Appel (surfaces=any: the dragon is not a closed manifold).
//
// Every 2D segment Open CASCADE outputs lies on the projection of one mesh edge; it is
// matched to that feature edge of hsr's (both ends on its line within kOnEdgePixels), so
// the two drawings become visible intervals of the same edges and the line error of
// renderer/reference/metrics judges both against the exact line reference. Printed: each side's
// visible length and time, and a table by kind of edge (contour, crease, boundary; on
// one, two or more faces) of the length each side draws wrongly or misses. Written to
// DIR (default out/occt_peer): overlay.png (white; Open CASCADE's hidden lines grey,
// its visible lines blue, hsr's visible lines red, both visible purple), and
// occt_errors.png and hsr_errors.png, each drawing judged by the exact reference in
// hsr compare's colours (exactly visible lines light grey, drawn but hidden red, visible
// but missed blue). Open CASCADE is used here only, never by the algorithms.
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <HLRAlgo_Projector.hxx>
#include <gp.hxx>
#include <HLRBRep_PolyAlgo.hxx>
#include <HLRBRep_PolyHLRToShape.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "algorithms/registry.hpp"
#include "peer_timing.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/image/image_grid.hpp"
#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_errors.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/reference/line_reference.hpp"
#include "renderer/util/error.hpp"

namespace {

using hsr::bench::millisecondsOf;

struct Segment {
  hsr::dvec2 from, to;  // pixels
};

double lengthOf(const std::vector<Segment>& segments) {
  double length = 0;
  for (const Segment& s : segments) length += glm::length(s.to - s.from);
  return length;
}

double lengthOf(const hsr::LineSet& drawing) {
  double length = 0;
  for (const hsr::LineSegment& piece : drawing.segments)
    if (piece.visible()) length += drawing.edges[piece.edge].lengthPixels() * (piece.end - piece.begin);
  return length;
}

// The projective map that turns hsr's perspective view into a parallel one: a point P at
// distance d = (P - eye).forward along the view axis goes to ((P - eye).right / d,
// (P - eye).up / d, 1 / d). It keeps straight lines straight and planes plane, and along
// each sight line it keeps the order of depth (nearer, larger z), so hidden lines of the
// mapped mesh seen along -z are the hidden lines of the mesh in hsr's view, with x and y
// hsr's normalized image coordinates. Open CASCADE's polygonal algorithm hides in the
// plane of its projector without the perspective divide (it uses the focus only to find
// contours), so it is given this parallel view.
gp_Pnt parallelViewOf(const hsr::CameraTransform& camera, const hsr::dvec3& p) {
  const hsr::dvec3 offset = p - camera.camera().eye;
  const double d = glm::dot(offset, camera.forward());
  if (!(d > 0)) throw hsr::InputError("occt_peer: a vertex lies behind the eye; the parallel view needs the whole mesh in front");
  return gp_Pnt(glm::dot(offset, camera.right()) / d, glm::dot(offset, camera.up()) / d, 1 / d);
}

// The mesh as Open CASCADE's B-rep, in the parallel view: vertices, one straight edge per
// mesh edge (shared by the faces on it), one planar face per triangle. Triangles without
// area are left out. An edge between two faces meeting flatter than the crease angle, in
// the mesh as given (the map bends angles), is marked smooth (G1), which is what
// BRepLib::EncodeRegularity would mark on the unmapped mesh.
struct MeshShape {
  TopoDS_Compound compound;
  std::size_t faces = 0, leftOut = 0;  // triangles given as faces, and those without area
};

MeshShape meshShape(const hsr::PreparedScene& scene, const hsr::CameraTransform& camera, double creaseDegrees) {
  MeshShape shape;
  TopoDS_Compound& compound = shape.compound;
  BRep_Builder builder;
  builder.MakeCompound(compound);
  std::vector<TopoDS_Vertex> vertices(scene.positions().size());
  for (std::size_t v = 0; v < vertices.size(); ++v) builder.MakeVertex(vertices[v], parallelViewOf(camera, scene.positions()[v]), 1e-9);
  struct SharedEdge {
    TopoDS_Edge edge;
    std::vector<std::pair<TopoDS_Face, hsr::dvec3>> faces;  // with their unit normals as given
  };
  std::unordered_map<std::uint64_t, SharedEdge> edges;
  const auto keyOf = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b); };
  const auto edgeOf = [&](std::uint32_t a, std::uint32_t b) {
    auto found = edges.find(keyOf(a, b));
    if (found == edges.end())
      found = edges.emplace(keyOf(a, b), SharedEdge{BRepBuilderAPI_MakeEdge(vertices[std::min(a, b)], vertices[std::max(a, b)]).Edge(), {}}).first;
    return a < b ? found->second.edge : TopoDS::Edge(found->second.edge.Reversed());
  };
  for (std::uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const hsr::dvec3 normal = scene.faceNormal(t);
    const hsr::Triangle& c = scene.triangles()[t];
    if (glm::length(normal) == 0 || c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      ++shape.leftOut;
      continue;
    }
    BRepBuilderAPI_MakeWire wire(edgeOf(c[0], c[1]), edgeOf(c[1], c[2]), edgeOf(c[2], c[0]));
    BRepBuilderAPI_MakeFace face(wire.Wire(), true);
    if (!wire.IsDone() || !face.IsDone()) throw hsr::InputError("occt_peer: Open CASCADE could not make a face of triangle " + std::to_string(t));
    builder.Add(compound, face.Face());
    ++shape.faces;
    for (std::size_t k = 0; k < 3; ++k) edges[keyOf(c[k], c[(k + 1) % 3])].faces.push_back({face.Face(), glm::normalize(normal)});
  }
  const double smoothCosine = std::cos(glm::radians(creaseDegrees));
  for (const auto& [key, shared] : edges)
    if (shared.faces.size() == 2 && glm::dot(shared.faces[0].second, shared.faces[1].second) > smoothCosine)
      builder.Continuity(shared.edge, shared.faces[0].first, shared.faces[1].first, GeomAbs_G1);
  return shape;
}

// The segments of a compound of 2D edges, in hsr's pixels.
std::vector<Segment> segmentsOf(const TopoDS_Shape& shape, const hsr::CameraTransform& camera) {
  std::vector<Segment> segments;
  if (shape.IsNull()) return segments;
  const double scaleY = 1.0 / std::tan(glm::radians(camera.camera().fovYDegrees) / 2);
  const double scaleX = scaleY * camera.height() / camera.width();
  const auto pixel = [&](const gp_Pnt& p) {
    return hsr::dvec2((p.X() * scaleX * 0.5 + 0.5) * camera.width(), (0.5 - p.Y() * scaleY * 0.5) * camera.height());
  };
  for (TopExp_Explorer edges(shape, TopAbs_EDGE); edges.More(); edges.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(edges.Current());
    // Straight pieces built in the projection's plane (2D curves only): their vertices.
    TopoDS_Vertex first, last;
    TopExp::Vertices(edge, first, last);
    if (first.IsNull() || last.IsNull()) continue;
    segments.push_back({pixel(BRep_Tool::Pnt(first)), pixel(BRep_Tool::Pnt(last))});
  }
  return segments;
}

// How far from a feature edge's projected line both ends of one of Open CASCADE's
// segments may lie for the segment to be a piece of that edge: its output is computed
// in the parallel view's coordinates (about 1) to about 1e-9 of them, a millionth of a
// pixel here, while distinct edges of a 100,000-triangle mesh are rarely that close.
constexpr double kOnEdgePixels = 1e-3;

// Open CASCADE's output as a drawing of hsr's feature edges: each segment becomes a piece
// [u0, u1] of the edge it lies on (visible: QI 0; hidden: QI 1), sorted edge by edge.
// Segments on no feature edge are measured apart (a line hsr does not draw at all).
struct MatchedDrawing {
  hsr::LineSet visible, hidden;
  double unmatchedVisiblePixels = 0, unmatchedHiddenPixels = 0;
};

MatchedDrawing onFeatureEdges(const hsr::LineSet& features, const std::vector<Segment>& visible, const std::vector<Segment>& hidden) {
  hsr::dvec2 lo(0), hi(features.width, features.height);
  for (const hsr::FeatureEdge& e : features.edges) {
    lo = glm::min(lo, glm::min(e.pixelFrom, e.pixelTo));
    hi = glm::max(hi, glm::max(e.pixelFrom, e.pixelTo));
  }
  hsr::ImageGrid grid(lo, hi, hsr::dvec2(features.width, features.height), 8);
  grid.bin(features.edges.size(), [&](std::size_t e, auto&& add) {
    grid.cellsOnSegment(features.edges[e].pixelFrom, features.edges[e].pixelTo, add);
  });
  const auto piecesOf = [&](const std::vector<Segment>& segments, int qi, hsr::LineSet& drawing, double& unmatched) {
    drawing.width = features.width, drawing.height = features.height, drawing.edges = features.edges;
    for (const Segment& s : segments) {
      std::uint32_t best = hsr::FeatureEdge::kNone;
      double bestDistance = kOnEdgePixels, u0 = 0, u1 = 0;
      grid.cellsOnSegment((s.from + s.to) * 0.5, (s.from + s.to) * 0.5, [&](std::size_t cell) {
        grid.itemsIn(cell, [&](std::uint32_t e) {
          const hsr::FeatureEdge& edge = features.edges[e];
          const hsr::dvec2 along = edge.pixelTo - edge.pixelFrom;
          const double length = glm::length(along);
          if (length == 0) return;
          const hsr::dvec2 unit = along / length, normal(-unit.y, unit.x);
          const double distance = std::max(std::abs(glm::dot(s.from - edge.pixelFrom, normal)), std::abs(glm::dot(s.to - edge.pixelFrom, normal)));
          const double a = glm::dot(s.from - edge.pixelFrom, unit), b = glm::dot(s.to - edge.pixelFrom, unit);
          if (distance > bestDistance || std::min(a, b) < -kOnEdgePixels || std::max(a, b) > length + kOnEdgePixels) return;
          best = e, bestDistance = distance;
          u0 = std::clamp(std::min(a, b) / length, 0.0, 1.0), u1 = std::clamp(std::max(a, b) / length, 0.0, 1.0);
        });
      });
      if (best == hsr::FeatureEdge::kNone) unmatched += glm::length(s.to - s.from);
      else drawing.segments.push_back({best, u0, u1, qi});
    }
    std::sort(drawing.segments.begin(), drawing.segments.end(), [](const hsr::LineSegment& a, const hsr::LineSegment& b) {
      return a.edge != b.edge ? a.edge < b.edge : a.begin < b.begin;
    });
  };
  MatchedDrawing matched;
  piecesOf(visible, 0, matched.visible, matched.unmatchedVisiblePixels);
  piecesOf(hidden, 1, matched.hidden, matched.unmatchedHiddenPixels);
  return matched;
}

// The hidden parts as if drawn: QI 1 pieces turned visible, so that the line error's
// "visible in the reference but not drawn" separates what Open CASCADE hid from what it
// did not report at all.
hsr::LineSet shownAsVisible(hsr::LineSet drawing) {
  for (hsr::LineSegment& piece : drawing.segments) piece.qi = 0;
  return drawing;
}

// What kind of edge an edge is, for the table: its kind and how many faces share it.
std::string edgeClass(const hsr::FeatureEdge& edge, const hsr::EdgeAdjacency& adjacency) {
  std::string name = hsr::edgeKindName(edge.kind);
  if (edge.meshEdge == hsr::FeatureEdge::kNone) return name;
  const std::uint32_t faces = adjacency.edges[edge.meshEdge].faceCount;
  return name + (faces == 1 ? ", one face" : faces == 2 ? ", two faces" : ", three or more faces");
}

struct Options {
  std::string scene = std::string(HSR_SOURCE_DIR) + "/scenes/dragon.toml";
  double crease = 30;
  int width = 0, height = 0;
  std::filesystem::path out = "out/occt_peer";
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const auto value = [&] {
      if (i + 1 >= argc) throw hsr::InputError(std::string(argv[i]) + ": expected a value");
      return std::string(argv[++i]);
    };
    if (std::strcmp(argv[i], "--crease") == 0) {
      const std::string angle = value();
      const auto [end, error] = std::from_chars(angle.data(), angle.data() + angle.size(), options.crease);
      if (error != std::errc() || end != angle.data() + angle.size() || !(options.crease >= 0 && options.crease <= 180))
        throw hsr::InputError("--crease " + angle + ": expected an angle in degrees from 0 to 180");
    } else if (std::strcmp(argv[i], "--out") == 0) options.out = value();
    else if (std::strcmp(argv[i], "--size") == 0) {
      const std::string size = value();
      if (std::sscanf(size.c_str(), "%dx%d", &options.width, &options.height) != 2)
        throw hsr::InputError("--size " + size + ": expected WIDTHxHEIGHT");
    } else if (argv[i][0] == '-') {
      throw hsr::InputError(std::string(argv[i]) + ": unknown option (usage: occt_peer [--crease DEGREES] [--size WxH] [--out FOLDER] [scene.toml])");
    } else options.scene = argv[i];
  }
  return options;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options options = parse(argc, argv);
  const hsr::Scene scene = hsr::loadScene(options.scene);
  hsr::PreparedScene prepared(scene);
  if (options.width > 0) prepared.setSize(options.width, options.height);
  const int width = prepared.width(), height = prepared.height();
  const hsr::CameraTransform& camera = prepared.camera();
  if (!camera.perspective()) throw hsr::InputError(options.scene + ": occt_peer maps a perspective camera only");
  std::printf("%s: %zu triangles at %dx%d, crease %g degrees\n", options.scene.c_str(), prepared.triangleCount(), width, height,
              options.crease);

  // hsr: Appel, counting every surface, with the same crease angle; then the exact drawing.
  const hsr::AlgorithmEntry& appel = hsr::findAlgorithm("appel");
  const hsr::KnobValues knobs = hsr::resolveKnobs(appel, {{"surfaces", "any"}, {"crease", std::to_string(options.crease)}});
  hsr::Stats stats;
  hsr::LineSet drawing;
  const double hsrMilliseconds = millisecondsOf([&] { drawing = appel.drawLines(prepared, knobs, 1, stats, nullptr); });
  std::vector<hsr::EdgeVisibility> truth;
  const double referenceMilliseconds =
      millisecondsOf([&] { truth = hsr::traceLineReference(prepared, drawing.edges, 0, stats); });

  // Open CASCADE: the B-rep, its smooth edges, its triangulation, then the hidden lines.
  MeshShape shape;
  const double buildMilliseconds = millisecondsOf([&] { shape = meshShape(prepared, camera, options.crease); });
  const double meshMilliseconds = millisecondsOf([&] { BRepMesh_IncrementalMesh(shape.compound, 1e-3, false, 0.5, false); });
  std::vector<Segment> occtVisible, occtHidden;
  const double hlrMilliseconds = millisecondsOf([&] {
    Handle(HLRBRep_PolyAlgo) algorithm = new HLRBRep_PolyAlgo();
    algorithm->Projector(HLRAlgo_Projector(gp_Ax2(gp::Origin(), gp::DZ(), gp::DX())));  // parallel, along -z
    algorithm->Load(shape.compound);
    algorithm->Update();
    HLRBRep_PolyHLRToShape extracted;
    extracted.Update(algorithm);
    occtVisible = segmentsOf(extracted.VCompound(), camera);  // sharp edges and outlines
    occtHidden = segmentsOf(extracted.HCompound(), camera);
  });
  const double occtMilliseconds = buildMilliseconds + meshMilliseconds + hlrMilliseconds;
  std::printf("Open CASCADE was given %zu triangles as faces (%zu without area left out)\n", shape.faces, shape.leftOut);

  const MatchedDrawing occt = onFeatureEdges(drawing, occtVisible, occtHidden);
  const std::vector<hsr::EdgeVisibility> hsrShown = hsr::edgeVisibility(drawing), occtShown = hsr::edgeVisibility(occt.visible),
                                         occtHid = hsr::edgeVisibility(shownAsVisible(occt.hidden));
  std::printf("visible length: hsr Appel %.1f px, the exact line reference %.1f px, Open CASCADE %.1f px (%+.2f%% against the reference; "
              "%.1f px of it on no feature edge of hsr's)\n",
              lengthOf(drawing), hsr::lineError(truth, truth).visibleLength, lengthOf(occtVisible),
              100 * (lengthOf(occtVisible) / hsr::lineError(truth, truth).visibleLength - 1), occt.unmatchedVisiblePixels);
  std::printf("time: hsr Appel %.0f ms (one thread), its exact line reference %.0f ms (all threads); Open CASCADE %.0f ms "
              "(B-rep with smooth edges %.0f, triangulation %.0f, hidden lines %.0f; one thread)\n",
              hsrMilliseconds, referenceMilliseconds, occtMilliseconds, buildMilliseconds, meshMilliseconds, hlrMilliseconds);

  // Edge by edge, grouped by kind: what each side draws that the reference hides, and what
  // it misses that the reference shows (Open CASCADE's misses split into the parts it
  // reports hidden and the parts it reports not at all).
  struct ClassRow {
    std::size_t edges = 0;
    std::vector<hsr::EdgeVisibility> truth, hsr, occtVisible, occtHidden;
  };
  std::map<std::string, ClassRow> rows;
  const hsr::EdgeAdjacency& adjacency = prepared.edgeAdjacency(stats);
  for (std::size_t e = 0; e < drawing.edges.size(); ++e) {
    ClassRow& row = rows[edgeClass(drawing.edges[e], adjacency)];
    ++row.edges;
    row.truth.push_back(truth[e]), row.hsr.push_back(hsrShown[e]);
    row.occtVisible.push_back(occtShown[e]), row.occtHidden.push_back(occtHid[e]);
  }
  std::printf("\n%-36s %7s %10s | %-17s | %-35s\n", "", "", "exactly", "hsr Appel, px", "Open CASCADE, px");
  std::printf("%-36s %7s %10s | %8s %8s | %8s %8s %8s %8s\n", "edges", "count", "visible", "drawn", "missed", "drawn", "missed",
              "(hidden", "absent)");
  for (const auto& [name, row] : rows) {
    const hsr::LineError mine = hsr::lineError(row.hsr, row.truth), theirs = hsr::lineError(row.occtVisible, row.truth),
                         hid = hsr::lineError(row.occtHidden, row.truth);
    const double calledHidden = hid.visibleLength - hid.wronglyHidden;  // exactly visible, reported hidden
    const double absent = std::max(0.0, theirs.wronglyHidden - calledHidden);  // reported neither way (max: rounding)
    std::printf("%-36s %7zu %10.1f | %8.1f %8.1f | %8.1f %8.1f %8.1f %8.1f\n", name.c_str(), row.edges, mine.visibleLength,
                mine.wronglyDrawn, mine.wronglyHidden, theirs.wronglyDrawn, theirs.wronglyHidden, calledHidden, absent);
  }
  std::printf("(drawn: drawn visible but hidden in the reference; missed: visible in the reference but not drawn, for Open CASCADE\n"
              " split into the parts it reports hidden and those it reports not at all)\n\n");

  // Pixel by pixel: each drawing rasterized with the line rule one pixel wide.
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  const auto mask = [&](const std::vector<Segment>& segments) {
    std::vector<std::uint8_t> covered(pixels, 0);
    for (const Segment& s : segments)
      hsr::rasterizeLine(s.from, s.to, 1.0, width, height, [&](int x, int y) { covered[std::size_t(y) * std::size_t(width) + std::size_t(x)] = 1; });
    return covered;
  };
  std::vector<Segment> hsrVisible;
  for (const hsr::LineSegment& piece : drawing.segments)
    if (piece.visible()) hsrVisible.push_back({drawing.edges[piece.edge].pixelAt(piece.begin), drawing.edges[piece.edge].pixelAt(piece.end)});
  const auto hsrMask = mask(hsrVisible), occtMask = mask(occtVisible), hiddenMask = mask(occtHidden);
  long both = 0, onlyHsr = 0, onlyOcct = 0;
  std::vector<std::uint8_t> overlay(4 * pixels, 255);
  const auto paint = [&](std::size_t p, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    overlay[4 * p] = r, overlay[4 * p + 1] = g, overlay[4 * p + 2] = b;
  };
  for (std::size_t p = 0; p < pixels; ++p) {
    if (hiddenMask[p]) paint(p, 190, 190, 190);
    if (occtMask[p] && hsrMask[p]) ++both, paint(p, 110, 0, 150);
    else if (occtMask[p]) ++onlyOcct, paint(p, 0, 70, 230);
    else if (hsrMask[p]) ++onlyHsr, paint(p, 230, 0, 0);
  }
  std::printf("pixels drawn visible: by both %ld, by hsr only %ld, by Open CASCADE only %ld\n", both, onlyHsr, onlyOcct);
  std::filesystem::create_directories(options.out);
  hsr::OutputFiles outputs;
  outputs.addRgbaPng(options.out / "overlay.png", width, height, overlay);
  outputs.addRgbaPng(options.out / "occt_errors.png", width, height, hsr::lineErrorMap(occt.visible, truth));
  outputs.addRgbaPng(options.out / "hsr_errors.png", width, height, hsr::lineErrorMap(drawing, truth));
  outputs.commit();
  std::printf("wrote overlay.png, occt_errors.png and hsr_errors.png in %s\n", options.out.c_str());
  return 0;
} catch (const hsr::InputError& error) {
  std::fprintf(stderr, "occt_peer: %s\n", error.what());
  return 2;
}
