// SPDX-License-Identifier: Apache-2.0
// shadecore — legends and layout for the render images (issue 23): the colour bar of the signed log-scale
// difference images (render::diff_rgb8) and the contact sheet's layout (cells, column headers, row labels and
// one legend strip), drawn with shadecore/common/png.hpp's Canvas and its 5×7 font.
//
// The difference scale (render::diff_rgb8, not changed here): per pixel Δ = code − 2^F·ref in output LSBs
// (2^−F); red where the image is brighter than the reference, blue where darker, intensity
// 255·log2(1 + |Δ|)/log2(1 + 2^F); black = identical. The legend's bar runs from −2^F (full blue) through 0
// (black) to +2^F (full red) on that scale, column by column through the same mapping (diff_colour below),
// with tick labels in LSB at 0, ±1, ±4, ±16, ±256, … (as many as fit without touching each other), the 8-bit
// display-level equivalent (1 level of an 8-bit PNG = 2^F/255 LSB, "1 lvl ≈ 257 LSB" at F = 16) and a caption
// ("cmodel − exact, LSB of 2^-16 (log)").
//
// ---- Usage in cli/cmd_render.cpp ------------------------------------------------------------------------
//
// diff_exact.png (the image at the top left, pixel (x, y) where it was, so the JSON's "max_at" still points
// at it; the legend strip below; an image narrower than the legend is padded on the right):
//
//     const Canvas d = with_diff_legend(fr.width, fr.height, render::diff_rgb8(main.image, main.exact), fr.F);
//     files.emplace_back("diff_exact.png", encode_png(d.width, d.height, d.rgb));
//
// Contact sheet (replaces the block after "// Contact sheet:" that computes pad / label_h / row_label_w, the
// Canvas and the cv.text() calls; col_names as today, one row name per mode):
//
//     std::vector<std::string> row_names;
//     for (const auto& m : cs.modes) row_names.push_back(m ? scene::to_string(*m) : "scene");
//     const SheetLayout L = layout_sheet(cs.cell_width, cs.cell_height, col_names, row_names, fr.F);
//     Canvas cv = L.canvas();           // L.width × L.height, background filled
//     L.draw_labels(cv);                // column headers and row labels
//     L.draw_legend(cv);                // one colour bar for every difference column
//     ...
//     L.place(cv, r, 0, render::to_rgb8(cell.exact));                       // row r, column 0: exact
//     L.place(cv, r, 1 + 2 * u, render::to_rgb8(cell.image));              // unit u
//     L.place(cv, r, 2 + 2 * u, render::diff_rgb8(cell.image, cell.exact)); // unit u − exact
//     ...
//     files.emplace_back("contact_sheet.png", encode_png(cv.width, cv.height, cv.rgb));
//
// (L.cell(r, c) is the cell's Box if the caller blits itself; every cell is cell_w × cell_h.) Suggested
// column names: "exact cos^n", then per unit "<unit>" and "<unit> − exact" (the legend says "(log)" and the
// unit of the scale, so the headers need not).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "shadecore/common/png.hpp"

namespace shadecore::canvas {

// A rectangle of pixels [x, x + w) × [y, y + h).
struct Box {
  int x = 0, y = 0, w = 0, h = 0;
  [[nodiscard]] int right() const { return x + w; }
  [[nodiscard]] int bottom() const { return y + h; }
  [[nodiscard]] bool overlaps(const Box& o) const {
    return w > 0 && h > 0 && o.w > 0 && o.h > 0 && x < o.right() && o.x < right() && y < o.bottom() && o.y < bottom();
  }
  [[nodiscard]] bool inside(const Box& o) const { return x >= o.x && y >= o.y && right() <= o.right() && bottom() <= o.bottom(); }
};

// One line of text and the box its ink lies in (text_box below).
struct TextBox {
  Box box;
  std::string text;
  int scale = 1;
};

// The box of `s` drawn by Canvas::text at (x, y): (6·chars − 1)·scale wide, Canvas::kTextRows·scale high.
Box text_box(int x, int y, const std::string& s, int scale);

// Splits `text` at blanks into lines of at most `max_px` pixels at `scale`; a word longer than that is cut
// into pieces that fit. No character is lost: joining the lines with blanks gives the words back.
std::vector<std::string> wrap_text(const std::string& text, int max_px, int scale);

// render::diff_rgb8's colour of a difference of `delta` LSBs at F fraction bits (the same formula).
std::array<uint8_t, 3> diff_colour(double delta, int F);

// "cmodel − exact, LSB of 2^-16 (log)" for what = "cmodel", F = 16.
std::string diff_caption(const std::string& what, int F);

// "1 lvl ≈ 257 LSB" at F = 16 (one level of an 8-bit image, 2^F/255 LSB).
std::string display_level_text(int F);

// ---- The colour bar ---------------------------------------------------------------------------------------

struct LegendTick {
  double value = 0;  // Δ in LSB
  int x = 0;         // the bar column of this value
  Box mark;          // the tick mark under the bar
  TextBox label;
};

// What draw_diff_legend draws and where (layout_diff_legend computes it without drawing).
struct DiffLegend {
  Box region;                    // the whole legend (x, y, width as given, the height it needs)
  Box bar;                       // the colour bar; its width is odd, its middle column is Δ = 0
  int F = 16, scale = 1;
  std::vector<LegendTick> ticks;  // in drawing order of priority (0, ±2^F, ±1, ±4, ±16, ±256, …)
  std::vector<TextBox> texts;     // caption and key lines (not the tick labels)
  // Δ shown by bar column x (bar.x ≤ x < bar.right()), and the column showing Δ.
  [[nodiscard]] double value_at(int x) const;
  [[nodiscard]] int x_of(double delta) const;
  // Every text box: texts and tick labels.
  [[nodiscard]] std::vector<TextBox> all_text() const;
};

// Text scale of a legend for an image `width` pixels wide (1 below 640 px, 2 below 1600, else 3).
int legend_scale(int width);
// The narrowest legend that is legible at `scale` (216·scale px: the caption on one line, the ends and 0 labelled).
int diff_legend_min_width(int scale);

// The legend in the region starting at (x, y), `width` pixels wide (at least diff_legend_min_width(scale) is
// legible; narrower still works, with fewer ticks and more caption lines). Its height is region.h.
DiffLegend layout_diff_legend(int x, int y, int width, int F, int scale, const std::string& caption);
// Draws it into `cv` (text in light grey: meant for a dark background) and returns the layout.
DiffLegend draw_diff_legend(Canvas& cv, int x, int y, int width, int F, int scale, const std::string& caption);

// The difference image (w × h, 8-bit RGB as from render::diff_rgb8) with a legend strip appended below:
// the image at (0, 0), the canvas max(w, diff_legend_min_width) wide (padded on the right in dark grey).
// `what` names the image in the caption ("cmodel − exact, ..."). If `layout` is given it receives the
// legend's layout (canvas coordinates).
Canvas with_diff_legend(int w, int h, const std::vector<uint8_t>& rgb, int F, const std::string& what = "cmodel",
                        DiffLegend* layout = nullptr);

// ---- A key of colours (issue 38: diff_rtl.png, gl-compare's diff.png) -------------------------------------

// One line of a key: a colour swatch and what the colour means.
struct KeyEntry {
  std::array<uint8_t, 3> colour{};
  std::string text;
};

// What draw_key_legend draws and where: the caption's lines, then one entry per line (a framed swatch, its text
// wrapped beside it).
struct KeyLegend {
  Box region;
  int scale = 1;
  std::vector<Box> swatches;     // one per entry, inside its frame
  std::vector<TextBox> texts;    // caption lines and entry lines
  [[nodiscard]] std::vector<TextBox> all_text() const { return texts; }
};

KeyLegend layout_key_legend(int x, int y, int width, const std::vector<KeyEntry>& entries, const std::string& caption,
                            int scale);
KeyLegend draw_key_legend(Canvas& cv, int x, int y, int width, const std::vector<KeyEntry>& entries,
                          const std::string& caption, int scale);

// An image (w × h RGB) with its key below, as with_diff_legend: the image at (0, 0), the canvas
// max(w, diff_legend_min_width) wide.
Canvas with_key_legend(int w, int h, const std::vector<uint8_t>& rgb, const std::vector<KeyEntry>& entries,
                       const std::string& caption, KeyLegend* layout = nullptr);

// ---- The contact sheet --------------------------------------------------------------------------------------

// Columns are slots at least cell_w wide (wider when a header word needs it, plus one character between
// neighbouring headers; the cell is centred in its slot),
// headers wrapped to the slot width, row labels as wide as the longest, one legend strip below the grid.
struct SheetLayout {
  int width = 0, height = 0;  // the canvas
  int cell_w = 0, cell_h = 0, rows = 0, cols = 0;
  int scale = 1, pad = 6;
  int slot_w = 0;             // column pitch minus pad
  int grid_x = 0, grid_y = 0; // top left of cell (0, 0)'s slot
  int F = 16;
  std::string caption;        // the legend's
  std::vector<TextBox> headers;     // every line of every column header
  std::vector<int> header_col;      // the column of each headers[i]
  std::vector<TextBox> row_labels;  // one per row
  Box legend;                 // the legend strip's region (layout_diff_legend at legend.x, legend.y, legend.w)

  [[nodiscard]] Box cell(int row, int col) const;   // where cell (row, col) goes (cell_w × cell_h)
  [[nodiscard]] Canvas canvas() const;              // width × height, background grey 24
  void draw_labels(Canvas& cv) const;               // headers and row labels
  DiffLegend draw_legend(Canvas& cv) const;         // the legend strip
  [[nodiscard]] DiffLegend legend_layout() const;   // what draw_legend draws
  // Blits a cell_w × cell_h RGB image into cell (row, col).
  void place(Canvas& cv, int row, int col, const std::vector<uint8_t>& rgb) const;
};

// Throws std::invalid_argument on no columns / rows or a cell outside 1..4096.
SheetLayout layout_sheet(int cell_w, int cell_h, const std::vector<std::string>& col_names,
                         const std::vector<std::string>& row_names, int F,
                         const std::string& caption_what = "unit");

}  // namespace shadecore::canvas
