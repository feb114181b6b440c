// Shaping: positions against HarfBuzz's own hb-shape, and properties of kerning, ligatures, joining, reordering,
// bidi and fallback that hold independently of any tool.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <regex>

#include "text_support.hpp"
#include "vraster/error.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;
using namespace vraster::text::testing;

namespace {

struct HbGlyph {
  long g, cl, ax, ay, dx, dy;
};

// Glyphs from `hb-shape --output-format=json --no-glyph-names` (font units: hb-shape's default size is the upem;
// clusters are code point indices).
std::vector<HbGlyph> hb_shape(const std::string& font, const std::string& text, const std::string& extra) {
  int status = 0;
  const std::string out = run_command("LANG=C.UTF-8 hb-shape --output-format=json --no-glyph-names " + extra + " '" + font +
                                          "' '" + text + "'",
                                      status);
  EXPECT_EQ(status, 0) << out;
  std::vector<HbGlyph> glyphs;
  const std::regex item("\\{([^}]*)\\}");
  const std::regex field("\"(\\w+)\":(-?\\d+)");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), item); it != std::sregex_iterator(); ++it) {
    HbGlyph g{};
    const std::string body = (*it)[1];
    for (auto f = std::sregex_iterator(body.begin(), body.end(), field); f != std::sregex_iterator(); ++f) {
      const std::string k = (*f)[1];
      const long v = std::stol((*f)[2]);
      if (k == "g") g.g = v;
      else if (k == "cl") g.cl = v;
      else if (k == "ax") g.ax = v;
      else if (k == "ay") g.ay = v;
      else if (k == "dx") g.dx = v;
      else if (k == "dy") g.dy = v;
    }
    glyphs.push_back(g);
  }
  return glyphs;
}

void expect_same_as_hb_shape(const std::string& font_path, const std::string& text, const std::string& lang,
                             const std::string& features = "") {
  require_program("hb-shape", "libharfbuzz-bin");
  const auto font = Font::load_file(font_path);
  TextStyle style;
  style.size = font->units_per_em();  // positions come out in font units, as hb-shape prints them
  style.language = lang;
  style.features = features;
  const auto ours = shape_text(decode_utf8(text), FontList(font), style);
  const auto ref = hb_shape(font_path, text, "--language=" + lang + (features.empty() ? "" : " --features=" + features));
  ASSERT_EQ(ours.size(), ref.size()) << text;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    SCOPED_TRACE("glyph " + std::to_string(i));
    EXPECT_EQ(static_cast<long>(ours[i].glyph), ref[i].g);
    EXPECT_EQ(static_cast<long>(ours[i].cluster), ref[i].cl);  // code point index
    EXPECT_EQ(ours[i].x_advance, static_cast<double>(ref[i].ax));
    EXPECT_EQ(ours[i].y_advance, static_cast<double>(ref[i].ay));
    EXPECT_EQ(ours[i].x_offset, static_cast<double>(ref[i].dx));
    EXPECT_EQ(ours[i].y_offset, static_cast<double>(ref[i].dy));
  }
}

const std::string kArabic = "\xd9\x85\xd8\xb1\xd8\xad\xd8\xa8\xd8\xa7 \xd8\xa8\xd8\xa7\xd9\x84\xd8\xb9\xd8\xa7\xd9\x84\xd9\x85";  // مرحبا بالعالم
const std::string kDevanagari =
    "\xe0\xa4\xa8\xe0\xa4\xae\xe0\xa4\xb8\xe0\xa5\x8d\xe0\xa4\xa4\xe0\xa5\x87 \xe0\xa4\x95\xe0\xa4\xbf\xe0\xa4\xb0\xe0\xa5\x8d\xe0\xa4\xa4\xe0\xa4\xbf";  // नमस्ते किर्ति

}  // namespace

TEST(ShapeVsHbShape, LatinWithKerning) {
  expect_same_as_hb_shape(repo_font("NotoSans-Regular.ttf"), "AVAWA Tofu office, fluffy affinity", "en");
}

TEST(ShapeVsHbShape, LatinWithLigaturesAndKerning) {
  // Noto Sans has no default f-ligatures; Noto Serif has fi, ffi, ff.
  expect_same_as_hb_shape(system_font(kNotoSerif), "AVAWA Tofu office, fluffy affinity", "en");
}

TEST(ShapeVsHbShape, LatinWithFeaturesOff) {
  expect_same_as_hb_shape(repo_font("NotoSans-Regular.ttf"), "AVAWA office fluffy", "en", "liga=0,kern=0");
}

TEST(ShapeVsHbShape, ArabicJoining) { expect_same_as_hb_shape(system_font(kAmiri), kArabic, "ar"); }

TEST(ShapeVsHbShape, DevanagariReordering) {
  expect_same_as_hb_shape(system_font(kNotoSansDevanagari), kDevanagari, "hi");
}

TEST(Shape, KerningPullsAVTogetherAndCanBeTurnedOff) {
  const auto font = Font::load_default();
  TextStyle style;
  style.size = 100;
  const auto kerned = shape_text(U"AV", FontList(font), style);
  style.features = "kern=0";
  const auto plain = shape_text(U"AV", FontList(font), style);
  ASSERT_EQ(kerned.size(), 2u);
  ASSERT_EQ(plain.size(), 2u);
  const double nominal = font->advance(font->glyph_index(U'A'), 100);
  EXPECT_EQ(plain[0].x_advance, nominal);
  EXPECT_LT(kerned[0].x_advance, nominal - 1.0);  // a visible kern: more than 1% of the em
}

TEST(Shape, LigaturesFormAndCanBeTurnedOff) {
  const auto font = Font::load_file(system_font(kNotoSerif));
  TextStyle style;
  const auto lig = shape_text(U"fi", FontList(font), style);
  EXPECT_EQ(lig.size(), 1u);
  EXPECT_NE(lig[0].glyph, font->glyph_index(U'f'));
  style.features = "liga=0";
  const auto sep = shape_text(U"fi", FontList(font), style);
  ASSERT_EQ(sep.size(), 2u);
  EXPECT_EQ(sep[0].glyph, font->glyph_index(U'f'));
  EXPECT_EQ(sep[1].glyph, font->glyph_index(U'i'));
}

TEST(Shape, InvalidFeatureListIsAnError) {
  EXPECT_THROW(parse_features("liga=0,=="), Error);
  EXPECT_EQ(parse_features("liga=0, kern").size(), 2u);
  EXPECT_EQ(parse_features("").size(), 0u);
}

TEST(Shape, ArabicLettersTakeJoiningFormsInVisualOrder) {
  const auto font = Font::load_file(system_font(kAmiri));
  const auto glyphs = shape_text(U"\u0628\u0628\u0628", FontList(font), TextStyle{});  // three beh
  ASSERT_EQ(glyphs.size(), 3u);
  const auto isolated = font->glyph_index(U'\u0628');
  // Initial, medial and final forms, none of them the isolated glyph; the leftmost glyph is the last letter.
  for (const auto& g : glyphs) EXPECT_NE(g.glyph, isolated);
  EXPECT_NE(glyphs[0].glyph, glyphs[2].glyph);
  EXPECT_EQ(glyphs[0].cluster, 2u);
  EXPECT_EQ(glyphs[2].cluster, 0u);
}

TEST(Shape, DevanagariVowelSignIMovesBeforeItsConsonant) {
  const auto font = Font::load_file(system_font(kNotoSansDevanagari));
  const auto glyphs = shape_text(U"\u0915\u093F", FontList(font), TextStyle{});  // KA + vowel sign I
  ASSERT_EQ(glyphs.size(), 2u);
  EXPECT_EQ(glyphs[1].glyph, font->glyph_index(U'\u0915'));  // the consonant is drawn second (right)
  EXPECT_NE(glyphs[0].glyph, font->glyph_index(U'\u0915'));
}

TEST(Shape, MixedDirectionLineIsReorderedByRuns) {
  FontList fonts = FontList::default_list();
  fonts.add(Font::load_file(system_font(kAmiri)));
  const std::u32string text = U"abc \u0645\u0631\u062D\u0628\u0627 def";  // abc مرحبا def
  const auto glyphs = shape_text(text, fonts, TextStyle{});
  std::vector<std::uint32_t> clusters;
  for (const auto& g : glyphs) clusters.push_back(g.cluster);
  // Left to right: a b c space, then the Arabic word from its last letter to its first, then space d e f.
  ASSERT_GE(clusters.size(), 8u);
  EXPECT_EQ(clusters[0], 0u);
  EXPECT_EQ(clusters[1], 1u);
  EXPECT_EQ(clusters[2], 2u);
  EXPECT_EQ(clusters.back(), 12u);
  std::vector<std::uint32_t> arabic;
  for (const auto& g : glyphs) {
    if (g.font == 1 && g.cluster >= 4 && g.cluster <= 8) arabic.push_back(g.cluster);
  }
  ASSERT_FALSE(arabic.empty());
  EXPECT_TRUE(std::is_sorted(arabic.rbegin(), arabic.rend())) << "Arabic run is not right to left";
  EXPECT_EQ(arabic.front(), 8u);
  EXPECT_EQ(arabic.back(), 4u);
}

TEST(Shape, RightToLeftParagraphPutsLatinRunOnTheLeftOfArabic) {
  FontList fonts = FontList::default_list();
  fonts.add(Font::load_file(system_font(kAmiri)));
  const std::string text = "\xd9\x85\xd8\xb1\xd8\xad\xd8\xa8\xd8\xa7 abc";  // مرحبا abc: Arabic first, logically
  TextStyle style;
  style.direction = Direction::Auto;  // first strong character is Arabic: RTL paragraph
  const TextLayout layout = layout_text(text, fonts, style);
  double x_a = 0, x_arabic_first = 0;
  for (const auto& g : layout.glyphs) {
    if (g.cluster == 6) x_a = g.position.x;
    if (g.cluster == 0) x_arabic_first = g.position.x;
  }
  EXPECT_LT(x_a, x_arabic_first);  // "abc" sits to the left, the first Arabic letter at the far right
  style.direction = Direction::LeftToRight;
  const TextLayout ltr = layout_text(text, fonts, style);
  for (const auto& g : ltr.glyphs) {
    if (g.cluster == 6) x_a = g.position.x;
    if (g.cluster == 0) x_arabic_first = g.position.x;
  }
  EXPECT_GT(x_a, x_arabic_first);
}

TEST(Shape, FallbackFontsCoverWhatTheFirstLacks) {
  FontList fonts = FontList::default_list();
  fonts.add(Font::load_file(system_font(kAmiri)));
  fonts.add(Font::load_file(system_font(kNotoSansDevanagari)));
  ASSERT_FALSE(fonts.fonts[0]->has_glyph(U'\u0628'));
  const auto glyphs = shape_text(U"A\u0628 \u0915", fonts, TextStyle{});
  ASSERT_EQ(glyphs.size(), 4u);
  EXPECT_EQ(glyphs[0].font, 0);
  EXPECT_EQ(glyphs[1].font, 1);
  EXPECT_EQ(glyphs[3].font, 2);
  for (const auto& g : glyphs) EXPECT_NE(g.glyph, 0u);
}

TEST(Shape, CharactersNoFontHasBecomeNotdef) {
  FontList fonts = FontList::default_list();
  fonts.add(Font::load_file(system_font(kAmiri)));
  const auto glyphs = shape_text(U"A\U0010FFFDB", fonts, TextStyle{});
  ASSERT_EQ(glyphs.size(), 3u);
  EXPECT_EQ(glyphs[1].glyph, 0u);
  EXPECT_EQ(glyphs[1].font, 0);
  EXPECT_GT(glyphs[1].x_advance, 0);  // .notdef is a visible box with an advance
  EXPECT_FALSE(fonts.fonts[0]->outline_units(0).empty());
}

TEST(Shape, ForcedScriptAndUnknownScript) {
  TextStyle style;
  style.script = "Lat!";
  EXPECT_THROW(shape_text(U"abc", FontList::default_list(), style), Error);
  style.script = "Latn";
  EXPECT_EQ(shape_text(U"abc", FontList::default_list(), style).size(), 3u);
}

TEST(Shape, LanguageSelectsLocalizedForms) {
  // Noto Sans has a Serbian form of Cyrillic be (б) behind the 'locl' feature: the language must reach HarfBuzz.
  const auto font = Font::load_default();
  TextStyle style;
  style.language = "ru";
  const auto ru = shape_text(U"\u0431", FontList(font), style);
  style.language = "sr";
  const auto sr = shape_text(U"\u0431", FontList(font), style);
  ASSERT_EQ(ru.size(), 1u);
  ASSERT_EQ(sr.size(), 1u);
  EXPECT_EQ(ru[0].glyph, font->glyph_index(U'\u0431'));
  EXPECT_NE(sr[0].glyph, ru[0].glyph);
}
