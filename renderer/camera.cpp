#include "renderer/camera.hpp"

#include <cmath>

namespace hsr {

CameraTransform::CameraTransform(const Camera& camera, int width, int height)
    : camera_(camera), width_(width), height_(height) {
  forward_ = glm::normalize(camera.target - camera.eye);
  right_ = glm::normalize(glm::cross(forward_, camera.up));
  up_ = glm::cross(right_, forward_);
  const double aspect = double(width) / height;
  if (perspective()) {
    scaleY_ = 1.0 / std::tan(glm::radians(camera.fovYDegrees) / 2);
    scaleX_ = scaleY_ / aspect;
  } else {
    scaleY_ = 2.0 / camera.orthoHeight;
    scaleX_ = scaleY_ / aspect;
  }
  inverseScaleX_ = 1.0 / scaleX_;
  inverseScaleY_ = 1.0 / scaleY_;
}

dvec3 CameraTransform::viewFromWorld(const dvec3& p) const {
  const dvec3 relative = p - camera_.eye;
  return {glm::dot(relative, right_), glm::dot(relative, up_), -glm::dot(relative, forward_)};
}

ClipVertex CameraTransform::clipFromWorld(const dvec3& p) const {
  const dvec3 v = viewFromWorld(p);
  const double d = -v.z;
  return {scaleX_ * v.x, scaleY_ * v.y, d, perspective() ? d : 1.0};
}

dvec2 CameraTransform::pixelFromClip(const ClipVertex& v) const {
  return {(v.x / v.w * 0.5 + 0.5) * width_, (0.5 - v.y / v.w * 0.5) * height_};
}

Ray CameraTransform::rayThroughPixel(double px, double py) const {
  const double ndcX = 2 * px / width_ - 1;
  const double ndcY = 1 - 2 * py / height_;
  const dvec3 across = right_ * (ndcX * inverseScaleX_) + up_ * (ndcY * inverseScaleY_);
  if (perspective()) return {camera_.eye, forward_ + across};
  return {camera_.eye + across, forward_};
}

}  // namespace hsr
