// SPDX-License-Identifier: Apache-2.0
// shadecore — PNG output (libpng, 8-bit RGB, written to memory so the file goes out atomically) and a
// small RGB canvas with a 5×7 bitmap font for the contact sheet's labels and the legends (shadecore/common/legend.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace shadecore::canvas {

// 8-bit RGB, row-major from the top. Deterministic: no time or text chunks.
std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb);

struct Canvas {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  Canvas(int w, int h, uint8_t grey);
  void blit(int x, int y, int w, int h, const std::vector<uint8_t>& src);
  // UTF-8 text in a 5×7 font (upper and lower case, digits, ASCII punctuation and − ≈ ± × · Δ θ …), `scale`
  // pixels per font pixel; a character advances 6·scale pixels; the ink lies in the kTextRows·scale pixels from
  // y (capitals and digits in the first 7, the descenders of g j p q y below them). A character without a
  // glyph leaves a blank.
  static constexpr int kTextRows = 9;
  void text(int x, int y, const std::string& s, uint8_t r, uint8_t g, uint8_t b, int scale = 1);
  // Width of `s` in pixels: 6·scale per character (code point), the last column of the last one blank.
  static int text_width(const std::string& s, int scale = 1);
  static bool has_glyph(char32_t cp);
  // A solid rectangle (clipped to the canvas).
  void fill(int x, int y, int w, int h, uint8_t r, uint8_t g, uint8_t b);
};

}  // namespace shadecore::canvas
