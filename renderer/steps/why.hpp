// Why a pixel came out as it did (hsr why): the events an algorithm's own loops meet at
// the pixels asked about, in the order they meet them, each with what the loop decided
// and the numbers it decided by. As with steps, an algorithm is handed a PixelWitness
// only when one is asked for (a null pointer otherwise, so a render without hsr why does
// no provenance work at all), and it records from its own loops: never a second
// implementation of the algorithm.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace hsr {

// A number in hsr why's answers: 9 significant digits, enough to tell apart the places
// and distances a loop compared.
inline std::string whyNumber(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

struct PixelEvent {
  std::uint32_t id = 0;  // the triangle the event is about: global index + 1 (0: the background)
  std::string outcome;   // what the loop decided, in the textbook's words ("written", "lost the depth test")
  std::string detail;    // the numbers it decided by, in the algorithm's own terms
  // The event's depth as the algorithm stored it, decoded to a distance along the view
  // axis (as Frame::depth measures it); NaN when the event has none.
  double distance = std::numeric_limits<double>::quiet_NaN();
  bool shown = false;  // after the event, the pixel shows its triangle
  // What the event is about when it is not a triangle (a window Warnock examined): named
  // in the triangle's place; empty for a triangle's event.
  std::string subject;
};

// hsr why --edge: what a line algorithm met deciding one edge of its drawing (Appel's
// walk along it, Roberts' test of each body), in the order it met it. Handed to the
// algorithm only when asked, as PixelWitness is.
// An EdgeEvent's place when it is about the whole edge, not a place on it.
inline constexpr double kWholeEdge = std::numeric_limits<double>::quiet_NaN();

struct EdgeEvent {
  // Where along the edge's projection: 0 at its start, 1 at its end; NaN for an event
  // about the whole edge (Roberts' test of one body).
  double u = 0;
  // The QI's change there, as Appel's walk meets it (0: none, or counted afresh); for the
  // algorithms that only know hidden or not, +1 where the edge may go out of sight
  // (Roberts: a body's hidden part begins) and -1 where it comes into sight.
  int change = 0;
  std::string outcome;  // what the algorithm decided there, in the textbook's words
  std::string detail;   // the numbers it decided by
  std::string subject = {};  // what the event is about besides the edge (Roberts: the body tested); empty: the edge itself
};
struct EdgeWitness {
  std::uint32_t edge = 0;  // the edge asked about: its index in the drawing's edges
  std::vector<EdgeEvent> events;
};

class PixelWitness {
 public:
  struct Pixel {
    int x, y;
  };
  // The pixels asked about (inside an image `width` pixels wide), each once.
  PixelWitness(std::vector<Pixel> pixels, int width);

  // The history of pixel (x, y) when it is one asked about, else null. An algorithm's
  // loops call this where they decide a pixel; a pixel is decided by one thread at a
  // time, so the histories need no lock.
  std::vector<PixelEvent>* at(int x, int y) {
    const auto found = std::lower_bound(keys_.begin(), keys_.end(), key(x, y));
    return found != keys_.end() && *found == key(x, y) ? &histories_[std::size_t(found - keys_.begin())] : nullptr;
  }

  // visit(x, history) for each pixel asked about in row y between columns a and b - 1, left
  // to right: for a loop that decides a run of pixels at once.
  template <typename Visit>
  void forEachInRun(int y, int a, int b, Visit&& visit) {
    if (a >= b) return;
    for (auto k = std::lower_bound(keys_.begin(), keys_.end(), key(a, y)); k != keys_.end() && *k < key(b, y); ++k)
      visit(int(*k - key(0, y)), histories_[std::size_t(k - keys_.begin())]);
  }

  // visit(x, y, history) for each pixel asked about, row by row: for a loop that decides
  // shapes rather than pixels, which asks each shape whether it holds the pixel.
  template <typename Visit>
  void forEachPixel(Visit&& visit) {
    for (std::size_t k = 0; k < keys_.size(); ++k)
      visit(int(keys_[k] % std::uint64_t(width_)), int(keys_[k] / std::uint64_t(width_)), histories_[k]);
  }

  std::size_t count() const { return pixels_.size(); }
  const Pixel& pixel(std::size_t asked) const { return pixels_[asked]; }
  // The asked-th pixel's history, in the order the algorithm met the events.
  const std::vector<PixelEvent>& history(std::size_t asked) const;
  // Every event recorded, at all pixels (the counter "why: events recorded").
  std::int64_t events() const;

 private:
  std::uint64_t key(int x, int y) const { return std::uint64_t(y) * std::uint64_t(width_) + std::uint64_t(x); }
  int width_;
  std::vector<Pixel> pixels_;               // as asked
  std::vector<std::uint64_t> keys_;         // the pixels' keys, ascending
  std::vector<std::size_t> placeOfAsked_;   // pixels_[i]'s key is keys_[placeOfAsked_[i]]
  std::vector<std::vector<PixelEvent>> histories_;  // by keys_' order
};

}  // namespace hsr
