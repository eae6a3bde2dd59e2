// SPDX-License-Identifier: Apache-2.0
// shadecore — the difference legend and the contact sheet's layout (shadecore/common/legend.hpp).
#include "shadecore/common/legend.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/core.h>

namespace shadecore::canvas {

namespace {
constexpr uint8_t kInk = 230;        // text
constexpr uint8_t kFrame = 140;      // the bar's frame and tick marks
constexpr uint8_t kStripGrey = 32;   // background of the strip under diff_exact.png

// Code points of a UTF-8 string, each as its own string (for cutting over-long words).
std::vector<std::string> chars_of(const std::string& s) {
  std::vector<std::string> out;
  for (size_t i = 0; i < s.size();) {
    size_t j = i + 1;
    while (j < s.size() && (static_cast<unsigned char>(s[j]) & 0xC0) == 0x80) ++j;
    out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

std::vector<std::string> words_of(const std::string& text) {
  std::vector<std::string> words;
  for (size_t i = 0; i < text.size();) {
    const size_t b = text.find(' ', i);
    const std::string w = text.substr(i, b == std::string::npos ? std::string::npos : b - i);
    if (!w.empty()) words.push_back(w);
    if (b == std::string::npos) break;
    i = b + 1;
  }
  return words;
}

// Δ ↔ position t in [−1, 1] on the log scale.
double t_of(double delta, int F) {
  const double full = std::log2(1.0 + std::ldexp(1.0, F));
  const double t = std::log2(1.0 + std::fabs(delta)) / full;
  return delta < 0 ? -t : t;
}
double delta_of(double t, int F) {
  const double d = std::pow(1.0 + std::ldexp(1.0, F), std::fabs(t)) - 1.0;
  return t < 0 ? -d : d;
}

std::string tick_text(double v) {
  const double a = std::fabs(v);
  std::string s;
  if (a < 10000) s = fmt::format("{:.0f}", a);
  else s = fmt::format("2^{}", static_cast<int>(std::lround(std::log2(a))));
  return v < 0 ? "-" + s : s;
}
}  // namespace

Box text_box(int x, int y, const std::string& s, int scale) {
  const int w = Canvas::text_width(s, scale);
  return Box{x, y, w > 0 ? w - scale : 0, Canvas::kTextRows * scale};
}

std::vector<std::string> wrap_text(const std::string& text, int max_px, int scale) {
  const int max_chars = std::max(1, (max_px + scale) / (6 * scale));  // n chars need (6n − 1)·scale px
  const std::vector<std::string> words = words_of(text);
  std::vector<std::string> lines;
  std::string line;
  int line_chars = 0;
  for (const auto& w : words) {
    auto cs = chars_of(w);
    const int n = static_cast<int>(cs.size());
    if (line_chars > 0 && line_chars + 1 + n <= max_chars) {
      line += " " + w;
      line_chars += 1 + n;
      continue;
    }
    if (line_chars > 0) lines.push_back(line);
    line.clear();
    line_chars = 0;
    // A word longer than a line: pieces of max_chars.
    size_t k = 0;
    while (static_cast<int>(cs.size() - k) > max_chars) {
      std::string piece;
      for (int c = 0; c < max_chars; ++c) piece += cs[k++];
      lines.push_back(piece);
    }
    for (; k < cs.size(); ++k) line += cs[k], ++line_chars;
  }
  if (line_chars > 0) lines.push_back(line);
  return lines;
}

std::array<uint8_t, 3> diff_colour(double delta, int F) {
  // render::diff_rgb8: v = round(255·log2(1 + |Δ|)/log2(1 + 2^F)), red for Δ > 0, blue otherwise.
  const double full = std::log2(1.0 + std::ldexp(1.0, F));
  const auto v = static_cast<uint8_t>(std::clamp(std::lround(255.0 * std::log2(1.0 + std::abs(delta)) / full), 0L, 255L));
  std::array<uint8_t, 3> c{0, 0, 0};
  c[delta > 0 ? 0 : 2] = v;
  return c;
}

std::string diff_caption(const std::string& what, int F) {
  return fmt::format("{} \u2212 exact, LSB of 2^-{} (log)", what, F);
}

std::string display_level_text(int F) {
  const double l = std::ldexp(1.0, F) / 255.0;
  const std::string v = l >= 100 ? fmt::format("{:.0f}", l) : l >= 10 ? fmt::format("{:.1f}", l) : fmt::format("{:.2f}", l);
  return "1 lvl \u2248 " + v + " LSB";
}

double DiffLegend::value_at(int x) const {
  const double t = bar.w > 1 ? 2.0 * (x - bar.x) / (bar.w - 1) - 1.0 : 0.0;
  return delta_of(std::clamp(t, -1.0, 1.0), F);
}

int DiffLegend::x_of(double delta) const {
  const double t = std::clamp(t_of(delta, F), -1.0, 1.0);
  return bar.x + static_cast<int>(std::lround((t + 1.0) / 2.0 * (bar.w - 1)));
}

std::vector<TextBox> DiffLegend::all_text() const {
  std::vector<TextBox> out = texts;
  for (const auto& t : ticks) out.push_back(t.label);
  return out;
}

int legend_scale(int width) { return width < 640 ? 1 : width < 1600 ? 2 : 3; }

int diff_legend_min_width(int scale) { return 216 * scale; }

DiffLegend layout_diff_legend(int x, int y, int width, int F, int scale, const std::string& caption) {
  DiffLegend L;
  L.F = F;
  L.scale = scale = std::max(1, scale);
  const int s = scale, m = 4 * s, line = Canvas::kTextRows * s, gap = 2 * s;
  const int inner_x = x + m, inner_w = std::max(1, width - 2 * m);
  int yc = y + m;
  for (const auto& ln : wrap_text(caption, inner_w, s)) {
    L.texts.push_back({text_box(inner_x, yc, ln, s), ln, s});
    yc += line + gap;
  }
  // The bar, inset by half an end label so that the end labels sit centred under its ends.
  const double full = std::ldexp(1.0, F);
  const int half_end = (text_box(0, 0, tick_text(-full), s).w + 1) / 2;
  int bw = std::min(inner_w - 2 * half_end, 1025 * s);
  if (bw < 3) bw = std::max(1, inner_w - 2);  // very narrow: the bar, ends unlabelled
  if (bw % 2 == 0) --bw;
  const int bar_h = 10 * s;
  yc += s;  // room for the frame
  L.bar = Box{x + (width - bw) / 2, yc, bw, bar_h};
  yc += bar_h + s;  // the frame below the bar
  // Ticks: 0, the ends ±2^F, then ±1, ±4, ±16, ±256, ±4096, ±2^16, … and last ±64, ±1024, ±2^14, …
  std::vector<double> mags = {0.0, full, 1.0, 4.0};
  for (int k = 4; k < F; k += 4) mags.push_back(std::ldexp(1.0, k));
  for (int k = 6; k < F; k += 4) mags.push_back(std::ldexp(1.0, k));
  const int mark_h = 3 * s, label_y = yc + mark_h + s;
  const Box inner{inner_x, y, inner_w, 1 << 30};
  std::vector<Box> placed;
  for (double mg : mags) {
    if (mg != 0 && mg != full && mg >= full) continue;
    std::vector<LegendTick> pair;
    bool fits = true;
    for (double v : mg == 0 ? std::vector<double>{0.0} : std::vector<double>{-mg, mg}) {
      LegendTick t;
      t.value = v;
      t.x = L.x_of(v);
      const std::string txt = tick_text(v);
      Box b = text_box(0, label_y, txt, s);
      b.x = t.x - b.w / 2;
      t.label = {b, txt, s};
      t.mark = Box{t.x - (s - 1) / 2, yc, s, mark_h};
      // A gap of one character to every label already placed, and inside the region.
      const Box spaced{b.x - 3 * s, b.y, b.w + 6 * s, b.h};
      if (!b.inside(inner)) fits = false;
      for (const auto& p : placed) fits = fits && !spaced.overlaps(p);
      for (const auto& q : pair) fits = fits && !spaced.overlaps(q.label.box);
      pair.push_back(t);
    }
    if (!fits || L.bar.w < 3) continue;
    for (const auto& t : pair) {
      placed.push_back(t.label.box);
      L.ticks.push_back(t);
    }
  }
  yc = label_y + line + gap + s;
  for (const std::string& key : {std::string("red: brighter, blue: darker"), display_level_text(F)})
    for (const auto& ln : wrap_text(key, inner_w, s)) {
      L.texts.push_back({text_box(inner_x, yc, ln, s), ln, s});
      yc += line + gap;
    }
  L.region = Box{x, y, width, yc - gap + m - y};
  return L;
}

DiffLegend draw_diff_legend(Canvas& cv, int x, int y, int width, int F, int scale, const std::string& caption) {
  const DiffLegend L = layout_diff_legend(x, y, width, F, scale, caption);
  const int s = L.scale;
  const Box& b = L.bar;
  cv.fill(b.x - s, b.y - s, b.w + 2 * s, b.h + 2 * s, kFrame, kFrame, kFrame);
  for (int i = 0; i < b.w; ++i) {
    const auto c = diff_colour(L.value_at(b.x + i), F);
    cv.fill(b.x + i, b.y, 1, b.h, c[0], c[1], c[2]);
  }
  for (const auto& t : L.ticks) {
    cv.fill(t.mark.x, t.mark.y, t.mark.w, t.mark.h, kFrame, kFrame, kFrame);
    cv.text(t.label.box.x, t.label.box.y, t.label.text, kInk, kInk, kInk, s);
  }
  for (const auto& t : L.texts) cv.text(t.box.x, t.box.y, t.text, kInk, kInk, kInk, s);
  return L;
}

Canvas with_diff_legend(int w, int h, const std::vector<uint8_t>& rgb, int F, const std::string& what,
                        DiffLegend* layout) {
  if (w < 1 || h < 1 || rgb.size() != static_cast<size_t>(w) * h * 3)
    throw std::invalid_argument("with_diff_legend: bad image size");
  const int s = legend_scale(w);
  const int W = std::max(w, diff_legend_min_width(s));
  const DiffLegend probe = layout_diff_legend(0, h, W, F, s, diff_caption(what, F));
  Canvas cv(W, h + probe.region.h, kStripGrey);
  cv.blit(0, 0, w, h, rgb);
  const DiffLegend L = draw_diff_legend(cv, 0, h, W, F, s, diff_caption(what, F));
  if (layout) *layout = L;
  return cv;
}

// ---- Key legend -------------------------------------------------------------------------------------------

KeyLegend layout_key_legend(int x, int y, int width, const std::vector<KeyEntry>& entries, const std::string& caption,
                            int scale) {
  KeyLegend L;
  L.scale = scale = std::max(1, scale);
  const int s = scale, m = 4 * s, line = Canvas::kTextRows * s, gap = 2 * s, sw = 7 * s;
  const int inner_x = x + m, inner_w = std::max(1, width - 2 * m);
  int yc = y + m;
  for (const auto& ln : wrap_text(caption, inner_w, s)) {
    L.texts.push_back({text_box(inner_x, yc, ln, s), ln, s});
    yc += line + gap;
  }
  const int tx = inner_x + sw + 2 * s + 4 * s;  // swatch, its frame, a gap
  const int tw = std::max(1, inner_x + inner_w - tx);
  for (const auto& e : entries) {
    L.swatches.push_back(Box{inner_x + s, yc + s, sw, sw});
    for (const auto& ln : wrap_text(e.text, tw, s)) {
      L.texts.push_back({text_box(tx, yc, ln, s), ln, s});
      yc += line + gap;
    }
  }
  L.region = Box{x, y, width, yc - gap + m - y};
  return L;
}

KeyLegend draw_key_legend(Canvas& cv, int x, int y, int width, const std::vector<KeyEntry>& entries,
                          const std::string& caption, int scale) {
  const KeyLegend L = layout_key_legend(x, y, width, entries, caption, scale);
  const int s = L.scale;
  for (size_t i = 0; i < entries.size(); ++i) {
    const Box& b = L.swatches[i];
    cv.fill(b.x - s, b.y - s, b.w + 2 * s, b.h + 2 * s, kFrame, kFrame, kFrame);
    cv.fill(b.x, b.y, b.w, b.h, entries[i].colour[0], entries[i].colour[1], entries[i].colour[2]);
  }
  for (const auto& t : L.texts) cv.text(t.box.x, t.box.y, t.text, kInk, kInk, kInk, s);
  return L;
}

Canvas with_key_legend(int w, int h, const std::vector<uint8_t>& rgb, const std::vector<KeyEntry>& entries,
                       const std::string& caption, KeyLegend* layout) {
  if (w < 1 || h < 1 || rgb.size() != static_cast<size_t>(w) * h * 3)
    throw std::invalid_argument("with_key_legend: bad image size");
  const int s = legend_scale(w);
  const int W = std::max(w, diff_legend_min_width(s));
  const KeyLegend probe = layout_key_legend(0, h, W, entries, caption, s);
  Canvas cv(W, h + probe.region.h, kStripGrey);
  cv.blit(0, 0, w, h, rgb);
  const KeyLegend L = draw_key_legend(cv, 0, h, W, entries, caption, s);
  if (layout) *layout = L;
  return cv;
}

// ---- Contact sheet ---------------------------------------------------------------------------------------

Box SheetLayout::cell(int row, int col) const {
  if (row < 0 || row >= rows || col < 0 || col >= cols) throw std::out_of_range("SheetLayout::cell");
  return Box{grid_x + col * (slot_w + pad) + (slot_w - cell_w) / 2, grid_y + row * (cell_h + pad), cell_w, cell_h};
}

Canvas SheetLayout::canvas() const { return Canvas(width, height, 24); }

void SheetLayout::draw_labels(Canvas& cv) const {
  for (const auto& t : headers) cv.text(t.box.x, t.box.y, t.text, kInk, kInk, kInk, t.scale);
  for (const auto& t : row_labels) cv.text(t.box.x, t.box.y, t.text, kInk, kInk, kInk, t.scale);
}

DiffLegend SheetLayout::legend_layout() const { return layout_diff_legend(legend.x, legend.y, legend.w, F, scale, caption); }

DiffLegend SheetLayout::draw_legend(Canvas& cv) const { return draw_diff_legend(cv, legend.x, legend.y, legend.w, F, scale, caption); }

void SheetLayout::place(Canvas& cv, int row, int col, const std::vector<uint8_t>& rgb) const {
  const Box b = cell(row, col);
  if (rgb.size() != static_cast<size_t>(cell_w) * cell_h * 3) throw std::invalid_argument("SheetLayout::place: not a cell image");
  cv.blit(b.x, b.y, b.w, b.h, rgb);
}

SheetLayout layout_sheet(int cell_w, int cell_h, const std::vector<std::string>& col_names,
                         const std::vector<std::string>& row_names, int F, const std::string& caption_what) {
  if (col_names.empty() || row_names.empty()) throw std::invalid_argument("layout_sheet: no columns or rows");
  if (cell_w < 1 || cell_h < 1 || cell_w > 4096 || cell_h > 4096) throw std::invalid_argument("layout_sheet: bad cell size");
  SheetLayout L;
  L.cell_w = cell_w, L.cell_h = cell_h;
  L.cols = static_cast<int>(col_names.size()), L.rows = static_cast<int>(row_names.size());
  L.F = F;
  L.caption = diff_caption(caption_what, F);
  const int small = std::min(cell_w, cell_h);
  const int s = L.scale = small < 192 ? 1 : small < 448 ? 2 : 3;
  const int pad = L.pad = 6 * s, line = Canvas::kTextRows * s, gap = 2 * s;
  // Slot width: the cell, or the longest word of any header if that is wider (headers wrap at blanks).
  // (a word plus one character, so that neighbouring headers keep a blank between them beyond the pad).
  int slot = cell_w;
  for (const auto& name : col_names)
    for (const auto& word : words_of(name)) slot = std::max(slot, text_box(0, 0, word, s).w + 6 * s);
  L.slot_w = slot;
  int row_w = 0;
  for (const auto& r : row_names) row_w = std::max(row_w, text_box(0, 0, r, s).w);
  std::vector<std::vector<std::string>> head(col_names.size());
  size_t head_lines = 0;
  for (size_t c = 0; c < col_names.size(); ++c) {
    head[c] = wrap_text(col_names[c], slot, s);
    head_lines = std::max(head_lines, head[c].size());
  }
  const int head_h = head_lines ? static_cast<int>(head_lines) * (line + gap) - gap : 0;
  L.grid_x = pad + (row_w > 0 ? row_w + pad : 0);
  L.grid_y = pad + (head_h > 0 ? head_h + pad : 0);
  for (int c = 0; c < L.cols; ++c) {
    const int sx = L.grid_x + c * (slot + pad);
    for (size_t k = 0; k < head[c].size(); ++k) {
      Box b = text_box(0, pad + static_cast<int>(k) * (line + gap), head[c][k], s);
      b.x = sx + (slot - b.w) / 2;
      L.headers.push_back({b, head[c][k], s});
      L.header_col.push_back(c);
    }
  }
  for (int r = 0; r < L.rows; ++r) {
    const int cy = L.grid_y + r * (cell_h + pad);
    L.row_labels.push_back({text_box(pad, cy + (cell_h - line) / 2, row_names[r], s), row_names[r], s});
  }
  const int grid_w = L.cols * slot + (L.cols - 1) * pad;
  const int grid_bottom = L.grid_y + L.rows * cell_h + (L.rows - 1) * pad;
  const int legend_w = std::max(grid_w, diff_legend_min_width(s));
  const DiffLegend probe = layout_diff_legend(L.grid_x, grid_bottom + pad, legend_w, F, s, L.caption);
  L.legend = probe.region;
  L.width = L.grid_x + legend_w + pad;
  L.height = L.legend.bottom() + pad;
  return L;
}

}  // namespace shadecore::canvas
