// Potentially visible sets (Airey 1990; Teller and Séquin 1991; shipped by the
// Quake-family engines): for every cell, once per level, the objects that can be seen
// from somewhere in it. A frame then costs a lookup: the eye's cell's set is drawn.
// Two ways to build the sets (knob `build`), the accuracy-against-time lesson applied to
// precomputation:
//
//   sampled       Airey's way: eye points spread through each cell (`samples`, a Halton
//                 sequence), from each the six faces of a cube map (`resolution`
//                 pixels a side) traced with the exact reference; the set is every object
//                 some ray hit. Aggressive: an object seen only from places no sample
//                 stood, or between the rays, is missing, and a walkthrough that comes
//                 there loses it (the indoor study counts the frames).
//   conservative  Teller's idea with the Quake vis tool's test: from each portal S out of
//                 the cell, chains of portals are followed as long as a line could pass
//                 them all. A portal P further on is cut to the part beyond the plane of
//                 every portal crossed, and by the separating planes of S and the last
//                 portal passed (a plane through an edge of one and a corner of the
//                 other, with each wholly on its own side: a line through both stays on
//                 the far one); nothing left, no line. S itself is cut to the near side of
//                 each portal's plane as the chain goes on. An object of a cell reached
//                 is in the set unless its box is wholly behind one of those planes.
//                 Never misses an object; keeps more than can be seen (every stabbing
//                 line that the planes admit, and everything hidden by furniture).
//
// The sets can be built once and kept in a file (`hsr pvs build SCENE --out FILE`, one
// line per cell, each naming its cell and objects) with a fingerprint of the level and
// the build's settings: `--cull pvs:cache=FILE` reads it, and refuses a file built for
// another level or other settings. Without a cache the stage builds the sets itself,
// once per walk ("pvs: built now").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "algorithms/culling/cells/cells.hpp"
#include "algorithms/culling/culling.hpp"

namespace hsr::culling::pvs {

enum class Build { sampled, conservative };

struct Knobs {
  int variant = 0;  // one variant: the eye's cell's set
  Build build = Build::conservative;
  int samples = 64;     // sampled: eye points per cell
  int resolution = 64;  // sampled: pixels a side of each cube-map face
  int maxChains = 1 << 18;  // conservative: chains followed from a cell before giving up
  std::string cache;        // a file hsr pvs build wrote; empty: build the sets now
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .variants(&Knobs::variant, {{0, "cell", "the precomputed set of the eye's cell: every object seen from somewhere in it"}},
                    "the lookup")
          .choice("build", &Knobs::build, {{Build::conservative, "conservative"}, {Build::sampled, "sampled"}},
                  "conservative: chains of portals a line can pass (never misses); sampled: eye points traced with the exact "
                  "reference (misses what no sample saw)")
          .number("samples", &Knobs::samples, {1, 100000}, {"4", "16", "256"}, "sampled: eye points per cell")
          .number("resolution", &Knobs::resolution, {1, 4096}, {"16", "128"}, "sampled: pixels a side of each cube-map face")
          .number("max-chains", &Knobs::maxChains, {1, 1e9}, {"1000"},
                  "conservative: portal chains followed from a cell before its search gives up and takes every object connected to it")
          .file("cache", &Knobs::cache, "the sets hsr pvs build --out FILE wrote for this level and these settings (none: build them now)");
  return table;
}

struct VisibleSets {
  std::vector<std::vector<std::uint32_t>> objects;  // per cell, the instances in its set, ascending
  double seconds = 0;                               // the build's time
  std::int64_t work = 0;                            // sampled: rays traced; conservative: portal chains followed
  std::int64_t cellsGivenUp = 0;                    // conservative: cells whose search passed `max-chains`: each takes
                                                    // every object of every cell connected to it
};

// Builds the sets as `knobs` say, on `threads` threads (0: all cores; the same sets for
// any count). Counts "pvs: rays traced" or "pvs: chains followed", "pvs: cells given
// up", "pvs: objects in all sets" (summed over the cells), and phase "pvs build".
VisibleSets build(const PreparedScene& scene, const cells::CellMap& map, const Knobs& knobs, int threads, Stats& stats);

// A hash of what the sets depend on: every object's box, the cells and the portals.
std::string fingerprint(const PreparedScene& scene);
// Writes the sets (whole or not at all). Throws InputError when the file cannot be written.
void writeCache(const std::filesystem::path& path, const PreparedScene& scene, const Knobs& knobs, const VisibleSets& sets);
// The cached sets. Throws InputError ("file:line: what, expected ...") for a file that is
// absent, not a cache, or built for another level or other settings.
VisibleSets readCache(const std::filesystem::path& path, const PreparedScene& scene, const Knobs& knobs);

// The triangles of `in` of the objects in the eye's cell's set (the union of the sets of
// the cells the eye is in, on a shared face). Counts "pvs: objects in the set", and notes
// "pvs: the eye's cells" and "pvs: the set" by name. With why, says for hsr why's
// objects whether the set holds them.
VisibleSet cull(const PreparedScene& scene, const cells::CellMap& map, const VisibleSets& sets, const CameraTransform& camera,
                const VisibleSet& in, Stats& stats, StageWitness* why = nullptr);

// The stage's entry in culling::stages().
StageEntry stage();

}  // namespace hsr::culling::pvs
