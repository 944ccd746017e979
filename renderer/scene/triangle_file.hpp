// The triangle file: a scene as world-space triangles and a camera, in plain text, for
// programs outside the suite (hsr grade hands one to a student's program in any
// language, coursework.md "Handing in a program"). Its format, line by line (# starts a
// comment; numbers as C's strtod reads them):
//
//   hsr-triangles 1
//   size W H                         the image, in pixels
//   projection perspective           or orthographic
//   eye X Y Z                        the camera, as a scene file's [camera] has it
//   target X Y Z
//   up X Y Z
//   fov_y DEGREES                    perspective only; orthographic: height WORLD_UNITS
//   near N
//   far F
//   clip_from_world                  the same camera as one matrix, four rows of four:
//   M00 M01 M02 M03                  (x, y, d, w) = M (p, 1), d the distance along the
//   ...                              view axis, w = d (perspective) or 1 (orthographic)
//   triangles T
//   AX AY AZ BX BY BZ CX CY CZ [O]   T lines; the triangle on line k has id k (from 1);
//                                    O, the object it belongs to (a run of lines with one
//                                    O is an object, which culling stages cull whole;
//                                    its corners at exactly equal coordinates are one
//                                    vertex, so its faces meet at shared edges)
//
// A pixel (i, j) is sampled at its center; a point's pixel coordinates are
// ((x / w + 1) W / 2, (1 - y / w) H / 2), row 0 at the top (renderer/util/conventions.hpp).
// What is visible at a center is the nearest triangle with near <= d <= far there.
#pragma once

#include <filesystem>
#include <string>

#include "renderer/scene/prepare.hpp"
#include "renderer/scene/scene.hpp"

namespace hsr {

// The prepared scene's triangles (every instance, in id order) and camera, at its size.
std::string triangleFileText(const PreparedScene& scene);

// Reads a triangle file into a scene, an object per run of one object number; the
// camera from its parameters (the matrix is for other programs, and is not read).
// Throws InputError("FILE:LINE: what, expected ...") on anything else.
Scene parseTriangleFile(const std::string& text, const std::filesystem::path& file);

}  // namespace hsr
