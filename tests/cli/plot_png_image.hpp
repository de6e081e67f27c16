#pragma once
// A decoded PNG (libpng's simplified API, RGB) and the plot frames found in it: the four panels
// `vdrive plot` draws are found by their black frame lines, not by fixed coordinates.
#include <png.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace vdrive::test {

struct Rgb {
  int r = 0, g = 0, b = 0;
};

struct PngImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGB, row by row
  std::string error;                 // non-empty: not decoded

  Rgb at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
    return {pixels[i], pixels[i + 1], pixels[i + 2]};
  }
};

inline PngImage read_png(const std::string& path) {
  PngImage out;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&image, path.c_str()) == 0) {
    out.error = image.message;
    return out;
  }
  image.format = PNG_FORMAT_RGB;
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr) == 0) {
    out.error = image.message;
    return out;
  }
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  return out;
}

inline bool dark(Rgb c) { return c.r < 90 && c.g < 90 && c.b < 90; }

inline Rgb parse_colour(const std::string& hex) {  // "#RRGGBB"
  const long v = std::strtol(hex.c_str() + 1, nullptr, 16);
  return {static_cast<int>((v >> 16) & 0xFF), static_cast<int>((v >> 8) & 0xFF), static_cast<int>(v & 0xFF)};
}

inline bool near(Rgb a, Rgb b, int tolerance) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance && std::abs(a.b - b.b) <= tolerance;
}

struct Frame {
  int left = 0, right = 0, top = 0, bottom = 0;  // the frame lines themselves
};

// Plot frames: rows holding a run of dark pixels longer than half the image are frame edges
// (tic marks and text are short; grid and data lines are not dark); runs of adjacent rows are one
// edge, and consecutive edges pair up as a frame's top and bottom.
inline std::vector<Frame> find_frames(const PngImage& img) {
  struct Edge {
    int y, left, right;
  };
  std::vector<Edge> edges;
  int previous = -2;
  for (int y = 0; y < img.height; ++y) {
    int best = 0, best_start = 0, run = 0;
    for (int x = 0; x < img.width; ++x) {
      run = dark(img.at(x, y)) ? run + 1 : 0;
      if (run > best) {
        best = run;
        best_start = x - run + 1;
      }
    }
    if (best * 2 <= img.width) continue;
    if (y != previous + 1) edges.push_back({y, best_start, best_start + best - 1});
    previous = y;
  }
  std::vector<Frame> frames;
  for (std::size_t i = 0; i + 1 < edges.size(); i += 2)
    frames.push_back({edges[i].left, edges[i].right, edges[i].y, edges[i + 1].y});
  return frames;
}

// Pixels of `colour` strictly inside the frame (its lines and the tic marks next to them excluded).
inline int count_inside(const PngImage& img, const Frame& f, Rgb colour, int tolerance) {
  int n = 0;
  for (int y = f.top + 3; y < f.bottom - 2; ++y)
    for (int x = f.left + 8; x < f.right - 7; ++x)
      if (near(img.at(x, y), colour, tolerance)) ++n;
  return n;
}

}  // namespace vdrive::test
