// SPDX-License-Identifier: Apache-2.0
// Issue 23: the legend of the signed log-scale difference images and the contact sheet's layout
// (shadecore/common/legend.hpp). The layout is checked on its boxes and on the pixels drawn: no two labels overlap, every
// label lies inside the canvas and outside every cell, for every cell size, unit count and mode count the
// scene format allows; the bar's colours are render::diff_rgb8's at the tick positions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "shadecore/common/legend.hpp"
#include "shadecore/common/png.hpp"
#include "shadecore/render/render.hpp"

using namespace shadecore::canvas;
namespace render = shadecore::render;

namespace {

// The colour render::diff_rgb8 gives a one-pixel image whose code differs from 2^F·ref by `delta` LSBs.
std::array<uint8_t, 3> rgb8_of_delta(long long delta, int F) {
  render::Image img;
  img.width = img.height = 1;
  img.F = F;
  render::RefImage ref;
  ref.width = ref.height = 1;
  const long long one = 1LL << F;
  // ref 0 and code Δ for Δ ≥ 0; ref 1 and code 2^F + Δ below (codes are unsigned).
  const double r = delta >= 0 ? 0.0 : 1.0;
  const auto code = static_cast<uint32_t>(delta >= 0 ? delta : one + delta);
  img.code = {code, code, code};
  img.covered = {1};
  img.group = {0};
  ref.value = {r, r, r};
  const auto v = render::diff_rgb8(img, ref);
  return {v[0], v[1], v[2]};
}

std::array<uint8_t, 3> pixel(const Canvas& cv, int x, int y) {
  const size_t k = (static_cast<size_t>(y) * cv.width + x) * 3;
  return {cv.rgb[k], cv.rgb[k + 1], cv.rgb[k + 2]};
}

// Ink of `t` drawn alone lies inside its box (the boxes the layout reports are where the text goes).
void expect_ink_inside_box(const TextBox& t) {
  Canvas cv(t.box.right() + 40, t.box.bottom() + 40, 0);
  cv.text(t.box.x, t.box.y, t.text, 255, 255, 255, t.scale);
  int ink = 0;
  for (int y = 0; y < cv.height; ++y)
    for (int x = 0; x < cv.width; ++x)
      if (pixel(cv, x, y)[0]) {
        ++ink;
        ASSERT_TRUE(x >= t.box.x && x < t.box.right() && y >= t.box.y && y < t.box.bottom())
            << "'" << t.text << "' has ink at (" << x << ", " << y << ") outside its box";
      }
  EXPECT_GT(ink, 0) << "'" << t.text << "' draws nothing";
}

std::vector<std::string> sheet_columns(int units) {
  // The longest unit names of config/configs.json, as cmd_render.cpp names the columns.
  const std::vector<std::string> u = {"cs16_faithful", "schlick_iter", "table1024", "cs16_compact"};
  std::vector<std::string> c = {"exact cos^n"};
  for (int i = 0; i < units; ++i) {
    c.push_back(u[i]);
    c.push_back(u[i] + " \u2212 exact (log)");
  }
  return c;
}

std::vector<std::string> sheet_rows(int modes) {
  const std::vector<std::string> m = {"scene", "flat", "gouraud", "phong"};
  std::vector<std::string> r;
  for (int i = 0; i < modes; ++i) r.push_back(m[i % 4]);
  return r;
}

void check_legend_boxes(const DiffLegend& L, const Box& canvas, const std::string& what) {
  EXPECT_TRUE(L.region.inside(canvas)) << what;
  EXPECT_TRUE(L.bar.inside(L.region)) << what;
  EXPECT_EQ(L.bar.w % 2, 1) << what;
  const auto texts = L.all_text();
  for (size_t i = 0; i < texts.size(); ++i) {
    EXPECT_TRUE(texts[i].box.inside(L.region)) << what << ": '" << texts[i].text << "' outside the legend";
    EXPECT_FALSE(texts[i].box.overlaps(L.bar)) << what << ": '" << texts[i].text << "' on the bar";
    for (size_t j = i + 1; j < texts.size(); ++j)
      EXPECT_FALSE(texts[i].box.overlaps(texts[j].box)) << what << ": '" << texts[i].text << "' / '" << texts[j].text << "'";
  }
}

}  // namespace

TEST(Legend, WrapKeepsEveryWordAndFits) {
  for (int px : {5, 11, 17, 40, 100, 1000})
    for (int s : {1, 2}) {
      const std::string text = "cs16_faithful \u2212 exact (log)";
      const auto lines = wrap_text(text, px, s);
      std::string joined;
      for (const auto& l : lines) {
        EXPECT_LE(text_box(0, 0, l, s).w, std::max(px, 5 * s)) << "'" << l << "' at " << px;
        joined += l;
      }
      std::string want = text;
      want.erase(std::remove(want.begin(), want.end(), ' '), want.end());
      joined.erase(std::remove(joined.begin(), joined.end(), ' '), joined.end());
      EXPECT_EQ(joined, want) << px;
    }
  EXPECT_EQ(wrap_text("a bc def", 1000, 1), std::vector<std::string>{"a bc def"});
  EXPECT_EQ(wrap_text("a bc def", 23, 1), (std::vector<std::string>{"a bc", "def"}));  // 4 chars = 23 px
}

TEST(Legend, FontHasTheLegendsCharacters) {
  for (char32_t c : {U'a', U'z', U'g', U'\u2212', U'\u2248', U'^', U'(', U')', U',', U':', U'-'})
    EXPECT_TRUE(Canvas::has_glyph(c)) << static_cast<uint32_t>(c);
  // Lower case is its own glyph now, not the upper-case one.
  Canvas a(6, 7, 0), b(6, 7, 0);
  a.text(0, 0, "a", 255, 255, 255);
  b.text(0, 0, "A", 255, 255, 255);
  EXPECT_NE(a.rgb, b.rgb);
  EXPECT_EQ(Canvas::text_width("\u2248 x"), 18);  // code points, not bytes
}

TEST(Legend, TextsAndCaption) {
  EXPECT_EQ(display_level_text(16), "1 lvl \u2248 257 LSB");
  EXPECT_EQ(display_level_text(8), "1 lvl \u2248 1.00 LSB");
  EXPECT_EQ(diff_caption("cmodel", 16), "cmodel \u2212 exact, LSB of 2^-16 (log)");
}

// The bar at each tick is render::diff_rgb8's colour of that Δ (up to one bar column of the scale), its ends
// are full blue and red, its middle black; texts stay off the bar and off each other; the image is kept.
TEST(Legend, DiffLegendBarMatchesDiffRgb8AtTicks) {
  for (int F : {8, 12, 16, 24})
    for (int w : {1, 7, 64, 215, 300, 639, 640, 1599, 1600, 4096}) {
      const int h = 3;
      std::vector<uint8_t> img(static_cast<size_t>(w) * h * 3);
      for (size_t i = 0; i < img.size(); ++i) img[i] = static_cast<uint8_t>(i * 7 + 1);
      DiffLegend L;
      const Canvas cv = with_diff_legend(w, h, img, F, "cmodel", &L);
      const std::string what = "F = " + std::to_string(F) + ", width " + std::to_string(w);
      ASSERT_GE(cv.width, w) << what;
      EXPECT_GE(cv.width, diff_legend_min_width(legend_scale(w))) << what;
      EXPECT_EQ(cv.height, h + L.region.h) << what;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c)
            ASSERT_EQ(cv.rgb[(static_cast<size_t>(y) * cv.width + x) * 3 + c], img[(static_cast<size_t>(y) * w + x) * 3 + c])
                << what << ": image pixel moved";
      check_legend_boxes(L, Box{0, 0, cv.width, cv.height}, what);
      EXPECT_GE(L.region.y, h) << what << ": the legend covers the image";
      const int mid_y = L.bar.y + L.bar.h / 2;
      // One bar column spans 2/(w − 1) of the scale: 255·2/(w − 1) intensity levels.
      const int tol = static_cast<int>(std::ceil(510.0 / (L.bar.w - 1))) + 1;
      const double full = std::ldexp(1.0, F);
      bool zero = false, lo = false, hi = false, one = false;
      for (const auto& t : L.ticks) {
        const auto want = rgb8_of_delta(std::llround(t.value), F);
        const auto got = pixel(cv, t.x, mid_y);
        for (int c = 0; c < 3; ++c)
          EXPECT_LE(std::abs(int(got[c]) - int(want[c])), tol)
              << what << ": tick " << t.label.text << " channel " << c << " bar " << int(got[c]) << " diff_rgb8 " << int(want[c]);
        EXPECT_EQ(got[1], 0) << what;
        if (t.value > 0) {
          EXPECT_EQ(got[2], 0) << what << ": tick " << t.label.text << " not red";
        }
        if (t.value < 0) {
          EXPECT_EQ(got[0], 0) << what << ": tick " << t.label.text << " not blue";
        }
        EXPECT_TRUE(t.label.box.y >= L.bar.bottom()) << what;
        expect_ink_inside_box(t.label);
        zero |= t.value == 0, lo |= t.value == -full, hi |= t.value == full, one |= t.value == 1;
      }
      EXPECT_TRUE(zero && lo && hi) << what << ": 0 and both ends must be labelled";
      if (F <= 16 && L.bar.w >= 600) {
        EXPECT_TRUE(one) << what << ": a wide bar labels ±1";
      }
      // As many ticks as fit: a wide bar has more labels than a narrow one.
      if (w >= 640) {
        EXPECT_GE(L.ticks.size(), 9u) << what;
      }
      EXPECT_EQ(pixel(cv, L.bar.x, mid_y), rgb8_of_delta(-(1LL << F), F)) << what;
      EXPECT_EQ(pixel(cv, L.bar.right() - 1, mid_y), rgb8_of_delta(1LL << F, F)) << what;
      EXPECT_EQ(pixel(cv, L.bar.x + L.bar.w / 2, mid_y), (std::array<uint8_t, 3>{0, 0, 0})) << what;
      bool level = false, caption = false;
      for (const auto& t : L.texts) {
        level |= t.text.find("lvl") != std::string::npos;
        caption |= t.text.find("cmodel") != std::string::npos;
        expect_ink_inside_box(t);
      }
      EXPECT_TRUE(level && caption) << what;
    }
}

// Every label box inside the canvas, none overlapping another or a cell, cells not overlapping each other,
// the legend below the cells, and no label ink inside a cell, for every allowed cell size × 1..4 units ×
// 1..8 modes.
TEST(Legend, ContactSheetLabelsNeverOverlap) {
  const std::vector<int> sizes = {16, 17, 23, 31, 40, 64, 79, 100, 128, 160, 191, 192, 255, 300, 447, 448, 640, 1024};
  for (int cw : sizes)
    for (int ch : {16, 160, 1024})
      for (int units = 1; units <= 4; ++units)
        for (int modes = 1; modes <= 8; modes += (cw > 300 ? 7 : 1)) {
          const auto cols = sheet_columns(units);
          const auto rows = sheet_rows(modes);
          const SheetLayout L = layout_sheet(cw, ch, cols, rows, 16);
          const std::string what = std::to_string(cw) + "x" + std::to_string(ch) + ", " + std::to_string(units) +
                                   " units, " + std::to_string(modes) + " modes";
          const Box canvas{0, 0, L.width, L.height};
          std::vector<Box> cells;
          for (int r = 0; r < L.rows; ++r)
            for (int c = 0; c < L.cols; ++c) {
              const Box b = L.cell(r, c);
              ASSERT_EQ(b.w, cw);
              ASSERT_EQ(b.h, ch);
              EXPECT_TRUE(b.inside(canvas)) << what;
              for (const auto& o : cells) ASSERT_FALSE(b.overlaps(o)) << what << ": cells overlap";
              EXPECT_FALSE(b.overlaps(L.legend)) << what << ": legend on a cell";
              cells.push_back(b);
            }
          std::vector<TextBox> labels = L.headers;
          labels.insert(labels.end(), L.row_labels.begin(), L.row_labels.end());
          ASSERT_EQ(L.row_labels.size(), rows.size());
          for (size_t i = 0; i < labels.size(); ++i) {
            ASSERT_TRUE(labels[i].box.inside(canvas)) << what << ": '" << labels[i].text << "' outside";
            EXPECT_FALSE(labels[i].box.overlaps(L.legend)) << what << ": '" << labels[i].text << "' on the legend";
            for (const auto& c : cells) ASSERT_FALSE(labels[i].box.overlaps(c)) << what << ": '" << labels[i].text << "' on a cell";
            for (size_t j = i + 1; j < labels.size(); ++j)
              ASSERT_FALSE(labels[i].box.overlaps(labels[j].box))
                  << what << ": '" << labels[i].text << "' overlaps '" << labels[j].text << "'";
          }
          // Every header is all there (wrapped, not cut), and its lines stay within its column.
          for (int c = 0; c < L.cols; ++c) {
            std::string joined;
            for (size_t i = 0; i < L.headers.size(); ++i)
              if (L.header_col[i] == c) joined += (joined.empty() ? "" : " ") + L.headers[i].text;
            EXPECT_EQ(joined, cols[c]) << what;
          }
          check_legend_boxes(L.legend_layout(), canvas, what);
          // Pixels: draw everything but the cells; nothing lands inside a cell.
          if (units == 4 && (modes == 8 || modes == 1) && ch == 160) {
            Canvas cv = L.canvas();
            L.draw_labels(cv);
            const DiffLegend D = L.draw_legend(cv);
            EXPECT_TRUE(D.region.inside(canvas));
            for (const auto& b : cells)
              for (int y = b.y; y < b.bottom(); y += std::max(1, b.h / 16))
                for (int x = b.x; x < b.right(); ++x)
                  ASSERT_EQ(pixel(cv, x, y), (std::array<uint8_t, 3>{24, 24, 24})) << what << ": ink in a cell";
            for (const auto& t : labels) expect_ink_inside_box(t);
          }
        }
}

TEST(Legend, ContactSheetPlaceAndErrors) {
  const SheetLayout L = layout_sheet(16, 16, sheet_columns(1), sheet_rows(2), 16);
  Canvas cv = L.canvas();
  const std::vector<uint8_t> red(16 * 16 * 3, 0);
  std::vector<uint8_t> img = red;
  for (size_t i = 0; i < img.size(); i += 3) img[i] = 200;
  L.place(cv, 1, 2, img);
  const Box b = L.cell(1, 2);
  EXPECT_EQ(pixel(cv, b.x, b.y), (std::array<uint8_t, 3>{200, 0, 0}));
  EXPECT_EQ(pixel(cv, b.right() - 1, b.bottom() - 1), (std::array<uint8_t, 3>{200, 0, 0}));
  EXPECT_EQ(pixel(cv, b.right(), b.bottom()), (std::array<uint8_t, 3>{24, 24, 24}));
  EXPECT_THROW((void)L.cell(2, 0), std::out_of_range);
  EXPECT_THROW(L.place(cv, 0, 0, std::vector<uint8_t>(5)), std::invalid_argument);
  EXPECT_THROW(layout_sheet(16, 16, {}, {"a"}, 16), std::invalid_argument);
  // Small cells: columns widen to the longest header word instead of cutting it.
  EXPECT_GE(L.slot_w, text_box(0, 0, "cs16_faithful", 1).w);
}

// Issue 38: the key under diff_rtl.png and gl-compare's diff.png. For image widths from tiny to wide: the image
// is where it was, every text and swatch inside the canvas and below the image, no two overlapping, each swatch
// drawn in its colour.
TEST(Legend, KeyLegendNeverOverlaps) {
  const std::vector<KeyEntry> entries = {{{255, 255, 255}, "RTL pixel differs from the C model's"},
                                         {{40, 40, 40}, "covered, RTL = C model"},
                                         {{255, 0, 255}, "a different object in each, with a long explanation "
                                                         "that has to wrap onto a second line on narrow images"}};
  for (int w : {1, 7, 48, 96, 215, 216, 480, 700, 1700}) {
    const int h = 20;
    std::vector<uint8_t> img(static_cast<size_t>(w) * h * 3, 77);
    KeyLegend L;
    const Canvas cv = with_key_legend(w, h, img, entries, "RTL vs C model, per pixel", &L);
    const std::string what = "width " + std::to_string(w);
    const Box canvas{0, 0, cv.width, cv.height};
    EXPECT_EQ(pixel(cv, w - 1, h - 1), (std::array<uint8_t, 3>{77, 77, 77})) << what;
    EXPECT_GE(L.texts.size(), entries.size() + 1) << what;
    std::vector<Box> boxes;
    for (const auto& t : L.texts) boxes.push_back(t.box);
    for (const auto& b : L.swatches) boxes.push_back(b);
    for (size_t i = 0; i < boxes.size(); ++i) {
      EXPECT_TRUE(boxes[i].inside(canvas)) << what << ": box " << i << " outside the canvas";
      EXPECT_GE(boxes[i].y, h) << what << ": box " << i << " on the image";
      for (size_t j = i + 1; j < boxes.size(); ++j) EXPECT_FALSE(boxes[i].overlaps(boxes[j])) << what << ": " << i << "/" << j;
    }
    ASSERT_EQ(L.swatches.size(), entries.size());
    for (size_t i = 0; i < entries.size(); ++i)
      EXPECT_EQ(pixel(cv, L.swatches[i].x, L.swatches[i].y), entries[i].colour) << what;
  }
  EXPECT_THROW(with_key_legend(4, 4, std::vector<uint8_t>(5), entries, "x"), std::invalid_argument);
}
