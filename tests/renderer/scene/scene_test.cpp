// Scene loading: the shipped scenes load as described, and every kind of bad input is
// refused with file:line, the key path and what was expected.
#include <gtest/gtest.h>

#include <fstream>

#include "renderer/scene/obj.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/error.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

TEST(Scene, ShippedScenesLoadWithTheirDescribedContents) {
  const PreparedScene cube(loadScene(test::sourcePath("scenes/cube.toml")));
  EXPECT_EQ(cube.triangleCount(), 12u);
  const Scene counters = loadScene(test::sourcePath("scenes/counters.toml"));
  EXPECT_EQ(counters.objects[1].instancing.copyCount(), 31u);
  EXPECT_EQ(counters.objects[1].mesh->triangles.size(), 588u);
  const Scene trees = loadScene(test::sourcePath("scenes/trees.toml"));
  EXPECT_EQ(trees.objects[1].instancing.copyCount(), 135u);
  EXPECT_EQ(trees.objects[1].mesh->triangles.size(), 424u);
  const Scene dragons = loadScene(test::sourcePath("scenes/dragons.toml"));
  EXPECT_EQ(dragons.objects[0].instancing.copyCount(), 4u);
  EXPECT_EQ(PreparedScene(dragons).triangleCount(), 4u * 99784u);
}

TEST(Scene, RingCopiesSurroundTheCenterFacingIt) {
  Instancing ring;
  ring.kind = Instancing::Kind::ring;
  ring.count = 4;
  ring.radius = 25;
  const std::vector<dmat4> copies = ring.copies();
  ASSERT_EQ(copies.size(), 4u);
  const dvec3 expected[4] = {{0, 0, -25}, {-25, 0, 0}, {0, 0, 25}, {25, 0, 0}};
  for (int k = 0; k < 4; ++k) {
    const dvec3 position(copies[std::size_t(k)] * dvec4(0, 0, 0, 1));
    EXPECT_NEAR(glm::distance(position, expected[k]), 0.0, 1e-9) << k;
    const dvec3 front(copies[std::size_t(k)] * dvec4(0, 0, 1, 0));  // the copy's +z side
    EXPECT_NEAR(glm::dot(front, -glm::normalize(position)), 1.0, 1e-12) << "copy " << k << " faces the center";
  }
}

TEST(Scene, ScatterIsDeterministicAndStaysInItsAnnulus) {
  Instancing scatter;
  scatter.kind = Instancing::Kind::scatter;
  scatter.count = 500;
  scatter.innerRadius = 4;
  scatter.radius = 45;
  scatter.seed = 7;
  const auto first = scatter.copies(), second = scatter.copies();
  for (std::size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(first[k], second[k]);
    const double r = glm::length(dvec3(first[k][3]));
    EXPECT_GE(r, 4.0);
    EXPECT_LE(r, 45.0);
  }
}

// Writes `text` to a file named `name` and returns what loading it says.
template <typename Load>
std::string errorOfLoading(const std::string& name, const std::string& text, Load&& load) {
  const auto file = test::outputPath(name);
  std::ofstream(file) << text;
  try {
    load(file);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(loaded without error)";
}

std::string errorOf(const std::string& toml) {
  return errorOfLoading("scene_test.toml", toml, [](const auto& file) { loadScene(file); });
}

const std::string kCamera = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n";
const std::string kBox = "[[objects]]\nshape = \"box\"\n";
const std::string kLight = "[[lights]]\ndirection = [0, -1, 0]\n";

TEST(Scene, BadInputNamesFileLineKeyAndExpectation) {
  const struct {
    std::string toml, expected;
  } cases[] = {
      {kCamera + kBox + "colour = [1, 0, 0]\n", "scene_test.toml:6:1: objects[0].colour: unknown key; expected one of name, shape"},
      {kCamera + kBox + "size = \"big\"\n", ":6:8: objects[0].size: expected a number or an array of 3 numbers"},
      {kCamera + kBox + "color = [1.5, 0, 0]\n", "objects[0].color: expected a finite number in [0, 1], got 1.5"},
      {kCamera + "fov_y = 180\n" + kBox, ":4:9: camera.fov_y: expected a finite number in [0.01, 179], got 180"},
      {kCamera + "far = 0.01\n" + kBox, "camera.far: must be greater than near"},
      {kCamera + "up = [0, 0, 1]\n" + kBox, "camera.up: must not be parallel to the view direction"},
      {"[camera]\neye = [0, 0, 5]\n" + kBox, "camera.target: missing; expected an array of 3 numbers"},
      {kCamera + "azimuth = 30\nelevation = 20\ndistance = 5\n" + kBox,
       ":2:7: camera.eye: give either eye or azimuth, elevation and distance, not both"},
      {"[camera]\ntarget = [0, 0, 0]\nup = [0, 1, 0]\nazimuth = 30\nelevation = 20\ndistance = 5\n" + kBox,
       ":3:6: camera.up: is implied by azimuth and elevation; leave it out"},
      {"[camera]\ntarget = [0, 0, 0]\nazimuth = 30\nelevation = 95\ndistance = 5\n" + kBox,
       ":4:13: camera.elevation: expected a finite number in [-90, 90], got 95"},
      {"[camera]\ntarget = [0, 0, 0]\nazimuth = 30\nelevation = 20\n" + kBox, "camera.distance: missing; expected a number"},
      {kBox, "camera: missing; expected a [camera] table"},
      {kCamera, "objects: missing; expected at least one [[objects]] table"},
      // A mistyped table is reported as itself, at its line, before anything is found missing.
      {kCamera + "[[object]]\nshape = \"box\"\n",
       ":4:3: object: unknown table; expected one of image, camera, effects, shadows, fog, outline, ambient, lights, objects, "
       "cells, portals (did you mean objects?)"},
      {"[camra]\neye = [0, 0, 5]\n" + kBox, ":1:2: camra: unknown table; expected one of image, camera"},
      {kCamera + kBox + "colour = [1, 0, 0]\n", "(did you mean color?)"},
      {kCamera + kBox + "shape = \"teapot\"\n", "not valid TOML"},
      {kCamera + "[[objects]]\nshape = \"teapot\"\n", "objects[0].shape: expected one of mesh, box, sphere"},
      {kCamera + "[[objects]]\nshape = \"mesh\"\nfile = \"nowhere.obj\"\n",
       "objects[0].file: " + test::outputPath("nowhere.obj").string() + ": cannot open the OBJ file"},
      {"effects = [\"lambert\"]\n" + kCamera + kBox, "effects: lambert shading needs at least one [[lights]] table"},
      {"effects = [\"gouraud\"]\n" + kCamera + kBox,
       ":1:12: effects[0]: expected one of none, flat, lambert, phong, shadows, transparency, fog, outline, got 'gouraud'"},
      {"effects = [\"flat\", \"phong\"]\n" + kCamera + kBox,
       ":1:20: effects[1]: only one shading effect (none, flat, lambert, phong) may be listed"},
      {"effects = [\"fog\", \"fog\"]\n" + kCamera + kBox, ":1:19: effects[1]: fog is listed twice"},
      {"effects = [\"shadows\"]\n" + kCamera + kBox, "effects: shadows need a lit shading effect (flat, lambert or phong) to darken"},
      {"[fog]\nstart = 1\n" + kCamera + kBox, ":1:1: fog: settings for an effect the scene does not list; add \"fog\" to effects"},
      {"effects = [\"fog\"]\n[fog]\nstart = 5\nend = 5\n" + kCamera + kBox, "fog.end: must be greater than start"},
      {"effects = [\"fog\"]\n[fog]\nkind = \"exponential\"\nend = 5\n" + kCamera + kBox,
       ":4:1: fog.end: unknown key; expected one of kind, density, color"},
      {"effects = [\"flat\", \"shadows\"]\n[shadows]\nresolution = 0\n" + kCamera + kBox + kLight,
       "shadows.resolution: expected an integer in [1, 8192], got 0"},
      {"effects = [\"lambert\"]\n" + kCamera + kBox + "shininess = 8\n" + kLight,
       "objects[0].shininess: a material's highlight needs \"phong\" in the scene's effects"},
      {"[image]\nwidth = 0\n" + kCamera + kBox, ":2:9: image.width: expected an integer in [1, 16384], got 0"},
      {"[image]\nwidth = 16384\nheight = 16385\n" + kCamera + kBox, "image.height: expected an integer in [1, 16384]"},
      {kCamera + "[[objects]]\nshape = \"sphere\"\nsegments = 2\n", "objects[0].segments: expected an integer in [3, 4096], got 2"},
      {kCamera + kBox + "[objects.copies]\nkind = \"ring\"\ncount = 5\n", "objects[0].copies.radius: missing; expected a number"},
      {kCamera + kBox + "[objects.copies]\nkind = \"grid\"\ncount = [1000, 1000, 1000]\nspacing = 1\n",
       "objects[0].copies.spacing: expected an array of 3 numbers"},
      {kCamera + kBox + "[objects.copies]\nkind = \"grid\"\ncount = [1000, 1000, 1000]\nspacing = [1, 1, 1]\n",
       "the scene exceeds 16777215 triangles"},
  };
  for (const auto& c : cases) EXPECT_NE(errorOf(c.toml).find(c.expected), std::string::npos) << errorOf(c.toml);
}

std::string objErrorOf(const std::string& text) {
  return errorOfLoading("scene_test.obj", text, [](const auto& file) { loadObj(file); });
}

TEST(Obj, BadInputNamesFileAndLine) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_NE(objErrorOf(triangle + "f 1 2 3\n").find("loaded without error"), std::string::npos);
  EXPECT_NE(objErrorOf("v 0 0 0\nv 1 abc 0\n").find("scene_test.obj:2: vertex needs three numbers x y z"), std::string::npos);
  EXPECT_NE(objErrorOf("v 0 0\n").find(":1: vertex needs three numbers"), std::string::npos);
  EXPECT_NE(objErrorOf("v 0 nan 0\n").find(":1: vertex coordinate is not finite (NaN or Inf), got 'nan'"), std::string::npos);
  EXPECT_NE(objErrorOf("v 0 0 inf\n").find(":1: vertex coordinate is not finite"), std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "f 1 2 4\n").find(":4: face index 4 is out of range: 3 vertices are defined before this line"),
            std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "f 1 2 -4\n").find(":4: face index -4 is out of range"), std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "f 1 2 0\n").find(":4: face corner '0' is not a vertex index"), std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "f 1 2\n").find(":4: face needs at least 3 corners, got 2"), std::string::npos);
  EXPECT_NE(objErrorOf(triangle).find(":3: no faces"), std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "vn 0 nan 1\n").find(":4: normal needs three finite numbers x y z of at most 1e12 in size, got 'vn 0 nan 1'"),
            std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "vn 0 0 1\nf 1//1 2//1 3//2\n")
                .find(":5: face corner '3//2' names normal 2, but 1 normals (vn) are defined before this line"),
            std::string::npos);
  EXPECT_NE(objErrorOf(triangle + "vn 0 0 1\nf 1//1 2//1 3//x\n").find(":5: face corner '3//x' names normal x"), std::string::npos);
  // Normals where the file gives them, zero (to be computed) where it does not.
  objErrorOf(triangle + "v 1 1 0\nvn 0 0 1\nvn 0 0.6 0.8\nf 1//1 2//2 3//1\nf 2 4 3\n");
  const Mesh withNormals = loadObj(test::outputPath("scene_test.obj"));
  ASSERT_EQ(withNormals.cornerNormals.size(), 2u);
  EXPECT_EQ(withNormals.cornerNormals[0][1], dvec3(0, 0.6, 0.8)) << "normals are read as correctly rounded doubles";
  EXPECT_EQ(withNormals.cornerNormals[1][0], dvec3(0));
  EXPECT_TRUE(loadObj((objErrorOf(triangle + "f 1 2 3\n"), test::outputPath("scene_test.obj"))).cornerNormals.empty());
  // Negative (relative) indices and slashes are valid OBJ.
  EXPECT_EQ(loadObj((objErrorOf(triangle + "f -3/1 -2/2 -1/3\n"), test::outputPath("scene_test.obj"))).triangles.size(), 1u);
}

// Every input path keeps double precision (README, "Robustness"): OBJ numbers are read
// correctly rounded, as std::from_chars reads them, so a file far from the origin keeps
// separations far below a float's step, and numbers an exporter wrote exactly stay exact.
TEST(Obj, CoordinatesAreCorrectlyRoundedDoubles) {
  const Mesh mesh = parseObj("v 100000.0000005 0 -9.75702e+06\nv 100000 1e-310 0.1\nv 0.333333 8 1\nf 1 2 3\n", "far.obj");
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0].x, 100000.0000005);      // a float would read 100000
  EXPECT_EQ(mesh.positions[0].x - mesh.positions[1].x, 100000.0000005 - 100000.0);
  EXPECT_EQ(mesh.positions[0].z, -9757020.0);          // tinyobjloader's own parser reads -9757019.9999999981
  EXPECT_EQ(mesh.positions[1].y, 1e-310);
  EXPECT_EQ(mesh.positions[2].x, 0.333333);
  // Every one of the bunny's values as std::from_chars reads it.
  const Mesh bunny = loadObj(test::sourcePath("models/bunny.obj"));
  EXPECT_EQ(bunny.positions[0], dvec3(1.301895, 0.122622, 2.550061));
}

TEST(Obj, StatedRoundingIsHalfAUnitInTheLastDigitOfSixOrMoreDigits) {
  const auto rounding = [](const std::string& coordinates) { return parseObj(coordinates + "\nv 0 0 0\nv 1 0 0\nf 1 2 3\n", "x.obj").statedRounding; };
  EXPECT_EQ(rounding("v 1 0.25 -3"), 0);                      // short numbers are exact
  EXPECT_EQ(rounding("v 1.5e-3 2 0"), 0);
  EXPECT_DOUBLE_EQ(rounding("v 0.333333 0 0"), 5e-7);         // %g: six digits
  EXPECT_DOUBLE_EQ(rounding("v 1.000000 0 0"), 5e-7);         // %.6f
  EXPECT_DOUBLE_EQ(rounding("v 123456 0 0"), 0.5);
  EXPECT_DOUBLE_EQ(rounding("v 1.2345678e-3 0 0"), 5e-11);
  EXPECT_DOUBLE_EQ(rounding("v 1.000000 -1234.56789 0.5"), 5e-6);  // the largest of the file's
}

}  // namespace
}  // namespace hsr
