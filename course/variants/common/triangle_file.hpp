// What the C++ variants share, written apart from hsr: reading a triangle file (its
// format: renderer/scene/triangle_file.hpp), writing an id image as a PNG, with no
// library (the PNG's pixels in stored, uncompressed deflate blocks), and a depth image
// as a portable float map.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace variant {

using Vec3 = std::array<double, 3>;

struct TriangleFile {
  int width = 0, height = 0;
  bool perspective = true;
  Vec3 eye{}, target{}, up{};
  double fovY = 45, orthoHeight = 2, near = 0.1, far = 1000;
  double clipFromWorld[4][4] = {};  // rows: (x, y, d, w) = M (p, 1)
  std::vector<std::array<Vec3, 3>> triangles;
};

inline TriangleFile readTriangleFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error(path + ": cannot open");
  TriangleFile scene;
  std::string line;
  const auto next = [&](std::istringstream& words) {
    while (std::getline(file, line)) {
      line = line.substr(0, line.find('#'));
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      words = std::istringstream(line);
      return true;
    }
    return false;
  };
  std::istringstream words;
  while (next(words)) {
    std::string key;
    words >> key;
    if (key == "size") words >> scene.width >> scene.height;
    else if (key == "projection") { std::string kind; words >> kind; scene.perspective = kind == "perspective"; }
    else if (key == "eye") words >> scene.eye[0] >> scene.eye[1] >> scene.eye[2];
    else if (key == "target") words >> scene.target[0] >> scene.target[1] >> scene.target[2];
    else if (key == "up") words >> scene.up[0] >> scene.up[1] >> scene.up[2];
    else if (key == "fov_y") words >> scene.fovY;
    else if (key == "height") words >> scene.orthoHeight;
    else if (key == "near") words >> scene.near;
    else if (key == "far") words >> scene.far;
    else if (key == "clip_from_world") {
      for (auto& row : scene.clipFromWorld) {
        next(words);
        for (double& value : row) words >> value;
      }
    } else if (key == "triangles") {
      std::size_t count = 0;
      words >> count;
      scene.triangles.resize(count);
      for (auto& triangle : scene.triangles) {
        next(words);
        for (Vec3& corner : triangle) words >> corner[0] >> corner[1] >> corner[2];
      }
    }
  }
  return scene;
}

inline std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// 24-bit RGB, the id big-endian (R the high byte), rows from the top.
inline void writeIdPng(const std::string& path, int width, int height, const std::vector<std::uint32_t>& ids) {
  std::vector<std::uint8_t> raw;  // each row: filter 0, then RGB
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    for (int x = 0; x < width; ++x) {
      const std::uint32_t id = ids[std::size_t(y) * std::size_t(width) + std::size_t(x)];
      raw.insert(raw.end(), {std::uint8_t(id >> 16), std::uint8_t(id >> 8), std::uint8_t(id)});
    }
  }
  std::vector<std::uint8_t> zlib = {0x78, 0x01};  // deflate, stored blocks of at most 65535 bytes
  std::uint32_t a = 1, b = 0;
  for (std::size_t at = 0; at < raw.size(); at += 65535) {
    const std::size_t size = std::min<std::size_t>(65535, raw.size() - at);
    zlib.push_back(at + size == raw.size() ? 1 : 0);  // the last block says so
    zlib.insert(zlib.end(), {std::uint8_t(size), std::uint8_t(size >> 8), std::uint8_t(~size), std::uint8_t(~size >> 8)});
    zlib.insert(zlib.end(), raw.begin() + long(at), raw.begin() + long(at + size));
  }
  for (const std::uint8_t byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  const std::uint32_t adler = b << 16 | a;
  zlib.insert(zlib.end(), {std::uint8_t(adler >> 24), std::uint8_t(adler >> 16), std::uint8_t(adler >> 8), std::uint8_t(adler)});
  std::ofstream out(path, std::ios::binary);
  const auto chunk = [&](const char* kind, const std::vector<std::uint8_t>& data) {
    const std::uint32_t size = std::uint32_t(data.size());
    const std::uint8_t length[4] = {std::uint8_t(size >> 24), std::uint8_t(size >> 16), std::uint8_t(size >> 8), std::uint8_t(size)};
    std::vector<std::uint8_t> typed(kind, kind + 4);
    typed.insert(typed.end(), data.begin(), data.end());
    const std::uint32_t crc = crc32(typed.data(), typed.size());
    const std::uint8_t check[4] = {std::uint8_t(crc >> 24), std::uint8_t(crc >> 16), std::uint8_t(crc >> 8), std::uint8_t(crc)};
    out.write(reinterpret_cast<const char*>(length), 4);
    out.write(reinterpret_cast<const char*>(typed.data()), std::streamsize(typed.size()));
    out.write(reinterpret_cast<const char*>(check), 4);
  };
  out.write("\x89PNG\r\n\x1a\n", 8);
  const std::uint32_t w = std::uint32_t(width), h = std::uint32_t(height);
  chunk("IHDR", {std::uint8_t(w >> 24), std::uint8_t(w >> 16), std::uint8_t(w >> 8), std::uint8_t(w), std::uint8_t(h >> 24),
                 std::uint8_t(h >> 16), std::uint8_t(h >> 8), std::uint8_t(h), 8, 2, 0, 0, 0});
  chunk("IDAT", zlib);
  chunk("IEND", {});
}

// A depth image (rows from the top down) as a greyscale PFM: a header, then float32s,
// little-endian, rows from the bottom up.
inline void writeDepthPfm(const std::string& path, int width, int height, const std::vector<float>& depth) {
  std::ofstream out(path, std::ios::binary);
  out << "Pf\n" << width << " " << height << "\n-1.0\n";
  for (int y = height - 1; y >= 0; --y)
    for (int x = 0; x < width; ++x) {
      std::uint32_t bits;
      std::memcpy(&bits, &depth[std::size_t(y) * std::size_t(width) + std::size_t(x)], 4);
      const char bytes[4] = {char(bits), char(bits >> 8), char(bits >> 16), char(bits >> 24)};
      out.write(bytes, 4);
    }
}

}  // namespace variant
