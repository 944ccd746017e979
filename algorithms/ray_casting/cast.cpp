// The frame loop's ray set-up (cast.hpp), four rays at a time where the CPU has AVX2.
#include "algorithms/ray_casting/cast.hpp"

#include "renderer/simd.hpp"

namespace hsr::ray_casting {
namespace {

// PixelRay's constructor and CameraTransform::rayThroughPixel lane by lane: the same
// operations in the same order, glm::dot's sum taken as it takes it, ((x + y) + z).
HSR_AVX2 void setUpFourAtATime(const CameraTransform& camera, int y, int x0, int count, PixelRay* out) {
  const dvec3& eye = camera.camera().eye;
  const dvec3& forward = camera.forward();
  for (int x = x0; x < x0 + count; x += 4) {
    const Double4 centers = double(x) + Double4{0, 1, 2, 3} + conventions::kPixelCenterOffset;
    const FourRays rays = camera.raysThroughPixels(centers, conventions::pixelCenter(y));
    Double4 inverse[3];
    for (int axis = 0; axis < 3; ++axis) inverse[axis] = inverseOf(rays.direction[axis]);
    const Double4 startDistance = (rays.origin[0] - eye.x) * forward.x + (rays.origin[1] - eye.y) * forward.y + (rays.origin[2] - eye.z) * forward.z;
    const Double4 slope = rays.direction[0] * forward.x + rays.direction[1] * forward.y + rays.direction[2] * forward.z;
    const Double4 perDistance = 1.0 / slope;
    const Double4 tNear = (camera.camera().near - startDistance) * perDistance;
    const Double4 tFar = (camera.camera().far - startDistance) * perDistance;
    for (int lane = 0; lane < std::min(4, x0 + count - x); ++lane) {
      PixelRay& pixel = out[x - x0 + lane];
      for (int axis = 0; axis < 3; ++axis) {
        pixel.ray.origin[axis] = rays.origin[axis][lane];
        pixel.ray.direction[axis] = rays.direction[axis][lane];
        pixel.inverseDirection[axis] = inverse[axis][lane];
      }
      pixel.startDistance = startDistance[lane], pixel.slope = slope[lane];
      pixel.tNear = tNear[lane], pixel.tFar = tFar[lane];
    }
  }
}

}  // namespace

void setUpPixelRays(const CameraTransform& camera, int y, int x0, int count, PixelRay* out) {
  if (cpuHasAvx2()) return setUpFourAtATime(camera, y, x0, count, out);
  for (int i = 0; i < count; ++i)
    out[i] = PixelRay(camera, camera.rayThroughPixel(conventions::pixelCenter(x0 + i), conventions::pixelCenter(y)));
}

}  // namespace hsr::ray_casting
