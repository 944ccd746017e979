// The height field as the floating horizon sees it, shared with its exact reference
// (reference.cpp): which object, the curves drawn on it, the order they are drawn in,
// and where the surface breaks (a jump, or a region where f is undefined).
//
// A curve is the surface cut by a vertical plane of constant object-space x or z: the
// textbooks' "curves of constant y" of z = f(x, y), here with the height along y. The
// curves are the scene's grid lines (`segments` = [nx, nz] gives nx + 1 curves of
// constant x and nz + 1 of constant z).
#pragma once

#include <string>
#include <vector>

#include "algorithms/floating_horizon/floating_horizon.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr::floating_horizon {

// Ground coordinates are object-space (x, z); index 0 is x, 1 is z.
struct CurveFamily {
  int fixedAxis = 1;               // the coordinate that is constant along each curve
  std::vector<double> positions;   // of the curves, front to back
};

struct CurveLayout {
  // The rows face the viewer and are drawn front to back; the cross family (the mesh
  // option) runs from row to row. Curve indices (CurvePlace::curve) count the rows in
  // this order, then the cross curves.
  CurveFamily rows, cross;
  std::size_t curveCount() const { return rows.positions.size() + cross.positions.size(); }
};

class SurfaceView {
 public:
  // The scene must pass refusal() (one height-field object, one copy).
  explicit SurfaceView(const PreparedScene& scene);

  const Solid& solid() const { return *solid_; }
  const CameraTransform& camera() const { return camera_; }
  dvec2 halfFootprint() const { return 0.5 * solid_->footprint; }

  // f at a ground point; NaN where f is undefined or the point lies within the near
  // plane (neither the floating horizon nor the line reference clips).
  double height(const dvec2& ground) const;
  dvec3 world(const dvec2& ground, double height) const;

  // Does the surface break between two ground points: a hole between them, or a jump?
  // A jump is told from a steep slope by bisection: following the half where the height
  // changes more, a continuous function's change shrinks with the interval, a jump's
  // does not. Costs one evaluation of f where the middle lies near the chord.
  bool breaksBetween(const dvec2& p, const dvec2& q) const { return breaksBetween(p, height(p), q, height(q)); }
  // The same, with the heights at p and q already known.
  bool breaksBetween(const dvec2& p, double heightP, const dvec2& q, double heightQ) const;

  // The curves and their front-to-back order for this view (see refusal for when one exists).
  CurveLayout layout(bool mesh) const;

  // The ground point of curve `family` at running coordinate `along`.
  static dvec2 ground(const CurveFamily& family, double position, double along) {
    return family.fixedAxis == 0 ? dvec2(position, along) : dvec2(along, position);
  }

 private:
  const Solid* solid_;
  dmat4 worldFromObject_;
  CameraTransform camera_;
};

// n evenly spaced coordinates over [-half, half], merged with `extra` (sorted, unique).
std::vector<double> coordinatesAcross(double half, int n, const std::vector<double>& extra);

}  // namespace hsr::floating_horizon
