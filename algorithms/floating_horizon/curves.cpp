#include "algorithms/floating_horizon/curves.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/util/error.hpp"

namespace hsr::floating_horizon {

namespace {

// The ground (object x, z) part of an object-space direction.
dvec2 groundOf(const dvec3& direction) { return {direction.x, direction.z}; }

// The view's directions in the height field's object space.
struct ObjectView {
  dvec3 eye, forward, up;
  dvec3 screenX;  // screen x grows along it: x_screen = screenX . p_object + constant (orthographic)
};

ObjectView objectView(const CameraTransform& camera, const dmat4& worldFromObject) {
  const dmat3 linear(worldFromObject);
  const dmat3 objectFromWorld = glm::inverse(linear);
  const dvec3 translation(worldFromObject[3]);
  return {objectFromWorld * (camera.camera().eye - translation), objectFromWorld * camera.forward(),
          objectFromWorld * camera.up(), glm::transpose(linear) * camera.right()};
}

}  // namespace

std::string refusal(const PreparedScene& scene) {
  const std::vector<Instance>& instances = scene.instances();
  if (instances.size() != 1 || scene.scene().objects[instances[0].object].solid.kind != Solid::Kind::heightField)
    return "the floating horizon draws one height-field object (shape = \"heightfield\" or \"grid\", no copies); this scene has " +
           std::to_string(instances.size()) + " object copies" +
           (instances.size() == 1 ? " and it is not a height field" : "");
  const Solid& solid = scene.scene().objects[instances[0].object].solid;
  const CameraTransform& camera = scene.camera();
  const ObjectView view = objectView(camera, instances[0].worldFromObject);
  // A screen column must not depend on the height: then each column is a vertical plane
  // through the surface, the premise of the horizon arrays.
  if (std::abs(view.screenX.y) > 1e-9 * glm::length(view.screenX))
    return "the floating horizon needs the image's x axis level with the height field (no camera roll, no height "
           "field tilted about the view direction), so that a screen column is a vertical slice of the surface";
  if (camera.perspective() && std::abs(view.eye.x) <= 0.5 * solid.footprint.x && std::abs(view.eye.z) <= 0.5 * solid.footprint.y)
    return "under perspective the floating horizon needs the eye outside the height field's footprint (seen from "
           "above), so that its curves have a front-to-back order; this eye is above or below it";
  return "";
}

SurfaceView::SurfaceView(const PreparedScene& scene)
    : solid_(&scene.scene().objects[scene.instances().at(0).object].solid),
      worldFromObject_(scene.instances()[0].worldFromObject),
      camera_(scene.camera()) {}

dvec3 SurfaceView::world(const dvec2& ground, double height) const {
  return dvec3(worldFromObject_ * dvec4(ground.x, height, ground.y, 1.0));
}

double SurfaceView::height(const dvec2& ground) const {
  const double h = solid_->function.evaluate(ground.x, ground.y);
  if (std::isnan(h) || camera_.clipFromWorld(world(ground, h)).d <= camera_.camera().near)
    return std::numeric_limits<double>::quiet_NaN();
  return h;
}

bool SurfaceView::breaksBetween(const dvec2& p, double heightP, const dvec2& q, double heightQ) const {
  dvec2 a = p, b = q;
  double ha = heightP, hb = heightQ;
  dvec2 middle = 0.5 * (a + b);
  double hm = height(middle);
  if (std::isnan(ha) || std::isnan(hb) || std::isnan(hm)) return true;
  const double firstChange = std::max(std::abs(hm - ha), std::abs(hb - hm));
  // The middle near the chord: smooth here (a jump puts the middle at one end's height).
  if (firstChange == 0 || std::abs(hm - 0.5 * (ha + hb)) <= 0.25 * std::abs(hb - ha)) return false;
  for (int halving = 0; halving < 64; ++halving) {
    if (std::abs(hm - ha) >= std::abs(hb - hm))
      b = middle, hb = hm;
    else
      a = middle, ha = hm;
    middle = 0.5 * (a + b);
    if (middle == a || middle == b) break;  // no double between them: as close as it gets
    hm = height(middle);
    if (std::isnan(hm)) return true;
  }
  return std::abs(hb - ha) > 0.5 * firstChange;
}

CurveLayout SurfaceView::layout(bool mesh) const {
  const ObjectView view = objectView(camera_, worldFromObject_);
  const dvec2 half = halfFootprint();
  const dvec2 eye = groundOf(view.eye);
  // Which way is "farther" across the ground: the view direction's ground part; looking
  // straight down it has none, and up the screen is farther.
  dvec2 away = groundOf(view.forward);
  if (glm::length(away) <= 1e-12 * glm::length(view.forward)) away = groundOf(view.up);
  // The rows are the curves the view looks across. Under perspective only a family whose
  // lines the eye lies beyond can be ordered front to back (refusal).
  int rowAxis = std::abs(away.x) > std::abs(away.y) ? 0 : 1;
  if (camera_.perspective() && !(std::abs(eye[rowAxis]) > half[rowAxis])) rowAxis = 1 - rowAxis;

  const auto family = [&](int fixedAxis) {
    CurveFamily result;
    result.fixedAxis = fixedAxis;
    result.positions = evenlySpaced(solid_->footprint[fixedAxis], solid_->cells[fixedAxis]);  // the grid lines
    // Front first: nearest the eye under perspective, least far along `away` otherwise.
    const auto distance = [&](double position) {
      return camera_.perspective() ? std::abs(position - eye[fixedAxis]) : (away[fixedAxis] < 0 ? -position : position);
    };
    std::stable_sort(result.positions.begin(), result.positions.end(),
                     [&](double a, double b) { return distance(a) < distance(b); });
    return result;
  };
  CurveLayout layout;
  layout.rows = family(rowAxis);
  if (mesh) layout.cross = family(1 - rowAxis);
  return layout;
}

std::vector<double> coordinatesAcross(double half, int n, const std::vector<double>& extra) {
  HSR_CHECK(n >= 2);
  std::vector<double> coordinates = extra;
  for (int i = 0; i < n; ++i) coordinates.push_back(half * (2.0 * i / (n - 1) - 1.0));
  std::sort(coordinates.begin(), coordinates.end());
  coordinates.erase(std::unique(coordinates.begin(), coordinates.end()), coordinates.end());
  return coordinates;
}

}  // namespace hsr::floating_horizon
