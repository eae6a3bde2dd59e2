// shadecore CLI — PNG output (libpng, 8-bit RGB, written to memory so the file goes out atomically) and a
// small RGB canvas with a 5×7 bitmap font for the contact sheet's labels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace shadecore::cli {

// 8-bit RGB, row-major from the top. Deterministic: no time or text chunks.
std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb);

struct Canvas {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  Canvas(int w, int h, uint8_t grey);
  void blit(int x, int y, int w, int h, const std::vector<uint8_t>& src);
  // Text in a 5×7 font (upper case, digits and a few symbols), `scale` pixels per font pixel.
  void text(int x, int y, const std::string& s, uint8_t r, uint8_t g, uint8_t b, int scale = 1);
  static int text_width(const std::string& s, int scale = 1) { return static_cast<int>(s.size()) * 6 * scale; }
};

}  // namespace shadecore::cli
