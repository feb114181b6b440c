// Fonts: loading (file, memory, CFF, collections), errors, sizes, outlines against FreeType's own numbers.
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "text_support.hpp"
#include "vraster/error.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;
using vraster::text::testing::ink_of;
using vraster::text::testing::ink_stats;
using vraster::text::testing::InkStats;
using vraster::text::testing::out_dir;
using vraster::text::testing::repo_font;
using vraster::text::testing::system_font;
using vraster::text::testing::kCantarellCff;
using vraster::text::testing::kNotoSerif;
using vraster::text::testing::kWqyMicroHeiCollection;

namespace {

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::uint32_t be32(const std::uint8_t* p) { return std::uint32_t{p[0]} << 24 | p[1] << 16 | p[2] << 8 | p[3]; }
void put32(std::uint8_t* p, std::uint32_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 24), p[1] = static_cast<std::uint8_t>(v >> 16);
  p[2] = static_cast<std::uint8_t>(v >> 8), p[3] = static_cast<std::uint8_t>(v);
}

// A TrueType collection of two fonts built by hand (OpenType spec, "TTC header"): the header, then each font
// with its table offsets moved by where the font now starts.
std::vector<std::uint8_t> make_collection(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  std::vector<std::uint8_t> out(12 + 8, 0);
  std::memcpy(out.data(), "ttcf", 4);
  put32(out.data() + 4, 0x00010000);
  put32(out.data() + 8, 2);
  for (int k = 0; k < 2; ++k) {
    const auto& font = k == 0 ? a : b;
    while (out.size() % 4) out.push_back(0);
    const auto base = static_cast<std::uint32_t>(out.size());
    put32(out.data() + 12 + 4 * k, base);
    out.insert(out.end(), font.begin(), font.end());
    const unsigned tables = static_cast<unsigned>(out[base + 4] << 8 | out[base + 5]);
    for (unsigned t = 0; t < tables; ++t) {
      std::uint8_t* rec = out.data() + base + 12 + 16 * t;
      put32(rec + 8, be32(rec + 8) + base);
    }
  }
  return out;
}

}  // namespace

TEST(Font, DefaultFontIsEmbeddedNotoSansRegular) {
  const auto font = Font::load_default();
  EXPECT_EQ(font->family_name(), "Noto Sans");
  EXPECT_EQ(font->style_name(), "Regular");
  // The embedded bytes are the shipped file, byte for byte.
  const auto file = read_bytes(repo_font("NotoSans-Regular.ttf"));
  const auto data = Font::default_font_data();
  ASSERT_EQ(data.size(), file.size());
  EXPECT_EQ(std::memcmp(data.data(), file.data(), file.size()), 0);
  EXPECT_NE(font->glyph_index(U'A'), 0u);
}

TEST(Font, FileAndMemoryLoadTheSameFace) {
  const auto path = system_font(kNotoSerif);
  const auto a = Font::load_file(path);
  const auto b = Font::load_memory(read_bytes(path), 0, "serif");
  EXPECT_EQ(a->family_name(), "Noto Serif");
  EXPECT_EQ(a->glyph_count(), b->glyph_count());
  EXPECT_EQ(a->glyph_index(U'g'), b->glyph_index(U'g'));
  EXPECT_NE(a->id(), b->id());
}

TEST(Font, OpenTypeCffOutlinesLoad) {
  const auto font = Font::load_file(system_font(kCantarellCff));
  bool any = false;
  for (int g = 1; g < font->glyph_count() && !any; ++g) any = !font->outline_units(static_cast<std::uint32_t>(g)).empty();
  EXPECT_TRUE(any) << "no CFF glyph with an outline";
}

TEST(Font, CollectionFacesAreSelectedByIndex) {
  const auto coll = make_collection(read_bytes(repo_font("NotoSans-Regular.ttf")),
                                    read_bytes(system_font(kNotoSerif)));
  const std::string path = out_dir() + "/two.ttc";
  write_bytes(path, coll);
  const auto sans = Font::load_file(path, 0);
  const auto serif = Font::load_file(path, 1);
  EXPECT_EQ(sans->face_count(), 2);
  EXPECT_EQ(sans->family_name(), "Noto Sans");
  EXPECT_EQ(serif->family_name(), "Noto Serif");
  // Shaping reads the same face HarfBuzz-side: serif and sans 'a' differ in advance.
  EXPECT_NE(sans->advance(sans->glyph_index(U'a'), 1000), serif->advance(serif->glyph_index(U'a'), 1000));
  try {
    Font::load_file(path, 2);
    FAIL() << "face 2 does not exist";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(Font, InstalledCollectionFacesAreSelectedByIndex) {
  // A real .ttc from Debian (WenQuanYi Micro Hei: a proportional and a monospaced face).
  const auto path = system_font(kWqyMicroHeiCollection);
  const auto first = Font::load_file(path, 0);
  const auto second = Font::load_file(path, 1);
  EXPECT_EQ(first->face_count(), 2);
  EXPECT_EQ(second->face_count(), 2);
  EXPECT_EQ(first->family_name(), "WenQuanYi Micro Hei");
  EXPECT_EQ(second->family_name(), "WenQuanYi Micro Hei Mono");
  EXPECT_NE(first->glyph_index(U'\u4E2D'), 0u);  // 中
  EXPECT_THROW(Font::load_file(path, 2), Error);
}

TEST(Font, MissingFileErrorNamesTheFile) {
  const std::string path = out_dir() + "/no-such-font.ttf";
  try {
    Font::load_file(path);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(Font, CorruptFileErrorNamesTheFile) {
  const std::string path = out_dir() + "/corrupt.ttf";
  std::vector<std::uint8_t> junk(4000);
  for (std::size_t i = 0; i < junk.size(); ++i) junk[i] = static_cast<std::uint8_t>(i * 131 + 7);
  write_bytes(path, junk);
  try {
    Font::load_file(path);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  write_bytes(path, {});
  EXPECT_THROW(Font::load_file(path), Error);
}

TEST(Font, TruncatedFontIsRejectedOrDrawsWithoutCrashing) {
  // A real font cut short at several lengths: the table directory points past the end. Each either fails to load
  // with a vraster::Error naming the font, or loads and then lays out and draws "Hello" (five glyphs, whatever
  // their outlines), never anything else. The uncut font is the control: it loads and draws ink.
  const auto original = read_bytes(repo_font("NotoSans-Regular.ttf"));
  ASSERT_GT(original.size(), 10000u);
  int rejected = 0;
  for (const std::size_t length : {std::size_t{4}, std::size_t{12}, std::size_t{100}, original.size() / 5,
                                   original.size() / 2, original.size() - 1, original.size()}) {
    SCOPED_TRACE("length " + std::to_string(length));
    std::vector<std::uint8_t> bytes(original.begin(), original.begin() + static_cast<std::ptrdiff_t>(length));
    std::shared_ptr<Font> font;
    try {
      font = Font::load_memory(bytes, 0, "truncated.ttf");
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("truncated.ttf"), std::string::npos) << e.what();
      ++rejected;
      continue;
    }
    Image image(96, 40);
    TextStyle style;
    style.size = 20;
    try {
      const auto layout = layout_text("Hello", FontList(font), style, LayoutOptions{}, {4, 28});
      EXPECT_EQ(layout.glyphs.size(), 5u);
      TextRenderer().draw(image, layout, Color{});
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("truncated.ttf"), std::string::npos) << e.what();
      continue;
    }
    if (length == original.size()) {
      const InkStats s = ink_stats(ink_of(image, false), image.width, image.height);
      EXPECT_GT(s.total, 50) << "the whole font draws no ink";
    }
  }
  EXPECT_GE(rejected, 3) << "a font cut to 4, 12 or 100 bytes has no complete table directory";
}

TEST(Font, BadSizesAreRejectedWithAMessage) {
  const auto font = Font::load_default();
  for (double s : {0.0, -3.0, 1e6, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(font->outline(font->glyph_index(U'A'), s), Error) << s;
    TextStyle style;
    style.size = s;
    EXPECT_THROW(layout_text("A", FontList(font), style), Error) << s;
  }
  EXPECT_NO_THROW(font->outline(font->glyph_index(U'A'), kMaxFontSize));
}

TEST(Font, UnhintedOutlineBoxEqualsFreeTypeBox) {
  // Independent numbers: FreeType's own control box of the unscaled outline, for a few glyphs.
  FT_Library lib;
  ASSERT_EQ(FT_Init_FreeType(&lib), 0);
  FT_Face face;
  const auto path = repo_font("NotoSans-Regular.ttf");
  ASSERT_EQ(FT_New_Face(lib, path.c_str(), 0, &face), 0);
  const auto font = Font::load_file(path);
  for (char32_t c : std::u32string(U"AgO&@%Q")) {
    const auto g = font->glyph_index(c);
    ASSERT_EQ(FT_Load_Glyph(face, g, FT_LOAD_NO_SCALE), 0);
    FT_BBox box;
    FT_Outline_Get_CBox(&face->glyph->outline, &box);
    const Rect r = font->outline_units(g).control_bounds();
    EXPECT_EQ(r.x0, box.xMin);
    EXPECT_EQ(r.x1, box.xMax);
    EXPECT_EQ(r.y0, -box.yMax);  // y flipped
    EXPECT_EQ(r.y1, -box.yMin);
    // The box cached with the outline (renderers size masks from it) is the same box.
    const Rect cached = font->glyph_outline(g).control_box;
    EXPECT_EQ(cached.x0, r.x0);
    EXPECT_EQ(cached.y0, r.y0);
    EXPECT_EQ(cached.x1, r.x1);
    EXPECT_EQ(cached.y1, r.y1);
    EXPECT_EQ(&font->glyph_outline(g).path, &font->outline_units(g));
  }
  // A glyph without an outline (space): empty path, empty box.
  const GlyphOutline& space = font->glyph_outline(font->glyph_index(U' '));
  EXPECT_TRUE(space.path.empty());
  EXPECT_TRUE(space.control_box.empty());
  FT_Done_Face(face);
  FT_Done_FreeType(lib);
}

TEST(Font, LightHintingSnapsTheCapHeightToThePixelGrid) {
  const auto font = Font::load_default();
  const auto g = font->glyph_index(U'H');
  for (double size : {11.0, 13.0, 17.0}) {
    const Rect hinted = font->outline(g, size, Hinting::Light).control_bounds();
    const Rect exact = font->outline(g, size, Hinting::None).control_bounds();
    EXPECT_NEAR(hinted.y0, std::round(hinted.y0), 1e-9) << size;  // top of H on a pixel boundary
    EXPECT_NEAR(hinted.y0, exact.y0, 0.75) << size;
    EXPECT_NEAR(hinted.x1 - hinted.x0, exact.x1 - exact.x0, 0.05) << size;  // light hinting leaves x alone
  }
}

TEST(Font, MetricsScaleWithSize) {
  const auto font = Font::load_default();
  const FontMetrics m10 = font->metrics(10), m20 = font->metrics(20);
  EXPECT_LT(m10.ascender, 0);
  EXPECT_GT(m10.descender, 0);
  EXPECT_NEAR(m20.line_height(), 2 * m10.line_height(), 1e-9);
  // Noto Sans: hhea ascender 1069, descender -293, line gap 0, 1000 units per em.
  EXPECT_NEAR(m10.ascender, -10.69, 1e-9);
  EXPECT_NEAR(m10.descender, 2.93, 1e-9);
}

TEST(Font, MutatedFontsNeverCrash) {
  // Seeded random byte changes in a real font (a small fuzz run): loading may fail with an Error; whatever loads
  // must shape, lay out and draw without crashing, and with bounded memory.
  const auto original = read_bytes(repo_font("NotoSans-Regular.ttf"));
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<std::uint32_t>(state >> 33);
  };
  int loaded = 0;
  for (int round = 0; round < 60; ++round) {
    auto bytes = original;
    const int changes = 1 + static_cast<int>(next() % 40);
    for (int k = 0; k < changes; ++k) {
      // Half the changes hit the first 4 KiB (table directory, head, hhea, maxp...), half anywhere.
      const std::size_t at = (k & 1) ? next() % 4096 : next() % bytes.size();
      bytes[at] = static_cast<std::uint8_t>(next());
    }
    try {
      const auto font = Font::load_memory(bytes, 0, "mutated");
      ++loaded;
      TextStyle style;
      style.size = 24;
      LayoutOptions lo;
      lo.max_width = 100;
      const auto layout = layout_text("Hamburg AVAWA office 0123", FontList(font), style, lo, {4, 30});
      Image image(128, 128);
      TextRenderer renderer;
      renderer.draw(image, layout, Color{});
      GlyphRenderOptions direct;
      direct.use_cache = false;
      renderer.draw(image, layout, Color{}, Affine::rotate(10), direct);
    } catch (const Error&) {
    }
  }
  EXPECT_GT(loaded, 0);
}

// ---- hostile fonts (issue 12) ----

namespace {

/// The bytes of `font` with table `tag` overwritten by seeded noise (the table directory stays intact).
std::vector<std::uint8_t> with_garbage_table(std::vector<std::uint8_t> font, const char* tag) {
  const auto u16 = [&](std::size_t at) { return std::size_t{font[at]} << 8 | font[at + 1]; };
  const auto u32 = [&](std::size_t at) { return u16(at) << 16 | u16(at + 2); };
  const std::size_t tables = u16(4);
  std::uint32_t state = 12345;
  for (std::size_t i = 0; i < tables; ++i) {
    const std::size_t record = 12 + 16 * i;
    if (std::memcmp(&font[record], tag, 4) != 0) continue;
    const std::size_t offset = u32(record + 8), length = u32(record + 12);
    for (std::size_t k = offset; k < offset + length && k < font.size(); ++k) {
      state = state * 1664525u + 1013904223u;
      font[k] = static_cast<std::uint8_t>(state >> 24);
    }
    return font;
  }
  ADD_FAILURE() << "no table " << tag;
  return font;
}

/// Loads `bytes` and lays out and draws "Hello"; returns the error message, or "" when everything worked.
std::string load_and_draw(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  try {
    const auto font = Font::load_memory(bytes, 0, name);
    Image image(96, 40);
    TextStyle style;
    style.size = 20;
    const auto layout = layout_text("Hello", FontList(font), style, LayoutOptions{}, {4, 28});
    TextRenderer().draw(image, layout, Color{});
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

}  // namespace

TEST(HostileFont, GarbageLocaTableIsAnError) {
  // FreeType gives glyphs it cannot place an empty outline: this drew blank text with exit status 0.
  const std::string message = load_and_draw(with_garbage_table(read_bytes(repo_font("NotoSans-Regular.ttf")), "loca"),
                                            "garbage-loca.ttf");
  EXPECT_NE(message.find("garbage-loca.ttf"), std::string::npos) << message;
  EXPECT_NE(message.find("loca table is corrupt"), std::string::npos) << message;
}

TEST(HostileFont, GarbageGlyfTableIsAnErrorNamingTheGlyph) {
  const std::string message = load_and_draw(with_garbage_table(read_bytes(repo_font("NotoSans-Regular.ttf")), "glyf"),
                                            "garbage-glyf.ttf");
  EXPECT_NE(message.find("garbage-glyf.ttf"), std::string::npos) << message;
  EXPECT_NE(message.find("glyph "), std::string::npos) << message;
  EXPECT_EQ(message.find("FreeType error"), std::string::npos) << "a bare error number: " << message;
}
