#include "renderer/geometry/camera.hpp"

#include <cmath>

#include "renderer/util/portable_math.hpp"

namespace hsr {

CameraProblem cameraProblem(const Camera& camera) {
  if (!(camera.far > camera.near)) return {"far", "must be greater than near"};
  const dvec3 forward = camera.target - camera.eye;
  if (glm::length(forward) == 0) return {"target", "must differ from eye"};
  if (glm::length(glm::cross(forward, camera.up)) <= 1e-9 * glm::length(forward) * glm::length(camera.up))
    return {"up", "must not be parallel to the view direction (target - eye)"};
  return {};
}

CameraTransform::CameraTransform(const Camera& camera, int width, int height)
    : camera_(camera), width_(width), height_(height) {
  forward_ = glm::normalize(camera.target - camera.eye);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
  const double aspect = double(width) / height;
  if (perspective()) {
    scaleY_ = 1.0 / portable::tan(glm::radians(camera.fovYDegrees) / 2);
    scaleX_ = scaleY_ / aspect;
  } else {
    scaleY_ = 2.0 / camera.orthoHeight;
    scaleX_ = scaleY_ / aspect;
  }
  inverseScaleX_ = 1.0 / scaleX_;
  inverseScaleY_ = 1.0 / scaleY_;
}

dmat4 CameraTransform::clipFromWorldMatrix() const {
  // Each clip coordinate is a scaled view axis applied to p - eye: a row (axis, -axis . eye).
  const auto row = [&](const dvec3& axis, double scale) { return dvec4(axis * scale, -glm::dot(axis, camera_.eye) * scale); };
  const dvec4 x = row(right_, scaleX_), y = row(up_, scaleY_), d = row(forward_, 1.0);
  const dvec4 w = perspective() ? d : dvec4(0, 0, 0, 1);
  return glm::transpose(dmat4(x, y, d, w));  // glm's constructor takes columns
}

std::array<Plane, 6> CameraTransform::frustumPlanes() const {
  // Gribb and Hartmann: a point is inside the side -w <= x when (row w + row x) . (p, 1)
  // >= 0, and so on; every side is a sum of rows, so its plane is read off the matrix.
  // Here d itself is the distance along the view axis, so near <= d <= far are rows
  // d - near and far - d (the same method, for a matrix that keeps d unprojected).
  const dmat4 transposed = glm::transpose(clipFromWorldMatrix());  // its columns are the matrix's rows
  const dvec4 x = transposed[0], y = transposed[1], d = transposed[2], w = transposed[3], one(0, 0, 0, 1);
  const dvec4 sides[6] = {w + x, w - x, w + y, w - y, d - camera_.near * one, camera_.far * one - d};
  std::array<Plane, 6> planes;
  for (int i = 0; i < 6; ++i) {
    const double length = glm::length(dvec3(sides[i]));
    planes[i] = {dvec3(sides[i]) / length, sides[i].w / length};
  }
  return planes;
}

Ray CameraTransform::rayThroughPixel(double px, double py) const {
  const double ndcX = 2 * px / width_ - 1;
  const double ndcY = 1 - 2 * py / height_;
  const dvec3 across = right_ * (ndcX * inverseScaleX_) + up_ * (ndcY * inverseScaleY_);
  if (perspective()) return {camera_.eye, forward_ + across};
  return {camera_.eye + across, forward_};
}

}  // namespace hsr
