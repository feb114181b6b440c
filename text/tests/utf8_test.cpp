// UTF-8 decoding: valid text round-trips; invalid sequences become U+FFFD per maximal subpart.
#include <gtest/gtest.h>

#include "vraster_text/text.hpp"

using namespace vraster::text;

TEST(Utf8, DecodesValidSequencesOfEveryLength) {
  EXPECT_EQ(decode_utf8("a\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80"), U"a\u00e9\u20ac\U0001F600");
  EXPECT_EQ(decode_utf8(""), U"");
  EXPECT_EQ(decode_utf8(std::string_view("a\0b", 3)), std::u32string(U"a\0b", 3));
}

TEST(Utf8, InvalidSequencesBecomeReplacementCharacters) {
  // The example of the Unicode Standard 15.0, section 3.9, table 3-8 ("U+FFFD for each maximal subpart").
  EXPECT_EQ(decode_utf8("\x61\xF1\x80\x80\xE1\x80\xC2\x62\x80\x63\x80\xBF\x64"),
            U"a\uFFFD\uFFFD\uFFFDb\uFFFDc\uFFFD\uFFFDd");
  EXPECT_EQ(decode_utf8("\xC0\xAF"), U"\uFFFD\uFFFD");          // overlong
  EXPECT_EQ(decode_utf8("\xED\xA0\x80"), U"\uFFFD\uFFFD\uFFFD");  // surrogate
  EXPECT_EQ(decode_utf8("\xF4\x90\x80\x80"), U"\uFFFD\uFFFD\uFFFD\uFFFD");  // above U+10FFFF
  EXPECT_EQ(decode_utf8("\xE2\x82"), U"\uFFFD");                // truncated at the end
  EXPECT_EQ(decode_utf8("\xFF"), U"\uFFFD");
}

TEST(Utf8, InvalidTextLaysOutAndDrawsWithReplacementGlyphs) {
  const auto fonts = FontList::default_list();
  const auto layout = layout_text("ok\xff\xfe!", fonts, TextStyle{});
  ASSERT_EQ(layout.glyphs.size(), 5u);
  EXPECT_EQ(layout.glyphs[2].glyph, fonts.fonts[0]->glyph_index(U'\uFFFD'));
}
