// SPDX-License-Identifier: Apache-2.0
// shadecore — PNG encoding through libpng and the contact sheet's canvas.
#include "shadecore/common/png.hpp"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <stdexcept>

namespace shadecore::canvas {

namespace {
void on_write(png_structp p, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(p));
  out->append(reinterpret_cast<const char*>(data), n);
}
void on_flush(png_structp) {}
void on_error(png_structp, png_const_charp msg) { throw std::runtime_error(std::string("PNG encoding failed: ") + msg); }
void on_warning(png_structp, png_const_charp) {}
}  // namespace

std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<size_t>(width) * height * 3)
    throw std::invalid_argument("encode_png: bad image size");
  std::string out;
  png_structp p = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  if (!p) throw std::runtime_error("PNG encoding failed: out of memory");
  png_infop info = png_create_info_struct(p);
  if (!info) {
    png_destroy_write_struct(&p, nullptr);
    throw std::runtime_error("PNG encoding failed: out of memory");
  }
  try {
    png_set_write_fn(p, &out, on_write, on_flush);
    png_set_IHDR(p, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(p, info);
    for (int y = 0; y < height; ++y)
      png_write_row(p, const_cast<png_bytep>(rgb.data() + static_cast<size_t>(y) * width * 3));
    png_write_end(p, nullptr);
  } catch (...) {
    png_destroy_write_struct(&p, &info);
    throw;
  }
  png_destroy_write_struct(&p, &info);
  return out;
}

Canvas::Canvas(int w, int h, uint8_t grey) : width(w), height(h), rgb(static_cast<size_t>(w) * h * 3, grey) {}

void Canvas::blit(int x, int y, int w, int h, const std::vector<uint8_t>& src) {
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int X = x + i, Y = y + j;
      if (X < 0 || Y < 0 || X >= width || Y >= height) continue;
      std::memcpy(&rgb[(static_cast<size_t>(Y) * width + X) * 3], &src[(static_cast<size_t>(j) * w + i) * 3], 3);
    }
}

namespace {
// 5×7 glyphs, one string of 7 rows × 5 columns ('#' = ink); descenders have 9 rows (Canvas::kTextRows).
struct Glyph {
  char32_t c;  // Unicode code point
  const char* rows;
};
constexpr Glyph kFont[] = {
    {'A', " ### #   ##   #######   ##   ##   #"},
    {'B', "#### #   ##   ##### #   ##   ##### "},
    {'C', " ### #   ##    #    #    #   # ### "},
    {'D', "#### #   ##   ##   ##   ##   ##### "},
    {'E', "######    #    #### #    #    #####"},
    {'F', "######    #    #### #    #    #    "},
    {'G', " ### #   ##    # ####   ##   # ####"},
    {'H', "#   ##   ##   #######   ##   ##   #"},
    {'I', " ###   #    #    #    #    #   ### "},
    {'J', "  ###   #    #    #    # #  #  ##  "},
    {'K', "#   ##  # # #  ##   # #  #  # #   #"},
    {'L', "#    #    #    #    #    #    #####"},
    {'M', "#   ### ### # ## # ##   ##   ##   #"},
    {'N', "#   ###  ## # ##  ###   ##   ##   #"},
    {'O', " ### #   ##   ##   ##   ##   # ### "},
    {'P', "#### #   ##   ##### #    #    #    "},
    {'Q', " ### #   ##   ##   ## # ##  #  ## #"},
    {'R', "#### #   ##   ##### # #  #  # #   #"},
    {'S', " #####    #     ###     #    ##### "},
    {'T', "#####  #    #    #    #    #    #  "},
    {'U', "#   ##   ##   ##   ##   ##   # ### "},
    {'V', "#   ##   ##   ##   ##   # # #   #  "},
    {'W', "#   ##   ##   ## # ## # ## # # # # "},
    {'X', "#   ##   # # #   #   # # #   ##   #"},
    {'Y', "#   ##   # # #   #    #    #    #  "},
    {'Z', "#####    #   #   #   #   #    #####"},
    {'0', " ### #   ##  ### # ###  ##   # ### "},
    {'1', "  #   ##    #    #    #    #   ### "},
    {'2', " ### #   #    #   #   #   #   #####"},
    {'3', "#####   #   #     #     ##   # ### "},
    {'4', "   #   ##  # # #  # #####   #    # "},
    {'5', "######    ####     #    ##   # ### "},
    {'6', "  ##  #   #    #### #   ##   # ### "},
    {'7', "#####    #   #   #   #    #    #   "},
    {'8', " ### #   ##   # ### #   ##   # ### "},
    {'9', " ### #   ##   # ####    #   #  ##  "},
    {'/', "    #    #   #   #   #   #    #    "},
    {'-', "               #####               "},
    {'.', "                          ##   ##  "},
    {':', "      ##   ##        ##   ##       "},
    {'(', "   #   #   #    #    #     #     # "},
    {')', " #     #     #    #    #   #   #   "},
    {'^', "  #   # # #   #                    "},
    {'=', "          #####     #####          "},
    {',', "                     ##    #   #   "},
    {'+', "       #    #  #####  #    #       "},
    {'|', "  #    #    #    #    #    #    #  "},
    {'_', "                              #####"},
    // Lower case (x-height 5 rows); g, j, p, q, y have 9 rows: their descenders go below the 7-row cell.
    {'a', "     " "     " " ### " "    #" " ####" "#   #" " ####"},
    {'b', "#    " "#    " "# ## " "##  #" "#   #" "#   #" "#### "},
    {'c', "     " "     " " ### " "#    " "#    " "#   #" " ### "},
    {'d', "    #" "    #" " ## #" "#  ##" "#   #" "#   #" " ####"},
    {'e', "     " "     " " ### " "#   #" "#####" "#    " " ### "},
    {'f', "  ## " " #  #" " #   " "###  " " #   " " #   " " #   "},
    {'g', "     " "     " " ####" "#   #" "#   #" "#   #" " ####" "    #" " ### "},
    {'h', "#    " "#    " "# ## " "##  #" "#   #" "#   #" "#   #"},
    {'i', "  #  " "     " " ##  " "  #  " "  #  " "  #  " " ### "},
    {'j', "   # " "     " "  ## " "   # " "   # " "   # " "   # " "#  # " " ##  "},
    {'k', "#    " "#    " "#  # " "# #  " "##   " "# #  " "#  # "},
    {'l', " ##  " "  #  " "  #  " "  #  " "  #  " "  #  " " ### "},
    {'m', "     " "     " "## # " "# # #" "# # #" "#   #" "#   #"},
    {'n', "     " "     " "# ## " "##  #" "#   #" "#   #" "#   #"},
    {'o', "     " "     " " ### " "#   #" "#   #" "#   #" " ### "},
    {'p', "     " "     " "#### " "#   #" "#   #" "#   #" "#### " "#    " "#    "},
    {'q', "     " "     " " ####" "#   #" "#   #" "#   #" " ####" "    #" "    #"},
    {'r', "     " "     " "# ## " "##  #" "#    " "#    " "#    "},
    {'s', "     " "     " " ### " "#    " " ### " "    #" "#### "},
    {'t', " #   " " #   " "###  " " #   " " #   " " #  #" "  ## "},
    {'u', "     " "     " "#   #" "#   #" "#   #" "#  ##" " ## #"},
    {'v', "     " "     " "#   #" "#   #" "#   #" " # # " "  #  "},
    {'w', "     " "     " "#   #" "#   #" "# # #" "# # #" " # # "},
    {'x', "     " "     " "#   #" " # # " "  #  " " # # " "#   #"},
    {'y', "     " "     " "#   #" "#   #" "#   #" "#   #" " ####" "    #" " ### "},
    {'z', "     " "     " "#####" "   # " "  #  " " #   " "#####"},
    // More symbols.
    {'<', "   # " "  #  " " #   " "#    " " #   " "  #  " "   # "},
    {'>', " #   " "  #  " "   # " "    #" "   # " "  #  " " #   "},
    {'%', "##   " "##  #" "   # " "  #  " " #   " "#  ##" "   ##"},
    {'*', "     " "  #  " "# # #" " ### " "# # #" "  #  " "     "},
    {'[', " ### " " #   " " #   " " #   " " #   " " #   " " ### "},
    {']', " ### " "   # " "   # " "   # " "   # " "   # " " ### "},
    {'!', "  #  " "  #  " "  #  " "  #  " "  #  " "     " "  #  "},
    {'?', " ### " "#   #" "    #" "   # " "  #  " "     " "  #  "},
    {'\'', "  #  " "  #  " " #   " "     " "     " "     " "     "},
    {'"', " # # " " # # " "     " "     " "     " "     " "     "},
    {';', "     " " ##  " " ##  " "     " " ##  " "  #  " " #   "},
    {'#', " # # " " # # " "#####" " # # " "#####" " # # " " # # "},
    {'&', " ##  " "#  # " "# #  " " #   " "# # #" "#  # " " ## #"},
    {'~', "     " "     " " #   " "# # #" "   # " "     " "     "},
    {U'\u2248', "     " " ## #" "#  # " "     " " ## #" "#  # " "     "},  // ≈
    {U'\u2212', "     " "     " "     " "#####" "     " "     " "     "},  // − (minus sign)
    {U'\u00B1', "  #  " "  #  " "#####" "  #  " "  #  " "     " "#####"},  // ±
    {U'\u00D7', "     " "#   #" " # # " "  #  " " # # " "#   #" "     "},  // ×
    {U'\u00B7', "     " "     " "     " "  #  " "     " "     " "     "},  // ·
    {U'\u0394', "  #  " "  #  " " # # " " # # " "#   #" "#   #" "#####"},  // Δ
    {U'\u03B8', " ### " "#   #" "#   #" "#####" "#   #" "#   #" " ### "},  // θ
    {U'\u2026', "     " "     " "     " "     " "     " "     " "# # #"},  // …
};
}  // namespace

namespace {
// One code point of UTF-8 text (malformed bytes are taken one at a time as U+FFFD).
char32_t next_code_point(const std::string& s, size_t& i) {
  const auto b = static_cast<unsigned char>(s[i++]);
  if (b < 0x80) return b;
  const int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : -1;
  if (extra < 0) return 0xFFFD;
  char32_t cp = b & (0x3F >> extra);
  for (int k = 0; k < extra; ++k) {
    if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  }
  return cp;
}

const char* glyph_rows(char32_t cp) {
  for (const auto& gl : kFont)
    if (gl.c == cp) return gl.rows;
  if (cp < 0x80 && std::isalpha(static_cast<int>(cp)))  // no glyph of this case: the other one
    for (const auto& gl : kFont)
      if (gl.c == static_cast<char32_t>(std::toupper(static_cast<int>(cp)))) return gl.rows;
  return nullptr;
}
}  // namespace

void Canvas::text(int x, int y, const std::string& s, uint8_t r, uint8_t g, uint8_t b, int scale) {
  int cx = x;
  for (size_t i = 0; i < s.size();) {
    const char* rows = glyph_rows(next_code_point(s, i));
    if (rows) {
      const size_t n = std::strlen(rows);
      for (int j = 0; j < static_cast<int>(n / 5); ++j)
        for (int k = 0; k < 5; ++k) {
          const size_t at = static_cast<size_t>(j) * 5 + k;
          if (at >= n || rows[at] != '#') continue;
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) {
              const int X = cx + k * scale + sx, Y = y + j * scale + sy;
              if (X < 0 || Y < 0 || X >= width || Y >= height) continue;
              uint8_t* px = &rgb[(static_cast<size_t>(Y) * width + X) * 3];
              px[0] = r, px[1] = g, px[2] = b;
            }
        }
    }
    cx += 6 * scale;
  }
}

int Canvas::text_width(const std::string& s, int scale) {
  int n = 0;
  for (size_t i = 0; i < s.size();) {
    next_code_point(s, i);
    ++n;
  }
  return n * 6 * scale;
}

bool Canvas::has_glyph(char32_t cp) { return cp == U' ' || glyph_rows(cp) != nullptr; }

void Canvas::fill(int x, int y, int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  for (int Y = std::max(y, 0); Y < std::min(y + h, height); ++Y)
    for (int X = std::max(x, 0); X < std::min(x + w, width); ++X) {
      uint8_t* px = &rgb[(static_cast<size_t>(Y) * width + X) * 3];
      px[0] = r, px[1] = g, px[2] = b;
    }
}

}  // namespace shadecore::canvas
