// Camera transforms: world -> view -> clip -> pixel, in double precision.
// Names say what they map (viewFromWorld: a world point into view space).
#pragma once

#include <array>

#include "renderer/util/math.hpp"
#include "renderer/util/simd.hpp"

namespace hsr {

// A camera as a scene file describes it (scenes/README.md).
enum class Projection { perspective, orthographic };

struct Camera {
  Projection projection = Projection::perspective;
  dvec3 eye{0, 0, 5};
  dvec3 target{0, 0, 0};
  dvec3 up{0, 1, 0};
  double fovYDegrees = 45;   // perspective: vertical field of view
  double orthoHeight = 2;    // orthographic: world units from the bottom to the top of the image
  double near = 0.1;         // distances along the view axis
  double far = 1000;
};

// What is wrong with a camera that no view can be made of, as the scene and triangle
// files report it: the setting at fault and what it must be ("far", "must be greater
// than near"); an empty key when nothing is.
struct CameraProblem {
  const char* key = nullptr;
  const char* must = nullptr;
  explicit operator bool() const { return key != nullptr; }
};
CameraProblem cameraProblem(const Camera& camera);

// A vertex in clip space, kept with its distance along the view axis:
// x, y as a projection matrix would give them, w the homogeneous divisor
// (= d under perspective, 1 under orthographic), d = -z_view. All four are linear
// in the 3D position, so clipping interpolates them linearly. Real is double for one
// vertex, or Double4 for four, a vertex per lane (the geometry stage's fast path).
template <typename Real>
struct ClipCoordinates {
  Real x, y, d, w;
};
using ClipVertex = ClipCoordinates<double>;

// The half-space normal . p + offset >= 0; with a unit normal, distance() is in world units.
struct Plane {
  dvec3 normal{0};
  double offset = 0;
  double distance(const dvec3& p) const { return glm::dot(normal, p) + offset; }
};

// The view volume's sides, in the order frustumPlanes() returns them.
enum FrustumSide { kLeftSide, kRightSide, kBottomSide, kTopSide, kNearSide, kFarSide };

struct Ray {
  dvec3 origin, direction;  // world space; direction not normalized
};

// Four rays, a ray per lane: Ray's coordinates, axis by axis (the fast paths' form).
struct FourRays {
  Double4 origin[3], direction[3];
};

class CameraTransform {
 public:
  CameraTransform(const Camera& camera, int width, int height);

  // Rotation of (p - eye): subtracting the eye first keeps precision far from the origin.
  dvec3 viewFromWorld(const dvec3& p) const {
    const dvec3 relative = p - camera_.eye;
    return {glm::dot(relative, right_), glm::dot(relative, up_), -glm::dot(relative, forward_)};
  }
  ClipVertex clipFromView(const dvec3& v) const { return clipFromView(v.x, v.y, v.z); }
  ClipVertex clipFromWorld(const dvec3& p) const { return clipFromWorld(p.x, p.y, p.z); }
  // The same of a point given by its coordinates, as doubles or as four points in lanes
  // (Real as in ClipCoordinates): the same operations in the same order (viewFromWorld
  // written out: glm's dot adds x, y, then z), so every lane holds the bits of the one
  // above.
  template <typename Real>
  HSR_INLINE ClipCoordinates<Real> clipFromView(Real x, Real y, Real z) const {
    const Real d = -z;
    return {scaleX_ * x, scaleY_ * y, d, perspective() ? d : broadcast<Real>(1.0)};
  }
  template <typename Real>
  HSR_INLINE ClipCoordinates<Real> clipFromWorld(Real x, Real y, Real z) const {
    const Real relativeX = x - camera_.eye.x, relativeY = y - camera_.eye.y, relativeZ = z - camera_.eye.z;
    return clipFromView(along(right_, relativeX, relativeY, relativeZ), along(up_, relativeX, relativeY, relativeZ),
                        -along(forward_, relativeX, relativeY, relativeZ));
  }
  // clipFromWorld as one matrix: (x, y, d, w) = clipFromWorldMatrix() * (p, 1).
  dmat4 clipFromWorldMatrix() const;
  // The six planes bounding what the camera sees (the image's four sides, the near and
  // far planes), inside >= 0, unit normals, extracted from the rows of the clip matrix
  // (Gribb and Hartmann 2001); indexed by FrustumSide.
  std::array<Plane, 6> frustumPlanes() const;
  // Pixel coordinates (x right, y down, conventions.hpp) of a clip vertex with w > 0.
  dvec2 pixelFromClip(const ClipVertex& v) const { return {pixelXFromClip(v), pixelYFromClip(v)}; }
  template <typename Real>
  HSR_INLINE Real pixelXFromClip(const ClipCoordinates<Real>& v) const { return (v.x / v.w * 0.5 + 0.5) * double(width_); }
  template <typename Real>
  HSR_INLINE Real pixelYFromClip(const ClipCoordinates<Real>& v) const { return (0.5 - v.y / v.w * 0.5) * double(height_); }
  // The world-space ray through a point in pixel coordinates: from the eye under
  // perspective, parallel to the view axis from the near-plane rectangle under orthographic.
  Ray rayThroughPixel(double px, double py) const;
  // rayThroughPixel for four points of one row, a point per lane, by the same operations
  // in the same order: the same rays, bit for bit.
  HSR_AVX2 FourRays raysThroughPixels(Double4 px, double py) const {
    const Double4 ndcX = 2.0 * px / double(width_) - 1.0;
    const double ndcY = 1 - 2 * py / height_;
    FourRays rays;
    for (int axis = 0; axis < 3; ++axis) {
      const Double4 across = right_[axis] * (ndcX * inverseScaleX_) + up_[axis] * (ndcY * inverseScaleY_);
      rays.origin[axis] = perspective() ? lanesOf(camera_.eye[axis]) : camera_.eye[axis] + across;
      rays.direction[axis] = perspective() ? forward_[axis] + across : lanesOf(forward_[axis]);
    }
    return rays;
  }

  // "t" is the quantity that is affine in screen space: 1/d under perspective, d under
  // orthographic. Depth formats store a + b t; see depth.hpp.
  template <typename Real>
  HSR_INLINE Real screenAffineDepth(Real d) const { return perspective() ? 1.0 / d : d; }
  double distanceFromScreenAffine(double t) const { return perspective() ? 1.0 / t : t; }

  // The world-space view basis: d = (p - eye) . forward is the distance along the view axis.
  const dvec3& forward() const { return forward_; }
  const dvec3& right() const { return right_; }
  const dvec3& up() const { return up_; }
  bool perspective() const { return camera_.projection == Projection::perspective; }
  const Camera& camera() const { return camera_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // (x, y, z) . axis, adding x, y, then z as glm::dot does. (A function, not a lambda:
  // see ClipVolume::bitOutside.)
  template <typename Real>
  HSR_INLINE static Real along(const dvec3& axis, Real x, Real y, Real z) {
    return x * axis.x + y * axis.y + z * axis.z;
  }

  Camera camera_;
  int width_, height_;
  dvec3 right_, up_, forward_;  // world-space view basis
  double scaleX_, scaleY_;      // clip x = scaleX * view x (divided by d under perspective)
  double inverseScaleX_, inverseScaleY_;  // so a ray per pixel costs no division
};

}  // namespace hsr
