#include "renderer/raster/depth.hpp"

#include <limits>

namespace hsr {

const std::vector<std::string>& depthFormatNames() {
  static const std::vector<std::string> names = {"float32", "reversed-float32", "reversed-float32-inf", "unorm24",
                                                 "unorm16"};
  return names;
}

const char* depthFormatName(DepthFormat format) { return depthFormatNames()[static_cast<int>(format)].c_str(); }

bool clipsFarPlane(DepthFormat format, Projection projection) {
  return !(format == DepthFormat::reversedFloat32Infinite && projection == Projection::perspective);
}

DepthEncoding depthEncoding(DepthFormat format, const CameraTransform& camera) {
  const double n = camera.camera().near, f = camera.camera().far;
  const bool reversed = format == DepthFormat::reversedFloat32 || format == DepthFormat::reversedFloat32Infinite;
  if (camera.perspective()) {
    // t = 1/d. Standard: z = f (d - n) / (d (f - n)); reversed: z = n (f - d) / (d (f - n));
    // reversed with f -> infinity: z = n / d.
    if (format == DepthFormat::reversedFloat32Infinite) return {0.0, n};
    if (reversed) return {-n / (f - n), n * f / (f - n)};
    return {f / (f - n), -n * f / (f - n)};
  }
  // t = d: depth is linear in distance under orthographic projection.
  if (reversed) return {f / (f - n), -1.0 / (f - n)};
  return {-n / (f - n), 1.0 / (f - n)};
}

double depthResolution(DepthFormat format, const CameraTransform& camera, double distance) {
  const DepthEncoding encoding = depthEncoding(format, camera);
  return withDepthFormat(format, [&]<typename Format>() {
    const auto stored = Format::store(encoding.z(camera.screenAffineDepth(distance)));
    const auto next = Format::towardFar(stored);
    if (next == stored) return std::numeric_limits<double>::infinity();
    const auto decoded = [&](typename Format::Stored s) { return camera.distanceFromScreenAffine(encoding.t(Format::load(s))); };
    return std::abs(decoded(next) - decoded(stored));
  });
}

}  // namespace hsr
