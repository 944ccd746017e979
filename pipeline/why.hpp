// hsr why: how an algorithm decided a pixel, from its own loops, beside the exact
// reference's certified answer for the same pixel, and why the two differ when they do.
//
// The algorithm runs once with a PixelWitness (renderer/steps/why.hpp) for the pixels
// asked about: its loops record every event they meet there (for the z-buffer, every
// fragment tested, with its stored depth, what the pixel held and the outcome). The
// reference traces the ray through each pixel's center as the whole-image reference
// does (renderer/reference/reference.hpp): the winner, its distance, whether exact
// arithmetic decided it and whether the pixel is a certified tie.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/pipeline.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/steps/why.hpp"

namespace hsr::pipeline {

struct PixelAnswer {
  PixelWitness::Pixel pixel;
  std::vector<PixelEvent> history;  // in the order the algorithm's loops met the events
  std::uint32_t shown = 0;          // the id the algorithm's frame holds there (0: background)
  double distance = 0;              // and its depth (+infinity for the background)
  ReferenceHit reference;           // the exact reference's certified answer
  bool culled = false;              // the reference's triangle was removed by the culling stages
  std::string culledBy;             // and the stage that removed it ("frustum:object")
  // Whether the algorithm is right here: it shows the reference's triangle, or the pixel
  // is a certified tie (any of the tied triangles is right; the reference names the lowest).
  bool agrees = false;
  std::string verdict;              // one sentence: agreement, or what made the difference
};

// The algorithm (it must answer why: AlgorithmEntry::answersWhy) run once on the scene at
// its size with the pixels watched (each inside the image, each once), and the reference
// traced through each. Stats: the render's, with "why: events recorded".
std::vector<PixelAnswer> explainPixels(const PreparedScene& scene, const Configuration& configuration,
                                       const std::vector<PixelWitness::Pixel>& pixels, int threads, Stats& stats);

// The answers as a person reads them, and as JSON (one object: the scene, the algorithm
// and its knobs, the size, and per pixel the history, what it shows, the reference's
// answer, agrees and the verdict; a triangle is its global index, null for none).
std::string whyText(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration,
                    const std::vector<PixelAnswer>& answers);
std::string whyJson(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration,
                    const std::vector<PixelAnswer>& answers);

// hsr why --edge: how a line algorithm decided one edge of its drawing, from its own walk
// (AlgorithmEntry::drawLinesWatchingEdge), beside the exact line reference's answer for
// the same edge.
struct EdgeAnswer {
  std::uint32_t edge = 0;
  double pixelsAway = -1;            // asked by a pixel: how far the edge passes from its center; -1: asked by number
  FeatureEdge drawn;                 // the edge, as the drawing has it
  std::vector<EdgeEvent> walk;       // what the walk met along it, in order
  std::vector<LineSegment> pieces;   // the algorithm's pieces of it, with their QI
  std::vector<Interval> referenceVisible;  // where the exact line reference sees it (sorted, disjoint, in u)
  double differingPixels = 0;        // the length, in pixels, where the two disagree on visibility
  std::string verdict;
};

// The edge asked about: "N", an index into the drawing's edges, or "X,Y", the edge passing
// nearest the center of pixel (X, Y) (within 3 pixels); InputError naming --edge otherwise.
// Runs the algorithm twice: to find the edge, then with the walk watched.
EdgeAnswer explainEdge(const PreparedScene& scene, const Configuration& configuration, const std::string& edgeText, int threads,
                       Stats& stats);
std::string edgeText(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration, const EdgeAnswer& answer);
std::string edgeJson(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration, const EdgeAnswer& answer);

// InputError ("--algo NAME: hsr why follows the loops of zbuffer so far; ...") for an
// algorithm that does not answer why at a pixel (--pixel), or along an edge (--edge).
void checkAnswersWhy(const AlgorithmEntry& algorithm);
void checkAnswersWhyAlongEdges(const AlgorithmEntry& algorithm);
// "X,Y" as a pixel of a width x height image, or InputError naming --pixel and what was
// expected.
PixelWitness::Pixel pixelOf(const std::string& text, int width, int height);

}  // namespace hsr::pipeline
