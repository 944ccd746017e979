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
  std::vector<std::uint32_t> tied;  // the triangles exactly nearest there: its winner, or all of a certified tie
  bool culled = false;              // the reference's triangle was removed by the culling stages
  std::string culledBy;             // and the stage that removed it ("frustum:object")
  // Whether the algorithm is right here: it shows the reference's triangle, or the pixel
  // is a certified tie, which the error metrics leave out (any of the tied triangles is
  // right; the reference names the lowest).
  bool agrees = false;
  std::string verdict;              // one sentence: agreement, or what made the difference
  std::size_t eventsByStep = 0;     // hsr why --step: how many of the history's events had happened by the step
};

// hsr why --step N: the histories as they stood when the algorithm recorded the Nth of
// the steps hsr render --steps records with the same options (--every as there), the
// finished image the last. The steps are recorded on one thread, their pictures drawn and
// let go: a step is marked by how many events each history held when it was recorded
// (the culling stages' events count from the first step).
struct StepAsked {
  std::size_t number = 0;  // from 1
  std::size_t every = 0;   // StepRecorder's stride: 0, about kFramesPerRun per run
  // What explainPixels found: the steps recorded, and the Nth's caption.
  std::size_t recorded = 0;
  std::string caption;
};

// The algorithm (it must answer why: AlgorithmEntry::answersWhy) run once on the scene at
// its size with the pixels watched (each inside the image, each once), and the reference
// traced through each. Stats: the render's, with "why: events recorded". `step`: hsr why
// --step's (each answer's eventsByStep set), or null; InputError naming --step when the
// algorithm recorded fewer steps.
std::vector<PixelAnswer> explainPixels(const PreparedScene& scene, const Configuration& configuration,
                                       const std::vector<PixelWitness::Pixel>& pixels, int threads, Stats& stats,
                                       StepAsked* step = nullptr);

// The answers as a person reads them, and as JSON (one object: the scene, the algorithm
// and its knobs, the size, its decisions (AlgorithmEntry::whyDecisions), whether it paints
// in order (a list-priority algorithm: AlgorithmEntry::order), the step asked
// about, and per pixel the history, what it
// shows, the reference's answer with its tied triangles, agrees and the verdict; a
// triangle is its global index, null for none). With a step, the text lists the events
// up to it and what the pixel showed then; the JSON gives each pixel's count up to it.
std::string whyText(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration,
                    const std::vector<PixelAnswer>& answers, const StepAsked* step = nullptr);
std::string whyJson(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration,
                    const std::vector<PixelAnswer>& answers, const StepAsked* step = nullptr);

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
  bool agrees = false;               // they disagree on no more than rounding (0.001 pixel)
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
