// The renders every target must give bit for bit the same, as lines of hashes: every
// shipped scene and hard case with every algorithm in the configurations the goldens
// cover, and N seeded random scenes (tests/property/random_scene.hpp) with the surface
// algorithms; one line per render: the scene, the configuration, then a hash of each
// image's bits (ids, depth, colour; a line algorithm's drawing), or the one-line reason
// the configuration refused the scene. hsr_identity (identity_main.cpp) prints them on
// every target scripts/cross.sh builds; the browser edition (web/) computes them in the
// page; tests/identity/expected.txt holds them as this suite's goldens hold images.
// It uses the core alone (renderer, algorithms, pipeline): no image library, no files
// written, nothing a target might lack.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace hsr::identity {

struct Options {
  int width = 320;              // the shipped scenes' width (the goldens'); the height keeps each scene's aspect
  int randomScenes = 100;       // seeds 1 .. N, at the property tests' 32 pixels wide
  int threads = 1;
  std::string only;             // only the shipped scenes whose name holds this
};

// Each render's line, in order: the shipped scenes under `scenes` by name (the study
// levels left out: too large), then the random scenes.
void renderLines(const std::filesystem::path& scenes, const Options& options, const std::function<void(const std::string&)>& line);

}  // namespace hsr::identity
