#include "renderer/lines/feature_edges.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "renderer/util/portable_math.hpp"

namespace hsr {

int ViewerPredicates::facing(const dvec3& a, const dvec3& b, const dvec3& c) {
  // The front side is the one the normal (b - a) x (c - a) points to; the viewer is on it
  // when the eye is, or (orthographic) when the normal points against the view direction.
  if (camera_.perspective()) return exact_.orient3d(a, b, c, camera_.camera().eye);
  return exact_.facing(a, b, c, -camera_.forward());
}

int ViewerPredicates::side(const dvec3& p, const dvec3& q, const dvec3& y) {
  // orient3d(eye, p, q, y); with the eye at infinity behind the view direction f it tends
  // to a positive multiple of det[f, q - p, y - p] = facing(p, q, y, f).
  if (camera_.perspective()) return exact_.orient3d(camera_.camera().eye, p, q, y);
  return exact_.facing(p, q, y, camera_.forward());
}

std::vector<std::int8_t> viewFacing(const PreparedScene& scene, const CameraTransform& camera, Stats& stats) {
  ViewerPredicates viewer(camera);
  std::vector<std::int8_t> facing(scene.triangleCount());
  for (std::size_t t = 0; t < facing.size(); ++t) {
    const Triangle& triangle = scene.triangles()[t];
    const auto& p = scene.positions();
    facing[t] = static_cast<std::int8_t>(viewer.facing(p[triangle[0]], p[triangle[1]], p[triangle[2]]));
  }
  stats.add("facing tests", static_cast<std::int64_t>(facing.size()));
  stats.add("exact fall-backs", viewer.exact().exactFallbacks);
  return facing;
}

const char* edgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::boundary: return "boundary";
    case EdgeKind::contour: return "contour";
    case EdgeKind::crease: return "crease";
    case EdgeKind::junction: return "junction";
    case EdgeKind::curve: return "curve";
  }
  return "?";
}

double FeatureEdge::lengthPixels() const { return glm::length(pixelTo - pixelFrom); }

double FeatureEdge::edgeParameter(double u) const {
  // s / w and 1 / w are affine in screen space; s = (u / w1) / ((1 - u) / w0 + u / w1).
  const double denominator = (1 - u) * divisorTo + u * divisorFrom;
  return denominator > 0 ? u * divisorFrom / denominator : u;
}

double FeatureEdge::projectedParameter(double s) const {
  const double denominator = (1 - s) * divisorFrom + s * divisorTo;
  return denominator > 0 ? s * divisorTo / denominator : s;
}

FeatureEdge projectEdge(const CameraTransform& camera, const dvec3& from, const dvec3& to, EdgeKind kind) {
  FeatureEdge edge;
  edge.from = from;
  edge.to = to;
  const ClipVertex a = camera.clipFromWorld(from), b = camera.clipFromWorld(to);
  edge.pixelFrom = camera.pixelFromClip(a);
  edge.pixelTo = camera.pixelFromClip(b);
  edge.divisorFrom = a.w;
  edge.divisorTo = b.w;
  edge.kind = kind;
  return edge;
}

std::vector<FeatureEdge> featureEdges(const PreparedScene& scene, const CameraTransform& camera,
                                      std::span<const std::int8_t> facing, double creaseDegrees, Stats& stats) {
  const EdgeAdjacency& adjacency = scene.edgeAdjacency(stats);
  const double creaseCosine = portable::cos(creaseDegrees * std::numbers::pi / 180);
  std::vector<FeatureEdge> edges;
  for (std::uint32_t index = 0; index < adjacency.edges.size(); ++index) {
    const MeshEdge& mesh = adjacency.edges[index];
    EdgeKind kind;
    if (mesh.faceCount == 1) {
      kind = EdgeKind::boundary;
    } else if ((facing[mesh.faces[0]] > 0) != (facing[mesh.faces[1]] > 0)) {
      kind = EdgeKind::contour;
    } else if (mesh.faceCount > 2 ||
               glm::dot(scene.faceNormal(mesh.faces[0]), scene.faceNormal(mesh.faces[1])) < creaseCosine) {
      kind = EdgeKind::crease;
    } else {
      continue;
    }
    FeatureEdge edge = projectEdge(camera, scene.positions()[mesh.a], scene.positions()[mesh.b], kind);
    edge.vertexFrom = mesh.a;
    edge.vertexTo = mesh.b;
    edge.meshEdge = index;
    edge.faces = {mesh.faces[0], mesh.faceCount > 1 ? mesh.faces[1] : FeatureEdge::kNone};
    edges.push_back(edge);
  }
  stats.add("feature edges", static_cast<std::int64_t>(edges.size()));
  return edges;
}

std::string nearPlaneRefusal(const PreparedScene& scene) {
  const Camera& camera = scene.scene().camera;
  const CameraTransform transform(camera, scene.width(), scene.height());
  for (const Instance& instance : scene.instances()) {
    for (std::uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t)
      for (std::uint32_t v : scene.triangles()[t]) {
        const double d = transform.clipFromWorld(scene.positions()[v]).d;
        if (d > camera.near) continue;
        char message[256];
        std::snprintf(message, sizeof message,
                      "object '%s' reaches %.6g from the eye along the view axis, not beyond the near plane (%g): "
                      "line drawings do not clip, so every vertex must lie beyond it",
                      scene.scene().objects[instance.object].name.c_str(), d, camera.near);
        return message;
      }
  }
  return "";
}

}  // namespace hsr
