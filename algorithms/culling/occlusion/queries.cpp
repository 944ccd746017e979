// The query methods (queries.hpp has the strategies and why they differ).
#include "algorithms/culling/occlusion/queries.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

#include "algorithms/culling/frustum.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr::culling::occlusion {
namespace {

// The chance that a node found hidden by its last `framesHidden` answers stays hidden:
// 0.29 with none, 0.73 after one, above 0.98 after five. CHC++ fits a curve of this
// shape to its measurements; this one is ours, and only shapes the multiqueries.
double chanceStaysHidden(int framesHidden) { return 0.99 - 0.7 * portable::exp(-double(framesHidden)); }

// A well-mixed 64-bit hash (splitmix64's finalizer): the "random" first wait of a leaf
// that turns visible, the same on every run.
std::uint64_t mixed(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Query boxes are grown by this much of a pixel. The rasterizer snaps a box's corners
// to 1/256 pixel and leaves out pixel centers on its outline's right and bottom edges,
// so an object seen at a pixel center a hair inside its box's outline could be missed;
// and a box's face resting on a surface already drawn (an object standing on the
// ground) ties with it in float depth. Grown by 1/16 pixel, and so moved that much
// nearer, the box covers every such pixel, and its query passes there.
constexpr double kMarginPixels = 1.0 / 16;

// How wide a pixel is in the world at view depth 1 under perspective (it grows with the
// depth), or at any depth under orthographic projection: the larger of its two sides.
double worldPerPixelAtUnitDepth(const CameraTransform& camera) {
  // A view-space point one unit right and up, one unit ahead, in clip space.
  const ClipVertex clip = camera.clipFromView(dvec3(1, 1, -1));
  return std::max(2 / (clip.x * camera.width()), 2 / (clip.y * camera.height()));
}

// A box's nearest and farthest points along the view axis, measured from the eye.
struct ViewExtent {
  double nearest, farthest;
};
ViewExtent alongView(const CameraTransform& camera, const Aabb& box) {
  const double center = glm::dot(box.center() - camera.camera().eye, camera.forward());
  const double reach = glm::dot((box.hi - box.lo) * 0.5, glm::abs(camera.forward()));
  return {center - reach, center + reach};
}

// A node waiting in the traversal queue: nearest first (ties by index, so every run
// walks the same way), with the view volume's planes its parent was not wholly inside.
struct Queued {
  double distance;
  std::uint32_t node, planes;
  bool operator>(const Queued& other) const { return distance != other.distance ? distance > other.distance : node > other.node; }
};

// A query in flight: the nodes it asks about (several for a multiquery), and whether
// the one node was visible last frame (chc: its answer is for the next frame).
struct InFlight {
  PendingQuery query;
  std::vector<Queued> nodes;
  bool wasVisible = false;
  bool atEye = false;  // a box at the eye: visible, no query asked
};

// hsr why's word for a node whose box reaches the near plane, visible without a query.
constexpr const char* kVisibleAtEye = "its box reaches the near plane: visible without a query";

class Traversal {
 public:
  // `watched`: hsr why asks what was decided about some objects (explain()).
  Traversal(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs, const VisibleSet& in, QueryMemory& memory,
            SimulatedGpu& gpu, bool watched)
      : scene_(scene), camera_(camera), knobs_(knobs), in_(in), memory_(memory), gpu_(gpu), hierarchy_(*memory.hierarchy),
        volume_(scene, camera), runs_(trianglesByInstance(scene, in)), drawn_(scene.instances().size(), 0), frame_(memory.frame),
        worldPerPixel_(worldPerPixelAtUnitDepth(camera)), decided_(watched ? hierarchy_.nodes().size() : 0) {}

  void stopAndWait();
  void delayed();
  void coherent(bool plusPlus);

  // The triangles of `in` of the objects drawn, in order.
  VisibleSet drawnSet() const;
  void count(Stats& stats) const;
  // hsr why: for each object asked about, what was last decided on the way down to it:
  // at its leaf, or at the node above it where the walk stopped (watched only).
  void explain(StageWitness& why) const;

 private:
  // Shared steps.
  QueryMemory::Node& state(std::uint32_t node) { return memory_.nodes[node]; }
  const HierarchyNode& node(std::uint32_t index) const { return hierarchy_.nodes()[index]; }
  void enqueue(std::uint32_t index, std::uint32_t planes);
  Queued nearest();
  bool inView(Queued& entry);
  // The box grown by kMarginPixels of a pixel (at its farthest point), as it is queried.
  Aabb widened(const Aabb& box) const;
  // Whether a node's box, widened, reaches the near plane: visible, never queried.
  bool atEye(const Aabb& box) const;
  // The boxes a node is bounded by (chcpp's tight bounds, or its own), and those widened,
  // as it is queried.
  std::vector<Aabb> boundingBoxes(std::uint32_t index) const;
  std::vector<Aabb> queryBoxes(std::uint32_t index) const;
  bool visible(std::int64_t passed) const { return passed > knobs_.threshold; }
  // hsr why: what a query's answer said, and what was decided at a node: `say()` (the
  // text) is called only when watched, so that a render not asked about builds none.
  std::string answered(std::int64_t passed) const;
  template <typename Say>
  void decide(std::uint32_t index, Say&& say) {
    if (!decided_.empty()) [[unlikely]]
      decided_[index] = say();
  }
  void drawLeaf(std::uint32_t index);
  // A leaf drawn, an inner node's children queued.
  void open(const Queued& entry);
  // chc, chcpp: a node found visible makes its ancestors visible too.
  void pullUpVisibility(std::uint32_t index);
  // chc, chcpp: queries a node (or, for chcpp, several together); one at the eye is answered at once.
  void issue(std::vector<Queued> nodes, bool wasVisible);
  void handleAnswer(const InFlight& answer);
  void issueHiddenBatch();
  // chcpp: the oldest visible leaf waiting in the queue, asked about, then drawn.
  void askAndDrawVisibleLeaf();

  const PreparedScene& scene_;
  const CameraTransform& camera_;
  const Knobs& knobs_;
  const VisibleSet& in_;
  QueryMemory& memory_;
  SimulatedGpu& gpu_;
  const ObjectHierarchy& hierarchy_;
  frustum::ViewVolume volume_;
  std::vector<TriangleRun> runs_;
  std::vector<std::uint8_t> drawn_;
  const std::int64_t frame_;
  const double worldPerPixel_;  // a pixel's width in the world at view depth 1 (perspective), or anywhere (orthographic)

  std::priority_queue<Queued, std::vector<Queued>, std::greater<>> traversal_;
  std::deque<InFlight> inFlight_;
  std::vector<Queued> hiddenBatch_;  // chcpp: nodes hidden last frame, their queries not yet issued
  std::deque<Queued> visibleBatch_;  // chcpp: leaves visible last frame, queried when the CPU would wait

  std::vector<std::string> decided_;  // per node, with hsr why: what was last decided there

  std::int64_t visited_ = 0, issued_ = 0, nodesQueried_ = 0, answeredVisible_ = 0;
  std::int64_t multiqueries_ = 0, multiqueriesReasked_ = 0, atEye_ = 0, objectsDrawn_ = 0;
};

// ---------------------------------------------------------------------------------
// The shared steps

void Traversal::enqueue(std::uint32_t index, std::uint32_t planes) {
  // Nearest first: the distance from the eye to the box (under orthographic projection,
  // along the view axis), so that what is drawn first hides the most.
  const Aabb& box = node(index).box;
  const dvec3& eye = camera_.camera().eye;
  double distance;
  if (camera_.perspective()) {
    const dvec3 outside = glm::max(glm::max(box.lo - eye, eye - box.hi), dvec3(0));
    distance = glm::dot(outside, outside);
  } else {
    distance = alongView(camera_, box).nearest;
  }
  traversal_.push({distance, index, planes});
}

Queued Traversal::nearest() {
  const Queued entry = traversal_.top();
  traversal_.pop();
  return entry;
}

bool Traversal::inView(Queued& entry) {
  ++visited_;
  const bool mayBeInside = volume_.boxMayBeInside(node(entry.node).box, entry.planes);
  if (!mayBeInside) decide(entry.node, [] { return "its box lies wholly outside the view volume: not queried, nothing below it drawn"; });
  return mayBeInside;
}

std::string Traversal::answered(std::int64_t passed) const {
  return std::to_string(passed) + " of its box's fragments passed the depth test (visible: more than " + std::to_string(knobs_.threshold) + "): " +
         (visible(passed) ? "visible" : "hidden");
}

Aabb Traversal::widened(const Aabb& box) const {
  const double farthest = alongView(camera_, box).farthest;
  const double margin = kMarginPixels * worldPerPixel_ * (camera_.perspective() ? std::max(farthest, camera_.camera().near) : 1.0);
  Aabb grown;
  grown.lo = box.lo - dvec3(margin), grown.hi = box.hi + dvec3(margin);
  return grown;
}

bool Traversal::atEye(const Aabb& node) const {
  // Some corner of the box as queried nearer than the near plane: its nearest point
  // along the view axis.
  const Aabb box = widened(node);
  const double slack = 0x1p-40 * (glm::length(box.center() - camera_.camera().eye) + glm::length((box.hi - box.lo) * 0.5));
  return alongView(camera_, box).nearest <= camera_.camera().near + slack;
}

std::vector<Aabb> Traversal::boundingBoxes(std::uint32_t index) const {
  const HierarchyNode& at = node(index);
  if (knobs_.strategy != QueryStrategy::chcpp || !knobs_.tightBounds) return {at.box};
  // Tight bounds: of the node's box, its children's boxes and its grandchildren's (a
  // leaf: its objects' boxes, cut to its own), the set with the least surface, among
  // sets of at most four boxes. A smaller surface is a smaller outline on screen.
  constexpr std::size_t kMostBoxes = 4;
  std::vector<Aabb> best = {at.box};
  double bestArea = at.box.halfArea();
  const auto consider = [&](std::vector<Aabb> boxes) {
    double area = 0;
    for (const Aabb& box : boxes) area += box.halfArea();
    if (boxes.size() <= kMostBoxes && area < bestArea) best = std::move(boxes), bestArea = area;
  };
  if (at.leaf()) {
    std::vector<Aabb> objects;
    for (std::uint32_t slot = at.firstObject; slot < at.firstObject + at.objectCount; ++slot) {
      const Aabb& box = scene_.instances()[hierarchy_.objects()[slot]].box;
      Aabb cut;
      cut.lo = glm::max(box.lo, at.box.lo), cut.hi = glm::min(box.hi, at.box.hi);
      objects.push_back(cut);
    }
    consider(std::move(objects));
    return best;
  }
  std::vector<Aabb> children, grandchildren;
  for (std::uint32_t c = at.firstChild; c < at.firstChild + at.childCount; ++c) {
    children.push_back(node(c).box);
    if (node(c).leaf()) grandchildren.push_back(node(c).box);
    for (std::uint32_t g = node(c).firstChild; g < node(c).firstChild + node(c).childCount; ++g) grandchildren.push_back(node(g).box);
  }
  consider(std::move(children));
  consider(std::move(grandchildren));
  return best;
}

std::vector<Aabb> Traversal::queryBoxes(std::uint32_t index) const {
  std::vector<Aabb> boxes = boundingBoxes(index);
  for (Aabb& box : boxes) box = widened(box);
  return boxes;
}

void Traversal::drawLeaf(std::uint32_t index) {
  const HierarchyNode& leaf = node(index);
  for (std::uint32_t slot = leaf.firstObject; slot < leaf.firstObject + leaf.objectCount; ++slot) {
    const std::uint32_t object = hierarchy_.objects()[slot];
    const TriangleRun run = runs_[object];
    // An object listed by two k-d leaves is drawn once; one the earlier stages culled, never.
    if (drawn_[object] || run.first == run.end) continue;
    drawn_[object] = 1;
    ++objectsDrawn_;
    gpu_.draw(scene_, object, {in_.triangles.data() + run.first, run.end - run.first});
  }
}

void Traversal::open(const Queued& entry) {
  const HierarchyNode& at = node(entry.node);
  if (at.leaf()) {
    drawLeaf(entry.node);
    return;
  }
  for (std::uint32_t c = at.firstChild; c < at.firstChild + at.childCount; ++c) enqueue(c, entry.planes);
}

void Traversal::pullUpVisibility(std::uint32_t index) {
  for (std::int32_t at = std::int32_t(index); at >= 0 && !state(std::uint32_t(at)).visible; at = node(std::uint32_t(at)).parent)
    state(std::uint32_t(at)).visible = true;
}

VisibleSet Traversal::drawnSet() const {
  VisibleSet out;
  for (std::size_t instance = 0; instance < drawn_.size(); ++instance)
    if (drawn_[instance]) out.triangles.insert(out.triangles.end(), in_.triangles.begin() + runs_[instance].first, in_.triangles.begin() + runs_[instance].end);
  return out;
}

void Traversal::count(Stats& stats) const {
  stats.add("queries: nodes visited", visited_);
  stats.add("queries: issued", issued_);
  stats.add("queries: nodes queried", nodesQueried_);
  stats.add("queries: answered visible", answeredVisible_);
  stats.add("queries: multiqueries", multiqueries_);
  stats.add("queries: multiqueries re-asked", multiqueriesReasked_);
  stats.add("queries: boxes at the eye", atEye_);
  stats.add("queries: objects drawn", objectsDrawn_);
}

void Traversal::explain(StageWitness& why) const {
  for (std::uint32_t leaf = 0; leaf < hierarchy_.nodes().size(); ++leaf) {
    const HierarchyNode& at = node(leaf);
    if (!at.leaf()) continue;
    for (std::uint32_t slot = at.firstObject; slot < at.firstObject + at.objectCount; ++slot) {
      std::string* const found = why.about(hierarchy_.objects()[slot]);
      if (!found || !found->empty()) continue;  // not asked about, or said at another leaf that lists it
      // Up from the leaf to the deepest node the walk decided something at.
      std::uint32_t depth = 0;
      for (std::int32_t up = at.parent; up >= 0; up = node(std::uint32_t(up)).parent) ++depth;
      for (std::int32_t up = std::int32_t(leaf), above = 0; up >= 0; up = node(std::uint32_t(up)).parent, ++above) {
        const std::string& decided = decided_[std::size_t(up)];
        if (decided.empty()) continue;
        *found = (above == 0 ? std::string("for its leaf of the hierarchy") : "for a node " + std::to_string(above) + " above its leaf in the hierarchy") +
                 " (depth " + std::to_string(depth - std::uint32_t(above)) + "): " + decided;
        break;
      }
    }
  }
}

// ---------------------------------------------------------------------------------
// stop-and-wait: down the hierarchy, each answer waited for.

void Traversal::stopAndWait() {
  enqueue(0, frustum::ViewVolume::kAllPlanes);
  while (!traversal_.empty()) {
    Queued entry = nearest();
    if (!inView(entry)) continue;
    bool isVisible = true;
    if (atEye(node(entry.node).box)) {
      ++atEye_;
      decide(entry.node, [] { return kVisibleAtEye; });
    } else {
      const PendingQuery query = gpu_.query(queryBoxes(entry.node));
      ++issued_, ++nodesQueried_;
      const std::int64_t passed = gpu_.answer(query);  // the CPU waits here, every time
      isVisible = visible(passed);
      answeredVisible_ += isVisible;
      decide(entry.node, [&] { return "its query, waited for: " + answered(passed) + (isVisible ? "" : ", nothing below it drawn"); });
    }
    if (isVisible) open(entry);
  }
}

// ---------------------------------------------------------------------------------
// delayed: each leaf by its newest answer, never waiting.

void Traversal::delayed() {
  // Step 1: the leaves in the view volume, nearest first (the view volume is the only
  // test on the way down: inner nodes are not queried).
  std::vector<std::uint32_t> leaves;
  enqueue(0, frustum::ViewVolume::kAllPlanes);
  while (!traversal_.empty()) {
    Queued entry = nearest();
    if (!inView(entry)) continue;
    if (node(entry.node).leaf())
      leaves.push_back(entry.node);
    else
      open(entry);
  }
  // Step 2, for each leaf nearest first: take in its answers (a leaf that was out of
  // view last frame forgets them: they were about another view), ask about it again for
  // a later frame, then draw it unless its newest answer in says hidden. The query goes
  // out before the leaf is drawn: after, it would find the leaf's own depth and pass.
  for (const std::uint32_t leaf : leaves) {
    QueryMemory::Node& at = state(leaf);
    if (at.lastVisited != frame_ - 1) at.inFlight.clear(), at.answered = false;
    at.lastVisited = frame_;
    std::int64_t newest = 0;
    while (!at.inFlight.empty() && gpu_.answered(at.inFlight.front())) {
      newest = gpu_.answer(at.inFlight.front());
      at.visible = visible(newest);
      answeredVisible_ += at.visible;
      at.answered = true;
      at.inFlight.pop_front();
    }
    decide(leaf, [&] {
      return !at.answered ? std::string("no answer about it in yet: drawn")
                          : "its newest answer in, from an earlier frame's query: " + answered(newest) + (at.visible ? ", drawn" : ", not drawn");
    });
    if (atEye(node(leaf).box)) {
      ++atEye_;
      at.inFlight.clear(), at.answered = false;  // drawn until the eye leaves its box
      decide(leaf, [] { return "its box reaches the near plane: drawn without a query"; });
    } else {
      at.inFlight.push_back(gpu_.query(queryBoxes(leaf)));
      ++issued_, ++nodesQueried_;
    }
    if (!at.answered || at.visible) drawLeaf(leaf);
  }
}

// ---------------------------------------------------------------------------------
// chc and chcpp: temporal coherence, answers taken as they come in.

void Traversal::issue(std::vector<Queued> nodes, bool wasVisible) {
  // A box at the eye needs no query: visible, answered at once.
  if (nodes.size() == 1 && atEye(node(nodes.front().node).box)) {
    ++atEye_;
    handleAnswer({PendingQuery(), std::move(nodes), wasVisible, true});
    return;
  }
  std::vector<Aabb> boxes;
  for (const Queued& entry : nodes) {
    const std::vector<Aabb> own = queryBoxes(entry.node);
    boxes.insert(boxes.end(), own.begin(), own.end());
  }
  ++issued_;
  nodesQueried_ += std::int64_t(nodes.size());
  multiqueries_ += nodes.size() > 1;
  inFlight_.push_back({gpu_.query(boxes), std::move(nodes), wasVisible});
}

void Traversal::handleAnswer(const InFlight& answer) {
  const std::int64_t passed = answer.atEye ? 0 : gpu_.answer(answer.query);
  const bool isVisible = answer.atEye || visible(passed);
  if (answer.nodes.size() > 1) {
    // A multiquery: hidden means all of its nodes are; visible says only that one of
    // them is, so each is asked again on its own.
    if (isVisible) {
      ++multiqueriesReasked_;
      for (const Queued& entry : answer.nodes) issue({entry}, false);
    } else {
      for (const Queued& entry : answer.nodes) {
        ++state(entry.node).framesHidden;
        decide(entry.node, [&] {
          return "a multiquery of " + std::to_string(answer.nodes.size()) + " nodes hidden last frame, with it: " + answered(passed) +
                 ", all of them: nothing below it drawn";
        });
      }
    }
    return;
  }
  const Queued& entry = answer.nodes.front();
  QueryMemory::Node& at = state(entry.node);
  decide(entry.node, [&] {
    return answer.atEye        ? std::string(kVisibleAtEye)
           : answer.wasVisible ? "visible last frame, so drawn without waiting; its query, for the next frame: " + answered(passed)
                               : "its query: " + answered(passed) + (isVisible ? "" : ", nothing below it drawn");
  });
  if (!isVisible) {
    ++at.framesHidden;
    return;
  }
  answeredVisible_ += !answer.atEye;
  at.framesHidden = 0;
  // chcpp: a leaf confirmed visible is next asked after assume-visible frames; one that
  // just turned visible after a random part of that, so that the leaves that came into
  // view together spread their queries over the frames that follow.
  const auto wait = std::int64_t(knobs_.assumeVisible);
  at.nextQuery = frame_ + (answer.wasVisible ? wait : 1 + std::int64_t(mixed(std::uint64_t(entry.node) * 0x9E3779B97F4A7C15ull ^ std::uint64_t(frame_)) % std::uint64_t(wait)));
  pullUpVisibility(entry.node);
  // A node visible last frame was opened already; one hidden last frame is opened now.
  if (!answer.wasVisible) open(entry);
}

void Traversal::askAndDrawVisibleLeaf() {
  const Queued entry = visibleBatch_.front();
  visibleBatch_.pop_front();
  issue({entry}, true);
  open(entry);
}

void Traversal::issueHiddenBatch() {
  if (!knobs_.multiqueries) {
    for (const Queued& entry : hiddenBatch_) issue({entry}, false);
    hiddenBatch_.clear();
    return;
  }
  // Multiqueries: the nodes most likely to stay hidden first; each query takes nodes
  // while that lowers the expected queries per node. A node asked alone costs one query;
  // a multiquery of n nodes costs itself, plus n more when it comes back visible:
  // 1 + (1 - P) n, P the chance that all n stay hidden.
  std::stable_sort(hiddenBatch_.begin(), hiddenBatch_.end(), [&](const Queued& a, const Queued& b) {
    return state(a.node).framesHidden > state(b.node).framesHidden;
  });
  const auto costPerNode = [](double allStayHidden, std::size_t n) {
    return n == 1 ? 1.0 : (1 + (1 - allStayHidden) * double(n)) / double(n);
  };
  std::size_t next = 0;
  while (next < hiddenBatch_.size()) {
    std::vector<Queued> group = {hiddenBatch_[next++]};
    double allStayHidden = chanceStaysHidden(state(group.front().node).framesHidden);
    while (next < hiddenBatch_.size()) {
      const double withNext = allStayHidden * chanceStaysHidden(state(hiddenBatch_[next].node).framesHidden);
      if (costPerNode(withNext, group.size() + 1) >= costPerNode(allStayHidden, group.size())) break;
      allStayHidden = withNext;
      group.push_back(hiddenBatch_[next++]);
    }
    issue(std::move(group), false);
  }
  hiddenBatch_.clear();
}

void Traversal::coherent(bool plusPlus) {
  enqueue(0, frustum::ViewVolume::kAllPlanes);
  const auto nothingElseToDo = [&] { return traversal_.empty() && hiddenBatch_.empty(); };
  while (!traversal_.empty() || !inFlight_.empty() || !hiddenBatch_.empty() || !visibleBatch_.empty()) {
    // Step 1: the answers that are in, oldest first. When the oldest is not in, chcpp
    // spends the wait issuing a visible leaf's query; with nothing else left, wait for it.
    while (!inFlight_.empty()) {
      if (gpu_.answered(inFlight_.front().query) || (nothingElseToDo() && (!plusPlus || visibleBatch_.empty()))) {
        const InFlight answer = std::move(inFlight_.front());
        inFlight_.pop_front();
        handleAnswer(answer);
      } else if (plusPlus && !visibleBatch_.empty()) {
        askAndDrawVisibleLeaf();
      } else {
        break;
      }
    }
    // Step 2: one node of the traversal, nearest first.
    if (!traversal_.empty()) {
      Queued entry = nearest();
      if (inView(entry)) {
        QueryMemory::Node& at = state(entry.node);
        const bool wasVisible = at.visible && at.lastVisited == frame_ - 1;
        at.visible = false;  // until an answer, or a visible descendant, says otherwise
        at.lastVisited = frame_;
        const bool leaf = node(entry.node).leaf();
        if (!wasVisible) {
          // Hidden last frame (or never seen): nothing below it is drawn before its
          // answer. chcpp gathers these queries into batches (a box at the eye needs none).
          if (!plusPlus || atEye(node(entry.node).box)) {
            issue({entry}, false);
          } else {
            hiddenBatch_.push_back(entry);
            if (hiddenBatch_.size() >= std::size_t(knobs_.batch)) issueHiddenBatch();
          }
        } else if (!leaf) {
          open(entry);  // visible last frame: opened without a query
          decide(entry.node, [] { return "visible last frame: opened without a query"; });
        } else if (!plusPlus) {
          // A leaf visible last frame: asked again, for the next frame, and drawn at once
          // without waiting for the answer. The query goes first: after the leaf is drawn
          // it would find the leaf's own depth and pass.
          issue({entry}, true);
          open(entry);
        } else if (frame_ >= at.nextQuery) {
          visibleBatch_.push_back(entry);  // chcpp: asked, then drawn, when the CPU would wait
        } else {
          pullUpVisibility(entry.node);  // chcpp: assumed visible this frame, drawn unasked
          open(entry);
          decide(entry.node, [&] { return "visible when last asked: assumed visible this frame and drawn, next asked in frame " + std::to_string(at.nextQuery); });
        }
      }
    }
    // Step 3 (chcpp): the traversal done, the gathered queries go out; the visible
    // leaves' (and their drawing) only once no answer is awaited that they could fill
    // the wait for.
    if (plusPlus && traversal_.empty()) {
      issueHiddenBatch();
      if (inFlight_.empty())
        while (!visibleBatch_.empty()) askAndDrawVisibleLeaf();
    }
  }
}

}  // namespace

VisibleSet cullWithQueries(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs, const VisibleSet& in,
                           std::unique_ptr<StageMemory>* memory, SimulatedGpu* gpu, Stats& stats, StageWitness* why) {
  PhaseTimer timer(stats, "culling: occlusion queries");
  // The memory of the walk, or of this frame alone; rebuilt for another scene or hierarchy.
  std::unique_ptr<StageMemory> ownMemory;
  std::unique_ptr<StageMemory>& slot = memory ? *memory : ownMemory;
  auto* remembered = dynamic_cast<QueryMemory*>(slot.get());
  if (!remembered || remembered->scene != &scene || remembered->hierarchy->kind() != knobs.hierarchy) {
    slot = std::make_unique<QueryMemory>();
    remembered = static_cast<QueryMemory*>(slot.get());
    remembered->scene = &scene;
    remembered->hierarchy.emplace(scene, knobs.hierarchy, stats);
    remembered->nodes.resize(remembered->hierarchy->nodes().size());
  }
  ++remembered->frame;
  // The walk's GPU, or one for this frame alone.
  std::optional<SimulatedGpu> ownGpu;
  if (!gpu) {
    ownGpu.emplace();
    ownGpu->beginFrame(camera);
  }
  SimulatedGpu& device = gpu ? *gpu : *ownGpu;
  device.setLatency({knobs.latency, knobs.latencyIn});

  const GpuCounts before = device.counts();
  Traversal traversal(scene, camera, knobs, in, *remembered, device, why != nullptr);
  if (!remembered->hierarchy->nodes().empty()) {
    switch (knobs.strategy) {
      case QueryStrategy::stopAndWait: traversal.stopAndWait(); break;
      case QueryStrategy::delayed: traversal.delayed(); break;
      case QueryStrategy::chc: traversal.coherent(false); break;
      case QueryStrategy::chcpp: traversal.coherent(true); break;
    }
  }
  traversal.count(stats);
  if (why) traversal.explain(*why);
  // What this stage asked of the GPU (a walk's GPU counts the whole frame).
  const GpuCounts& after = device.counts();
  stats.add("queries: stalls", after.stalls - before.stalls);
  stats.add("queries: boxes queried", after.boxesQueried - before.boxesQueried);
  stats.add("queries: box fragments tested", after.queryFragments - before.queryFragments);
  stats.add("queries: box fragments passed", after.fragmentsPassed - before.fragmentsPassed);
  stats.add("queries: triangles drawn", after.trianglesDrawn - before.trianglesDrawn);
  stats.add("queries: fragments written", after.fragmentsWritten - before.fragmentsWritten);
  if (ownGpu) {
    const GpuFrameTimes times = ownGpu->endFrame();
    stats.addSeconds("queries: frame", times.frame);
    stats.addSeconds("queries: waiting", times.waiting);
    stats.addSeconds("queries: cpu busy", times.cpuBusy);
    stats.addSeconds("queries: gpu busy", times.gpuBusy);
  }
  return traversal.drawnSet();
}

}  // namespace hsr::culling::occlusion
