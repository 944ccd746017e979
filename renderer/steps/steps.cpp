#include "renderer/steps/steps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <unistd.h>

#include "renderer/image/image_library.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/steps/label_font.hpp"
#include "renderer/steps/steps_page.hpp"
#include "renderer/util/error.hpp"

namespace hsr {

bool StepRecorder::due(std::size_t index, std::size_t count) const {
  const std::size_t stride = every_ > 0 ? every_ : std::max<std::size_t>(1, (count + kFramesPerRun - 1) / kFramesPerRun);
  return index + 1 == count || (index + 1) % stride == 0;
}

bool StepRecorder::due(std::size_t index) const { return every_ > 0 ? (index + 1) % every_ == 0 : index < kFramesPerRun; }

void StepRecorder::record(std::string caption, Image picture, SourceLocation where) {
  const std::lock_guard lock(mutex_);
  if (sink_)
    sink_(Step{std::move(caption), std::move(picture), where});
  else
    steps_.push_back({std::move(caption), std::move(picture), where});
}

std::string stepCountError(const std::string& text) {
  const bool whole = !text.empty() && text.size() <= 9 && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  return whole ? "" : text + ": expected a whole number from 0 to " + std::to_string(kMostSteps);
}

namespace {

std::uint8_t* pixelAt(Image& picture, int x, int y) {
  return &picture.pixels[(std::size_t(y) * std::size_t(picture.width) + std::size_t(x)) * 4];
}

void put(Image& picture, int x, int y, Rgb color) {
  std::uint8_t* pixel = pixelAt(picture, x, y);
  pixel[0] = color[0], pixel[1] = color[1], pixel[2] = color[2], pixel[3] = 255;
}

// The heat ramp: black -> red -> yellow -> white as t goes from 0 to 1.
Rgb heat(double t) {
  const auto channel = [&](double from) { return std::uint8_t(std::lround(255 * std::clamp(3 * t - from, 0.0, 1.0))); };
  return {channel(0), channel(1), channel(2)};
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// Copies `picture` into `into` with its top left corner at (left, top); it must fit.
void paste(Image& into, const Image& picture, int left, int top) {
  for (int y = 0; y < picture.height; ++y)
    std::copy_n(&picture.pixels[std::size_t(y) * std::size_t(picture.width) * 4], std::size_t(picture.width) * 4,
                pixelAt(into, left, top + y));
}

// The animation's frames are at most this wide: GIF encoding costs about 0.1 s per
// 200,000 pixels, and a frame of a 1280 x 720 z-buffer (colour beside depth) has 1.8 M.
constexpr int kAnimationWidth = 720;

// Shrunk to `width` by averaging the pixels under each new one (a box filter: a frame
// has flat areas and thin lines, which it keeps as lighter lines; a windowed sinc, as
// OpenImageIO's resize uses, costs some forty times more here for no visible gain).
Image atMostWide(const Image& picture, int width) {
  if (picture.width <= width) return picture;
  const int height = std::max(1, int(std::lround(double(picture.height) * width / picture.width)));
  Image smaller = blankPicture(width, height);
  for (int y = 0; y < height; ++y) {
    const int y0 = y * picture.height / height, y1 = std::max(y0 + 1, (y + 1) * picture.height / height);
    for (int x = 0; x < width; ++x) {
      const int x0 = x * picture.width / width, x1 = std::max(x0 + 1, (x + 1) * picture.width / width);
      std::array<int, 4> sum{};
      for (int sy = y0; sy < y1; ++sy)
        for (int sx = x0; sx < x1; ++sx)
          for (int c = 0; c < 4; ++c) sum[std::size_t(c)] += picture.pixels[(std::size_t(sy) * std::size_t(picture.width) + std::size_t(sx)) * 4 + std::size_t(c)];
      const int count = (y1 - y0) * (x1 - x0);
      for (int c = 0; c < 4; ++c) pixelAt(smaller, x, y)[c] = std::uint8_t((sum[std::size_t(c)] + count / 2) / count);
    }
  }
  return smaller;
}

}  // namespace

Image blankPicture(int width, int height, Rgb color) {
  Image picture{width, height, 4, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4, 255)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) put(picture, x, y, color);
  return picture;
}

Image surfacePicture(const PreparedScene& scene, const CameraTransform& view, std::span<const std::uint32_t> ids, int width,
                     int height) {
  Image picture = blankPicture(width, height, {235, 235, 235});
  // A light above, to the right of and behind the eye: floors, fronts and sides of a box
  // come out in three different shades.
  const dvec3 light = glm::normalize(0.8 * view.up() - view.forward() + 0.4 * view.right());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::uint32_t id = ids[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      if (id == 0) continue;
      const std::uint32_t triangle = id - 1;
      // Facing the light (either side): full colour; edge-on: 35% of it.
      const double facing = std::abs(glm::dot(scene.faceNormal(triangle), light));
      const vec3 color = scene.instanceOf(triangle).color * float(0.35 + 0.65 * facing);
      const auto channel = [](float c) { return std::uint8_t(std::lround(255 * std::clamp(c, 0.0f, 1.0f))); };
      put(picture, x, y, {channel(color.x), channel(color.y), channel(color.z)});
    }
  return picture;
}

Image depthPicture(std::span<const float> depth, int width, int height) {
  float nearest = INFINITY, farthest = 0;
  for (const float d : depth)
    if (std::isfinite(d)) nearest = std::min(nearest, d), farthest = std::max(farthest, d);
  Image picture = blankPicture(width, height, {0, 0, 0});
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float d = depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      if (!std::isfinite(d)) continue;
      const double t = farthest > nearest ? (d - nearest) / (farthest - nearest) : 0;
      const auto grey = std::uint8_t(std::lround(255 - 195 * t));
      put(picture, x, y, {grey, grey, grey});
    }
  return picture;
}

Image heatMapPicture(std::span<const double> values, int width, int height, const std::string& unit) {
  constexpr int kLegendHeight = 36, kRampHeight = 10, kMargin = 6;
  const double largest = std::max(1e-300, *std::max_element(values.begin(), values.end()));
  Image picture = blankPicture(width, height + kLegendHeight);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) put(picture, x, y, heat(values[std::size_t(y) * std::size_t(width) + std::size_t(x)] / largest));
  // The legend: the ramp across the width, 0 under its left end, the largest under its right.
  for (int y = height + kMargin; y < height + kMargin + kRampHeight; ++y)
    for (int x = kMargin; x < width - kMargin; ++x) put(picture, x, y, heat(double(x - kMargin) / std::max(1, width - 2 * kMargin - 1)));
  const int baseline = height + kLegendHeight - 5;
  drawLabel(picture, kMargin, baseline, "0", {0, 0, 0}, kSmallLabelSize);
  const std::string top = number(largest) + " " + unit;
  const int topWidth = labelWidth(top, kSmallLabelSize);
  drawLabel(picture, std::max(kMargin + 20, width - kMargin - topWidth), baseline, top, {0, 0, 0}, kSmallLabelSize);
  return picture;
}

Image besideEachOther(const std::vector<Image>& pictures) {
  int width = 0, height = 0;
  for (const Image& picture : pictures) width += picture.width + (width ? kPanelGap : 0), height = std::max(height, picture.height);
  Image combined = blankPicture(width, height);
  int left = 0;
  for (const Image& picture : pictures) {
    paste(combined, picture, left, 0);
    left += picture.width + kPanelGap;
  }
  return combined;
}

void tint(Image& picture, std::span<const std::size_t> pixels, Rgb color) {
  for (const std::size_t p : pixels)
    for (std::size_t c = 0; c < 3; ++c) picture.pixels[4 * p + c] = std::uint8_t((picture.pixels[4 * p + c] + color[c] + 1) / 2);
}

void drawSegment(Image& picture, const dvec2& a, const dvec2& b, Rgb color, double width) {
  rasterizeLine(a, b, width, picture.width, picture.height, [&](int x, int y) { put(picture, x, y, color); });
}

void drawWireframe(Image& picture, const PreparedScene& scene, const CameraTransform& view, std::span<const std::uint32_t> triangles,
                   Rgb color) {
  const double near = view.camera().near;
  const auto along = [](const ClipVertex& a, const ClipVertex& b, double t) {
    return ClipVertex{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.d + t * (b.d - a.d), a.w + t * (b.w - a.w)};
  };
  for (const std::uint32_t triangle : triangles) {
    const Triangle& corners = scene.triangles()[triangle];
    for (int e = 0; e < 3; ++e) {
      ClipVertex a = view.clipFromWorld(scene.positions()[corners[e]]), b = view.clipFromWorld(scene.positions()[corners[(e + 1) % 3]]);
      if (a.d < near && b.d < near) continue;
      if (a.d < near) a = along(a, b, (near - a.d) / (b.d - a.d));
      if (b.d < near) b = along(b, a, (near - b.d) / (a.d - b.d));
      drawSegment(picture, view.pixelFromClip(a), view.pixelFromClip(b), color, 1.0);
    }
  }
}

void drawLegend(Image& picture, const std::vector<std::pair<Rgb, std::string>>& entries) {
  constexpr int kLine = 17, kSample = 22, kPad = 5;
  int widest = 0;
  for (const auto& [color, text] : entries) widest = std::max(widest, labelWidth(text, kSmallLabelSize));
  const int boxWidth = std::min(picture.width, kPad * 3 + kSample + widest), boxHeight = std::min(picture.height, kPad * 2 + kLine * int(entries.size()));
  for (int y = 0; y < boxHeight; ++y)
    for (int x = 0; x < boxWidth; ++x) {
      std::uint8_t* pixel = pixelAt(picture, x, y);
      // A translucent white box, so the legend reads over any drawing.
      for (int c = 0; c < 3; ++c) pixel[c] = std::uint8_t(255 - (255 - pixel[c]) / 5);
    }
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const double y = kPad + kLine * (double(e) + 0.5);
    drawSegment(picture, {kPad, y}, {kPad + kSample, y}, entries[e].first, 2.5);
    drawLabel(picture, kPad * 2 + kSample, int(y) + 5, entries[e].second, {0, 0, 0}, kSmallLabelSize);
  }
}

Image graphvizPicture(const std::string& graph) {
  const std::filesystem::path drawn = std::filesystem::temp_directory_path() / ("hsr-diagram-" + std::to_string(::getpid()) + ".png");
  const std::string command = "dot -Tpng -Gdpi=72 -o '" + drawn.string() + "' 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "w");
  // Where no program can be started at all (the browser edition), the step is recorded
  // with a picture that says where the diagram is drawn; the other steps are as anywhere.
  if (!pipe) {
    Image notice = blankPicture(520, 64, {250, 246, 225});
    drawLabel(notice, 12, 26, "This diagram is drawn by Graphviz's dot, which this build cannot start", {0, 0, 0});
    drawLabel(notice, 12, 48, "(" + std::string(std::strerror(errno)) + "): hsr render --steps draws it.", {0, 0, 0});
    return notice;
  }
  std::fwrite(graph.data(), 1, graph.size(), pipe);
  const int status = pclose(pipe);
  Image picture;
  const std::string error = status == 0 ? imageLibrary().readImage(drawn.string(), picture) : "dot failed";
  std::error_code ignored;
  std::filesystem::remove(drawn, ignored);
  if (!error.empty())
    throw InputError("steps: cannot draw a diagram with Graphviz's dot (is it installed? scripts/setup.sh installs graphviz): " + error);
  if (picture.channels == 4) return picture;
  // dot's PNG may come without alpha: made RGBA.
  Image rgba = blankPicture(picture.width, picture.height);
  for (std::size_t p = 0; p < std::size_t(picture.width) * std::size_t(picture.height); ++p)
    for (int c = 0; c < 3; ++c) rgba.pixels[4 * p + std::size_t(c)] = picture.pixels[std::size_t(picture.channels) * p + std::size_t(std::min(c, picture.channels - 1))];
  return rgba;
}

Image withCaption(const Image& picture, const std::string& caption) {
  constexpr int kBand = 22;
  Image framed = blankPicture(picture.width, picture.height + kBand);
  paste(framed, picture, 0, kBand);
  drawLabel(framed, 4, kBand - 6, caption, {0, 0, 0});
  return framed;
}

std::string stepNumber(std::size_t index) {
  char number[32];
  std::snprintf(number, sizeof number, "%04zu", index + 1);
  return number;
}

void StepsWriter::add(const Step& step) {
  files_.addRgbaPng(folder_ / stepPictureName(frames_.size()), step.picture.width, step.picture.height, step.picture.pixels);
  recorded_.emplace_back(step.caption, step.where);
  frames_.push_back(withCaption(atMostWide(step.picture, kAnimationWidth), step.caption));
}

void StepsWriter::finish(const std::string& title, const PixelQuestion& question) {
  std::string captions;
  std::vector<std::string> pictures;
  for (std::size_t s = 0; s < recorded_.size(); ++s) {
    captions += stepNumber(s) + " " + recorded_[s].first + "\n";
    pictures.push_back(stepPictureName(s));
  }
  files_.addText(folder_ / "captions.txt", captions);
  files_.addText(folder_ / "steps.html", stepsPage(title, pageSteps(recorded_, pictures), question));
  // An animation's frames share one size: each is padded with white to the largest.
  int width = 0, height = 0;
  for (const Image& frame : frames_) width = std::max(width, frame.width), height = std::max(height, frame.height);
  for (Image& frame : frames_) {
    if (frame.width == width && frame.height == height) continue;
    Image padded = blankPicture(width, height);
    paste(padded, frame, 0, 0);
    frame = std::move(padded);
  }
  const std::filesystem::path animation = files_.addWrittenElsewhere(folder_ / "steps.gif");
  if (const std::string error = imageLibrary().writeAnimation(animation.string(), frames_, framesPerSecond_); !error.empty())
    throw InputError((folder_ / "steps.gif").string() + ": cannot write the animation: " + error);
  files_.commit();
}

}  // namespace hsr
