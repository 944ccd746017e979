// The frame loop's ray set-up (cast.hpp), four rays at a time where the CPU has AVX2.
#include "algorithms/ray_casting/cast.hpp"

#include "renderer/util/simd.hpp"

namespace hsr::ray_casting {
HSR_AVX2 FourPixelRays::FourPixelRays(const CameraTransform& camera, Double4 centersX, int y)
    : rays(camera.raysThroughPixels(centersX, conventions::pixelCenter(y))) {
  const dvec3& eye = camera.camera().eye;
  const dvec3& forward = camera.forward();
  for (int axis = 0; axis < 3; ++axis) inverseDirection[axis] = inverseOf(rays.direction[axis]);
  startDistance = (rays.origin[0] - eye.x) * forward.x + (rays.origin[1] - eye.y) * forward.y + (rays.origin[2] - eye.z) * forward.z;
  slope = rays.direction[0] * forward.x + rays.direction[1] * forward.y + rays.direction[2] * forward.z;
  const Double4 perDistance = 1.0 / slope;
  tNear = (camera.camera().near - startDistance) * perDistance;
  tFar = (camera.camera().far - startDistance) * perDistance;
}

HSR_AVX2 PixelRay FourPixelRays::lane(int i) const {
  PixelRay pixel;
  for (int axis = 0; axis < 3; ++axis) {
    pixel.ray.origin[axis] = rays.origin[axis][i];
    pixel.ray.direction[axis] = rays.direction[axis][i];
    pixel.inverseDirection[axis] = inverseDirection[axis][i];
  }
  pixel.startDistance = startDistance[i], pixel.slope = slope[i];
  pixel.tNear = tNear[i], pixel.tFar = tFar[i];
  return pixel;
}

namespace {

HSR_AVX2 void setUpFourAtATime(const CameraTransform& camera, int y, int x0, int count, PixelRay* out) {
  for (int x = x0; x < x0 + count; x += 4) {
    const FourPixelRays four(camera, double(x) + Double4{0, 1, 2, 3} + conventions::kPixelCenterOffset, y);
    for (int lane = 0; lane < std::min(4, x0 + count - x); ++lane) out[x - x0 + lane] = four.lane(lane);
  }
}

}  // namespace

void setUpPixelRays(const CameraTransform& camera, int y, int x0, int count, PixelRay* out) {
  if (cpuHasAvx2()) return setUpFourAtATime(camera, y, x0, count, out);
  for (int i = 0; i < count; ++i)
    out[i] = PixelRay(camera, camera.rayThroughPixel(conventions::pixelCenter(x0 + i), conventions::pixelCenter(y)));
}

}  // namespace hsr::ray_casting
