// Layout: wrapping, alignment, line height, hard breaks, measuring.
#include <gtest/gtest.h>

#include <cmath>

#include "text_support.hpp"
#include "vraster/error.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;
using namespace vraster::text::testing;

namespace {

const std::string kParagraph =
    "The quick brown fox jumps over the lazy dog while the five boxing wizards jump quickly and a wonderful "
    "serif font keeps its kerning pairs such as AV and To intact.";

double sum_of_advances(const FontList& fonts, const std::u32string& text, double size) {
  double w = 0;
  for (char32_t c : text) w += fonts.fonts[0]->advance(fonts.fonts[0]->glyph_index(c), size);
  return w;
}

}  // namespace

TEST(Layout, SingleLineAdvanceIsTheSumOfGlyphAdvancesWithoutKerningPairs) {
  const auto fonts = FontList::default_list();
  TextStyle style;
  style.size = 20;
  const auto m = measure_text("minimum", fonts, style);  // no kerning pairs or ligatures in this word
  EXPECT_NEAR(m.advance, sum_of_advances(fonts, U"minimum", 20), 1e-9);
  EXPECT_EQ(m.lines, 1);
}

TEST(Layout, WrappedLinesFitTheWidthAndBreakAtSpaces) {
  const auto fonts = FontList::default_list();
  TextStyle style;
  style.size = 16;
  LayoutOptions lo;
  lo.max_width = 200;
  const TextLayout layout = layout_text(kParagraph, fonts, style, lo, {5, 30});
  ASSERT_GE(layout.lines.size(), 4u);
  const std::u32string text = decode_utf8(kParagraph);
  for (std::size_t k = 0; k < layout.lines.size(); ++k) {
    const TextLine& line = layout.lines[k];
    EXPECT_LE(line.width, 200 + 1e-9) << k;
    // Lines start at a word and end at a word: never inside one.
    EXPECT_NE(text[line.text_begin], U' ');
    EXPECT_NE(text[line.text_end - 1], U' ');
    if (line.text_end < text.size()) {
      EXPECT_EQ(text[line.text_end], U' ') << k;
    }
    // Greedy: the next line's first word would not have fitted.
    if (k + 1 < layout.lines.size()) {
      std::uint32_t e = layout.lines[k + 1].text_begin;
      while (e < text.size() && text[e] != U' ') ++e;
      const std::u32string with_next = text.substr(line.text_begin, e - line.text_begin);
      EXPECT_GT(measure_text(std::string(with_next.begin(), with_next.end()), fonts, style).advance, 200.0) << k;
    }
  }
  // Every non-space character appears on exactly one line, in order.
  std::uint32_t covered = 0;
  for (const TextLine& line : layout.lines) {
    EXPECT_GE(line.text_begin, covered);
    for (std::uint32_t i = covered; i < line.text_begin; ++i) EXPECT_EQ(text[i], U' ');
    covered = line.text_end;
  }
  EXPECT_EQ(covered, text.size());
}

TEST(Layout, LineHeightAndBaselines) {
  const auto fonts = FontList::default_list();
  TextStyle style;
  style.size = 10;
  LayoutOptions lo;
  lo.max_width = 150;
  const TextLayout natural = layout_text(kParagraph, fonts, style, lo, {0, 12});
  const double lh = fonts.fonts[0]->metrics(10).line_height();
  for (std::size_t k = 0; k < natural.lines.size(); ++k) EXPECT_NEAR(natural.lines[k].baseline, 12 + k * lh, 1e-9);
  lo.line_height = 17.5;
  const TextLayout fixed = layout_text(kParagraph, fonts, style, lo, {0, 12});
  for (std::size_t k = 0; k < fixed.lines.size(); ++k) EXPECT_NEAR(fixed.lines[k].baseline, 12 + k * 17.5, 1e-9);
  for (const auto& g : fixed.glyphs) {
    bool on_a_baseline = false;
    for (const auto& line : fixed.lines) on_a_baseline |= std::abs(g.position.y - line.baseline) < 1e-9;
    EXPECT_TRUE(on_a_baseline);
  }
}

TEST(Layout, AlignmentPlacesLinesInTheBox) {
  const auto fonts = FontList::default_list();
  TextStyle style;
  LayoutOptions lo;
  lo.max_width = 180;
  for (Align align : {Align::Left, Align::Center, Align::Right}) {
    lo.align = align;
    const TextLayout layout = layout_text(kParagraph, fonts, style, lo, {10, 20});
    for (const TextLine& line : layout.lines) {
      const double expected = align == Align::Left     ? 10.0
                              : align == Align::Center ? 10.0 + (180 - line.width) / 2
                                                       : 10.0 + 180 - line.width;
      EXPECT_NEAR(line.x, expected, 1e-9);
      if (line.glyph_end > line.glyph_begin) {
        EXPECT_NEAR(layout.glyphs[line.glyph_begin].position.x, line.x, 1e-9);
      }
    }
    EXPECT_NEAR(layout.logical.x0, 10, 1e-9);
    EXPECT_NEAR(layout.logical.x1, 190, 1e-9);
  }
}

TEST(Layout, HardBreaksStartNewLines) {
  const auto fonts = FontList::default_list();
  const auto layout = layout_text("one\ntwo\r\nthree\n", fonts, TextStyle{});
  ASSERT_EQ(layout.lines.size(), 4u);
  EXPECT_EQ(layout.lines[0].glyph_end - layout.lines[0].glyph_begin, 3u);
  EXPECT_EQ(layout.lines[1].glyph_end - layout.lines[1].glyph_begin, 3u);
  EXPECT_EQ(layout.lines[2].glyph_end - layout.lines[2].glyph_begin, 5u);
  EXPECT_EQ(layout.lines[3].glyph_end, layout.lines[3].glyph_begin);
}

TEST(Layout, AWordLongerThanTheWidthGetsALineOfItsOwn) {
  const auto fonts = FontList::default_list();
  LayoutOptions lo;
  lo.max_width = 30;
  const auto layout = layout_text("a incomprehensibilities b", fonts, TextStyle{}, lo);
  ASSERT_EQ(layout.lines.size(), 3u);
  EXPECT_GT(layout.lines[1].width, 30);
}

TEST(Layout, MeasuringNeedsNoDrawingAndMatchesLayout) {
  const auto fonts = FontList::default_list();
  TextStyle style;
  style.size = 24;
  const TextMetrics m = measure_text("Hxg", fonts, style);
  const FontMetrics fm = fonts.fonts[0]->metrics(24);
  EXPECT_NEAR(m.height, fm.line_height(), 1e-9);
  // Ink: 'H' sits on the baseline, 'g' descends below it, cap height above.
  EXPECT_LT(m.ink.y0, -0.6 * 24);
  EXPECT_GT(m.ink.y1, 0.1 * 24);
  EXPECT_GT(m.ink.x0, 0);  // H has a left side bearing
  EXPECT_LT(m.ink.x1, m.advance + 1);
  EXPECT_NEAR(m.logical.y0, fm.ascender, 1e-9);
  EXPECT_NEAR(m.logical.y1, fm.descender, 1e-9);
}

TEST(Layout, EmptyTextAndSpacesHaveNoInk) {
  const auto fonts = FontList::default_list();
  const auto empty = layout_text("", fonts, TextStyle{}, {}, {3, 4});
  EXPECT_EQ(empty.glyphs.size(), 0u);
  EXPECT_EQ(empty.lines.size(), 1u);
  EXPECT_EQ(empty.ink.x0, 3);
  EXPECT_EQ(empty.ink.y0, 4);
  const auto spaces = measure_text("   ", fonts, TextStyle{});
  EXPECT_EQ(spaces.advance, 0);  // trailing spaces do not count
}

TEST(Layout, BadOptionsAreErrors) {
  const auto fonts = FontList::default_list();
  LayoutOptions lo;
  lo.max_width = -1;
  EXPECT_THROW(layout_text("x", fonts, TextStyle{}, lo), Error);
  lo.max_width = std::nan("");
  EXPECT_THROW(layout_text("x", fonts, TextStyle{}, lo), Error);
  EXPECT_THROW(layout_text("x", FontList{}, TextStyle{}), Error);
  TextStyle style;
  style.features = "+";
  EXPECT_THROW(layout_text("x", fonts, style), Error);
}

TEST(Layout, TenThousandCharactersLayOutQuickly) {
  std::string text;
  while (text.size() < 10000) text += kParagraph + " ";
  LayoutOptions lo;
  lo.max_width = 600;
  const auto layout = layout_text(text, FontList::default_list(), TextStyle{}, lo);
  EXPECT_GT(layout.lines.size(), 100u);
  for (const auto& line : layout.lines) EXPECT_LE(line.width, 600 + 1e-9);
}

TEST(Layout, TabsAndControlCharactersDrawNoBoxes) {
  const auto fonts = FontList::default_list();
  const auto layout = layout_text("a\tb\x01" "c", fonts, TextStyle{});
  for (const auto& g : layout.glyphs) EXPECT_NE(g.glyph, 0u) << "cluster " << g.cluster;  // no .notdef
  const auto tab = measure_text("a\tb", fonts, TextStyle{}), space = measure_text("a b", fonts, TextStyle{});
  EXPECT_NEAR(tab.advance, space.advance, 1e-9);
  const auto ctl = measure_text("a\x01" "b", fonts, TextStyle{}), none = measure_text("ab", fonts, TextStyle{});
  EXPECT_NEAR(ctl.advance, none.advance, 1e-9);
}

TEST(Layout, WrappedRightToLeftParagraphReadsFromTheRight) {
  FontList fonts(Font::load_file(system_font(kAmiri)));
  // Six Arabic words; each line must hold its logically first word at the right end.
  const std::string word = "\xd9\x83\xd9\x84\xd9\x85\xd8\xa9";  // كلمة
  std::string text;
  for (int i = 0; i < 6; ++i) text += (i ? " " : "") + word;
  TextStyle style;
  style.size = 20;
  LayoutOptions lo;
  lo.max_width = 120;
  lo.align = Align::Right;
  const TextLayout layout = layout_text(text, fonts, style, lo);
  ASSERT_GE(layout.lines.size(), 2u);
  for (const TextLine& line : layout.lines) {
    ASSERT_GT(line.glyph_end, line.glyph_begin);
    // The rightmost glyph belongs to the line's first character; the leftmost to its last word.
    const auto& rightmost = layout.glyphs[line.glyph_end - 1];
    const auto& leftmost = layout.glyphs[line.glyph_begin];
    EXPECT_EQ(rightmost.cluster, line.text_begin);
    EXPECT_GT(leftmost.cluster, line.text_begin);
    EXPECT_NEAR(line.x + line.width, 120, 1e-9);
  }
}
