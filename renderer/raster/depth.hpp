// Depth formats: what a depth buffer stores, how it is compared, and what it costs.
// Every format stores a function of the screen-affine depth t (camera.hpp), which is
// what makes depth a plane over the screen: z = a + b t, then rounded to the format.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/geometry/camera.hpp"

namespace hsr {

// The counter (Stats) of fragments of different triangles stored at the same depth, where
// submission order decided the pixel: kept by every algorithm with a depth buffer, read
// by hsr render for its note.
inline constexpr const char* kDepthTiesCounter = "depth ties";

enum class DepthFormat { float32, reversedFloat32, reversedFloat32Infinite, unorm24, unorm16 };

const std::vector<std::string>& depthFormatNames();  // as the CLI spells them, in enum order
const char* depthFormatName(DepthFormat format);

// z = a + b t maps the near plane to 0 and the far plane to 1 (1 and 0 when reversed;
// the infinite format puts the far plane at infinity, where t = 0 under perspective).
struct DepthEncoding {
  double a = 0, b = 1;
  double z(double t) const { return a + b * t; }
  double t(double z) const { return (z - a) * (1.0 / b); }  // the reciprocal folds to a constant per frame
};
DepthEncoding depthEncoding(DepthFormat format, const CameraTransform& camera);

// Whether triangles are clipped against the far plane (not with an infinite far plane
// under perspective).
bool clipsFarPlane(DepthFormat format, Projection projection);

// The stored type, the value a cleared buffer holds (the far end), the test, and the
// next value a stored one can take toward the far end.
struct Float32Depth {
  using Stored = float;
  static constexpr Stored kFar = 1.0f;
  static Stored store(double z) { return static_cast<float>(std::clamp(z, 0.0, 1.0)); }
  static double load(Stored s) { return s; }
  static bool nearer(Stored candidate, Stored current) { return candidate < current; }
  static Stored towardFar(Stored s) { return std::nextafter(s, kFar); }
};
struct ReversedFloat32Depth {
  using Stored = float;
  static constexpr Stored kFar = 0.0f;
  static Stored store(double z) { return static_cast<float>(std::clamp(z, 0.0, 1.0)); }
  static double load(Stored s) { return s; }
  static bool nearer(Stored candidate, Stored current) { return candidate > current; }
  static Stored towardFar(Stored s) { return std::nextafter(s, kFar); }
};
template <typename Integer, int Bits>
struct UnormDepth {
  using Stored = Integer;
  static constexpr double kSteps = double((std::uint64_t{1} << Bits) - 1);
  static constexpr Stored kFar = static_cast<Stored>((std::uint64_t{1} << Bits) - 1);
  // Round to the nearest step (halves up): the clamped value is never negative, so
  // adding one half and truncating is exact and needs no library call per fragment.
  static Stored store(double z) { return static_cast<Stored>(std::clamp(z, 0.0, 1.0) * kSteps + 0.5); }
  static double load(Stored s) { return s / kSteps; }
  static bool nearer(Stored candidate, Stored current) { return candidate < current; }
  static Stored towardFar(Stored s) { return s == kFar ? s : static_cast<Stored>(s + 1); }
};
using Unorm24Depth = UnormDepth<std::uint32_t, 24>;
using Unorm16Depth = UnormDepth<std::uint16_t, 16>;

// The smallest separation the format resolves at view distance `distance`: how much
// farther a surface must lie to be stored as another value (the distance of the next
// value the format can store, toward the far end, less this one's). Infinite at the far
// end of the format's range.
double depthResolution(DepthFormat format, const CameraTransform& camera, double distance);

// Calls visit.template operator()<Format>() with the traits type of `format`, so a
// depth-testing loop is compiled once per format with its comparison inlined.
template <typename Visitor>
decltype(auto) withDepthFormat(DepthFormat format, Visitor&& visit) {
  switch (format) {
    case DepthFormat::float32: return visit.template operator()<Float32Depth>();
    case DepthFormat::reversedFloat32:
    case DepthFormat::reversedFloat32Infinite: return visit.template operator()<ReversedFloat32Depth>();
    case DepthFormat::unorm24: return visit.template operator()<Unorm24Depth>();
    case DepthFormat::unorm16: break;
  }
  return visit.template operator()<Unorm16Depth>();
}

}  // namespace hsr
