// SVG text in the resolved tree (svg_subset/src/text.cpp): glyph outlines as PathNodes, checked against the
// fonts' own outlines and metrics, without pixels.
#include <ft2build.h>
#include FT_FREETYPE_H
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include "svg_subset/tree.hpp"
#include "text_support.hpp"
#include "vraster/error.hpp"
#include "vraster_text/font_db.hpp"
#include "vraster_text/layout.hpp"

namespace vraster::text {
namespace {

using svg::Group;
using svg::Node;
using svg::PathNode;
using testing::kAmiri;
using testing::kNotoSerif;
using testing::system_font;

constexpr testing::SystemFont kNotoSans{"/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf", "fonts-noto-core"};
constexpr testing::SystemFont kNotoSansBold{"/usr/share/fonts/truetype/noto/NotoSans-Bold.ttf", "fonts-noto-core"};

/// A database of Debian-packaged fonts: Noto Sans (regular, bold), Noto Serif, Amiri.
std::shared_ptr<FontDb> test_fonts() {
  auto db = std::make_shared<FontDb>();
  db->add_file(system_font(kNotoSans));
  db->add_file(system_font(kNotoSansBold));
  db->add_file(system_font(kNotoSerif));
  db->add_file(system_font(kAmiri));
  db->set_generic_family(GenericFamily::Serif, "Noto Serif");
  db->set_generic_family(GenericFamily::SansSerif, "Noto Sans");
  return db;
}

svg::Tree parse(const std::string& body, std::shared_ptr<FontDb> fonts = test_fonts()) {
  svg::ParseOptions options;
  options.fonts = std::move(fonts);
  return svg::parse_svg_tree("<svg xmlns='http://www.w3.org/2000/svg' width='400' height='200'>" + body + "</svg>",
                             "<test>", options);
}

/// The PathNodes of the first <text> (the first group child of the root).
std::vector<const PathNode*> text_paths(const svg::Tree& tree) {
  std::vector<const PathNode*> out;
  for (const Node& n : tree.root.children) {
    if (const auto* g = std::get_if<Group>(&n.value)) {
      for (const Node& c : g->children) {
        if (const auto* p = std::get_if<PathNode>(&c.value)) out.push_back(p);
      }
      return out;
    }
  }
  return out;
}

/// The box of one glyph's outline with its pen at (x, y), `size` px per em.
Rect glyph_box(const Font& font, char32_t c, double size, double x, double y) {
  const double s = size / font.units_per_em();
  return font.outline_units(font.glyph_index(c)).transformed(Affine::translate(x, y) * Affine::scale(s)).bounds();
}

TextStyle sized(double size) {
  TextStyle style;
  style.size = size;
  return style;
}

bool same_color(const Color& a, const Color& b) { return a.r == b.r && a.g == b.g && a.b == b.b && a.a == b.a; }

double advance(const Font& font, char32_t c, double size) { return font.advance(font.glyph_index(c), size); }

void expect_box(const Rect& actual, const Rect& expected, double eps = 1e-6) {
  EXPECT_NEAR(actual.x0, expected.x0, eps);
  EXPECT_NEAR(actual.y0, expected.y0, eps);
  EXPECT_NEAR(actual.x1, expected.x1, eps);
  EXPECT_NEAR(actual.y1, expected.y1, eps);
}

TEST(SvgText, GlyphPositionsFollowXAndDxLists) {
  // Empty tspans split the text into one PathNode per character; the lists belong to <text>.
  const svg::Tree tree = parse(
      "<text x='10 50' y='80' dx='0 0 5' dy='0 0 -3' font-family='Noto Sans' font-size='20'>"
      "A<tspan fill='red'>B</tspan><tspan fill='blue'>C</tspan></text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 3u);
  const auto font = Font::load_file(system_font(kNotoSans));
  expect_box(paths[0]->path.bounds(), glyph_box(*font, 'A', 20, 10, 80));
  expect_box(paths[1]->path.bounds(), glyph_box(*font, 'B', 20, 50, 80));  // x list: absolute, a new chunk
  // C: after B's advance, moved by its dx and dy.
  expect_box(paths[2]->path.bounds(), glyph_box(*font, 'C', 20, 50 + advance(*font, 'B', 20) + 5, 77));
  EXPECT_TRUE(same_color(paths[1]->fill->paint.color, Color::rgb8(255, 0, 0)));
  // objectBoundingBox paints refer to the whole text's box: from A's pen to the end of C's advance.
  ASSERT_TRUE(paths[0]->paint_box.has_value());
  EXPECT_NEAR(paths[0]->paint_box->x0, 10, 1e-9);
  EXPECT_NEAR(paths[0]->paint_box->x1, 50 + advance(*font, 'B', 20) + 5 + advance(*font, 'C', 20), 1e-9);
}

TEST(SvgText, RotateListTurnsEachGlyphAboutItsOrigin) {
  const svg::Tree tree = parse("<text x='100' y='100' rotate='90' font-family='Noto Sans' font-size='20'>L</text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  const auto font = Font::load_file(system_font(kNotoSans));
  const Rect upright = glyph_box(*font, 'L', 20, 0, 0);
  // rotate(90) maps (x, y) to (-y, x) around the pen position.
  expect_box(paths[0]->path.bounds(), Rect{100 - upright.y1, 100 + upright.x0, 100 - upright.y0, 100 + upright.x1});
}

TEST(SvgText, TextAnchorMiddleShiftsByHalfTheAdvance) {
  const auto font = Font::load_file(system_font(kNotoSans));
  const double width = measure_text("Wave", FontList(font), sized(30)).advance;
  const auto x0 = [&](const char* anchor) {
    const svg::Tree tree = parse(std::string("<text x='200' y='100' font-family='Noto Sans' font-size='30' text-anchor='") +
                                 anchor + "'>Wave</text>");
    const auto paths = text_paths(tree);
    EXPECT_EQ(paths.size(), 1u);
    return paths.empty() ? 0.0 : paths[0]->path.bounds().x0;
  };
  const double start = x0("start");
  EXPECT_NEAR(x0("middle"), start - width / 2, 1e-6);
  EXPECT_NEAR(x0("end"), start - width, 1e-6);
}

TEST(SvgText, FamilyListPicksTheFirstFamilyTheDatabaseHas) {
  const auto db = test_fonts();
  FontQuery q;
  q.families = {"No Such Family", "Noto Serif", "sans-serif"};
  ASSERT_NE(db->match(q), nullptr);
  EXPECT_EQ(db->match(q)->family_name(), "Noto Serif");
  q.families = {"No Such Family", "sans-serif"};
  EXPECT_EQ(db->match(q)->family_name(), "Noto Sans");
  q.weight = 700;
  EXPECT_EQ(db->match(q)->style_name(), "Bold");
  q.families = {"No Such Family"};  // nothing matches: the default family, generic serif
  q.weight = 400;
  EXPECT_EQ(db->match(q)->family_name(), "Noto Serif");

  // Through the tree: the outline drawn is Noto Serif's.
  const svg::Tree tree = parse("<text x='10' y='100' font-family=\"'No Such', 'Noto Serif', sans-serif\" "
                               "font-size='40'>g</text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  const auto serif = Font::load_file(system_font(kNotoSerif));
  expect_box(paths[0]->path.bounds(), glyph_box(*serif, 'g', 40, 10, 100));
}

TEST(SvgText, CharactersTheFontLacksFallBackToAFontThatHasThem) {
  const auto db = test_fonts();
  FontQuery q;
  q.families = {"Noto Serif"};
  const FontList list = db->fonts_for(q, U"A\u0628");  // Latin A, Arabic beh
  ASSERT_EQ(list.fonts.size(), 2u);
  EXPECT_EQ(list.fonts[0]->family_name(), "Noto Serif");
  EXPECT_EQ(list.fonts[1]->family_name(), "Amiri");
  // In a document the Arabic letter is drawn (not a .notdef box of Noto Serif's).
  const svg::Tree tree = parse("<text x='10' y='100' font-family='Noto Serif' font-size='40'>\u0628</text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  const auto amiri = Font::load_file(system_font(kAmiri));
  const Rect beh = glyph_box(*amiri, U'\u0628', 40, 0, 100);
  EXPECT_NEAR(paths[0]->path.bounds().height(), beh.height(), 1e-6);
}

TEST(SvgText, DecorationRectanglesComeFromTheFontMetrics) {
  const svg::Tree tree = parse(
      "<text x='10' y='100' font-family='Noto Sans' font-size='40' fill='green' "
      "text-decoration='underline line-through'>AB</text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 3u);  // underline, glyphs, line-through: SVG's painting order
  // The font's own numbers, read with FreeType here: post.underlinePosition is the line's centre (FreeType
  // reports it half a thickness lower), the thickness is post.underlineThickness.
  FT_Library library;
  ASSERT_EQ(FT_Init_FreeType(&library), 0);
  FT_Face face;
  ASSERT_EQ(FT_New_Face(library, system_font(kNotoSans).c_str(), 0, &face), 0);
  const double s = 40.0 / face->units_per_EM;
  const double thickness = face->underline_thickness * s;
  const double centre = 100 - (face->underline_position + face->underline_thickness / 2.0) * s;
  FT_Done_Face(face);
  FT_Done_FreeType(library);
  const auto font = Font::load_file(system_font(kNotoSans));
  const double width = measure_text("AB", FontList(font), sized(40)).advance;
  expect_box(paths[0]->path.bounds(), Rect{10, centre - thickness / 2, 10 + width, centre + thickness / 2});
  EXPECT_GT(paths[0]->path.bounds().y0, 100);  // below the baseline
  const Rect strike = paths[2]->path.bounds();
  EXPECT_LT(strike.y1, 100);  // above it
  EXPECT_NEAR(strike.x0, 10, 1e-9);
  EXPECT_NEAR(strike.x1, 10 + width, 1e-9);
  EXPECT_TRUE(same_color(paths[0]->fill->paint.color, Color::rgb8(0, 128, 0)));
}

TEST(SvgText, TextPathPlacesGlyphsAlongAStraightLine) {
  const auto font = Font::load_file(system_font(kNotoSans));
  const double a = advance(*font, 'H', 20);
  // A horizontal path: glyphs sit where they would on the line from its start (plus startOffset).
  svg::Tree tree = parse(
      "<path id='p' d='M 20 100 L 220 100' fill='none'/>"
      "<text font-family='Noto Sans' font-size='20'><textPath href='#p' startOffset='5'>H<tspan "
      "fill='red'>H</tspan></textPath></text>");
  auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 2u);
  expect_box(paths[0]->path.bounds(), glyph_box(*font, 'H', 20, 25, 100));
  expect_box(paths[1]->path.bounds(), glyph_box(*font, 'H', 20, 25 + a, 100));
  // A vertical path going down: glyphs turned by 90 degrees, advancing downwards.
  tree = parse(
      "<path id='p' d='M 100 20 L 100 220' fill='none'/>"
      "<text font-family='Noto Sans' font-size='20'><textPath href='#p'>H</textPath></text>");
  paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  const Rect upright = glyph_box(*font, 'H', 20, 0, 0);
  expect_box(paths[0]->path.bounds(), Rect{100 - upright.y1, 20 + upright.x0, 100 - upright.y0, 20 + upright.x1});
  // Glyphs whose advance midpoint lies past the end of the path are dropped: 2.4 advances hold two.
  tree = parse("<path id='p' d='M 0 100 L " + std::to_string(2.4 * a) +
               " 100' fill='none'/><text font-family='Noto Sans' font-size='20'><textPath href='#p'>HHHH</textPath></text>");
  paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_NEAR(paths[0]->path.bounds().x1, glyph_box(*font, 'H', 20, a, 100).x1, 1e-6);
}

TEST(SvgText, TextPathFollowsTheCurveItselfNotAPolyline) {
  // On a circle of radius 100 about (200, 100), a glyph's advance midpoint lies at arc length startOffset +
  // advance / 2 and the glyph turns with the circle's tangent there (a polyline's chords would turn it by up to
  // half a chord's bend, moving its top by a tenth of a unit).
  const auto font = Font::load_file(system_font(kNotoSans));
  const double a = advance(*font, 'H', 20), r = 100, offset = 40;
  const svg::Tree tree = parse(
      "<path id='p' d='M 300 100 A 100 100 0 0 1 100 100' fill='none'/>"
      "<text font-family='Noto Sans' font-size='20'><textPath href='#p' startOffset='40'>H</textPath></text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  const double theta = (offset + a / 2) / r;  // clockwise on screen from (300, 100)
  const double s = 20.0 / font->units_per_em();
  const Affine expected = Affine::translate(200 + r * std::cos(theta), 100 + r * std::sin(theta)) *
                          Affine::rotate(theta * 180 / std::numbers::pi + 90) * Affine::translate(-a / 2, 0) *
                          Affine::scale(s);
  expect_box(paths[0]->path.bounds(), font->outline_units(font->glyph_index('H')).transformed(expected).bounds(), 1e-4);
}

TEST(SvgText, TextPathChunksAndTextAfterThePath) {
  const auto font = Font::load_file(system_font(kNotoSans));
  const double a = advance(*font, 'H', 20);
  // An absolute x inside the textPath starts a chunk at that distance along the path (its y means nothing
  // there); text after the textPath goes on from the path's end point (SVG 2, 11.8.3), not from its last glyph.
  const svg::Tree tree = parse(
      "<path id='p' d='M 20 100 L 220 100' fill='none'/>"
      "<text font-family='Noto Sans' font-size='20'><textPath href='#p'>H<tspan x='50' y='30' fill='red'>H</tspan>"
      "</textPath><tspan fill='blue'>H</tspan></text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 3u);
  expect_box(paths[0]->path.bounds(), glyph_box(*font, 'H', 20, 20, 100));
  expect_box(paths[1]->path.bounds(), glyph_box(*font, 'H', 20, 70, 100));
  expect_box(paths[2]->path.bounds(), glyph_box(*font, 'H', 20, 220, 100));
  EXPECT_GT(220, 70 + a);  // the end point is not where the last glyph ended
}

TEST(SvgText, TextPathWrapsAroundOneClosedSubpathAndHonoursPathLength) {
  const auto font = Font::load_file(system_font(kNotoSans));
  const double a = advance(*font, 'H', 20);
  // A closed square of perimeter 400: from startOffset 395 the first glyph's midpoint (395 + a / 2) wraps to the
  // top edge; on the same square left open, it lies past the end and is dropped.
  const std::string text = "<text font-family='Noto Sans' font-size='20'><textPath href='#p' startOffset='395'>H</textPath></text>";
  svg::Tree tree = parse("<path id='p' d='M 0 100 H 100 V 200 H 0 Z' fill='none'/>" + text);
  auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  ASSERT_GT(a, 10);  // so the midpoint 395 + a / 2 is past the end: it wraps to a / 2 - 5
  expect_box(paths[0]->path.bounds(), glyph_box(*font, 'H', 20, -5, 100), 1e-6);
  tree = parse("<path id='p' d='M 0 100 H 100 V 200 H 0 V 100' fill='none'/>" + text);
  EXPECT_TRUE(text_paths(tree).empty());
  // pathLength: startOffset counts in the author's units (here half the real ones).
  tree = parse("<path id='p' d='M 20 100 L 220 100' pathLength='100' fill='none'/>"
               "<text font-family='Noto Sans' font-size='20'><textPath href='#p' startOffset='10'>H</textPath></text>");
  paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  expect_box(paths[0]->path.bounds(), glyph_box(*font, 'H', 20, 40, 100));
}

TEST(SvgText, TheTextBoxIsTheUnionOfFullGlyphCells) {
  // SVG 2, 8.10: objectBoundingBox paints on text refer to the glyph cells (advance wide, ascender to
  // descender), not to the outlines: a lowercase word without descenders still gets the descender's depth.
  const auto font = Font::load_file(system_font(kNotoSans));
  const svg::Tree tree = parse("<text x='10' y='80' font-family='Noto Sans' font-size='20'>vow</text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 1u);
  ASSERT_TRUE(paths[0]->paint_box.has_value());
  const FontMetrics fm = font->metrics(20);
  const double width = measure_text("vow", FontList(font), sized(20)).advance;
  expect_box(*paths[0]->paint_box, Rect{10, 80 + fm.ascender, 10 + width, 80 + fm.descender}, 1e-6);
  EXPECT_LT(paths[0]->path.bounds().y1, 80 + fm.descender - 1);  // the outlines stop well above it
}

TEST(SvgText, HiddenTextCountsInItsGroupsBoundingBox) {
  // A hidden shape draws nothing but still counts in the bounding box of its group (objectBoundingBox clip
  // paths, masks and paints of the group refer to it); text is no exception. Unpainted text likewise.
  const auto font = Font::load_file(system_font(kNotoSans));
  const FontMetrics fm = font->metrics(20);
  const double width = measure_text("vow", FontList(font), sized(20)).advance;
  for (const char* paint : {"visibility='hidden'", "fill='none'"}) {
    const svg::Tree tree = parse(std::string("<g><text x='10' y='80' font-family='Noto Sans' font-size='20' ") +
                                 paint + ">vow</text><rect x='200' y='90' width='10' height='10'/></g>");
    const auto* g = std::get_if<Group>(&tree.root.children.at(0).value);
    ASSERT_NE(g, nullptr);
    const auto* text = std::get_if<Group>(&g->children.at(0).value);
    ASSERT_NE(text, nullptr);
    ASSERT_EQ(text->children.size(), 1u) << paint;
    const auto* glyphs = std::get_if<PathNode>(&text->children[0].value);
    ASSERT_NE(glyphs, nullptr);
    EXPECT_FALSE(glyphs->fill.has_value()) << paint;
    EXPECT_FALSE(glyphs->stroke.has_value()) << paint;
    const std::optional<Rect> box = svg::object_bounds(*g, Affine{});
    ASSERT_TRUE(box.has_value());
    expect_box(*box, Rect{10, 80 + fm.ascender, 210, 100}, 1e-6);
    EXPECT_LT(10 + width, 200);  // the rectangle ends the box on the right, the text's cells on the left and top
  }
}

TEST(SvgText, VerticalTextRunsDownWithGlyphsTurnedSideways) {
  const svg::Tree tree = parse("<text x='100' y='20' writing-mode='tb' font-family='Noto Sans' font-size='20'>"
                               "H<tspan fill='red'>H</tspan></text>");
  const auto paths = text_paths(tree);
  ASSERT_EQ(paths.size(), 2u);
  const auto font = Font::load_file(system_font(kNotoSans));
  const double a = advance(*font, 'H', 20);
  const FontMetrics m = font->metrics(20);
  const double shift = (m.ascender + m.descender) / 2;  // the central baseline sits on x = 100
  const Rect upright = glyph_box(*font, 'H', 20, 0, 0);
  // rotate(90) maps (x, y) to (-y, x): the glyph's top points to +x, its advance runs down.
  for (int i = 0; i < 2; ++i) {
    expect_box(paths[static_cast<std::size_t>(i)]->path.bounds(),
               Rect{100 + shift - upright.y1, 20 + i * a + upright.x0, 100 + shift - upright.y0,
                    20 + i * a + upright.x1});
  }
}

TEST(SvgText, WhiteSpaceIsCollapsedUnlessPreserved) {
  const auto box = [](const std::string& text) {
    const svg::Tree tree = parse(text);
    const auto paths = text_paths(tree);
    EXPECT_EQ(paths.size(), 1u);
    return paths.empty() ? Rect{} : paths[0]->path.bounds();
  };
  const Rect plain = box("<text x='10' y='100' font-family='Noto Sans' font-size='20'>A B</text>");
  // Leading and trailing space stripped, newlines removed, runs of spaces and tabs collapsed to one.
  expect_box(box("<text x='10' y='100' font-family='Noto Sans' font-size='20'>\n   A \t\n   B  \n</text>"), plain);
  expect_box(box("<text x='10' y='100' font-family='Noto Sans' font-size='20'>  A <tspan> </tspan>B</text>"), plain);
  // xml:space="preserve": every space kept, newlines and tabs become spaces.
  const auto font = Font::load_file(system_font(kNotoSans));
  const double space = advance(*font, ' ', 20);
  const Rect kept = box("<text x='10' y='100' xml:space='preserve' font-family='Noto Sans' font-size='20'>\n A B</text>");
  EXPECT_NEAR(kept.x0, plain.x0 + 2 * space, 1e-6);
}

TEST(SvgText, BrokenFontFilesAreSkippedWithAWarning) {
  const std::string dir = testing::out_dir() + "/broken_fonts";
  std::filesystem::create_directories(dir);
  {
    std::FILE* f = std::fopen((dir + "/garbage.ttf").c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fputs("not a font at all, just some bytes", f);
    std::fclose(f);
  }
  std::filesystem::copy_file(system_font(kNotoSans), dir + "/NotoSans-Regular.ttf",
                             std::filesystem::copy_options::overwrite_existing);
  FontDb db;
  EXPECT_EQ(db.add_directory(dir), 1u);  // the good font only
  ASSERT_EQ(db.warnings().size(), 1u);
  EXPECT_NE(db.warnings()[0].find("garbage.ttf"), std::string::npos) << db.warnings()[0];
  EXPECT_THROW(db.add_directory(dir + "/no-such-dir"), Error);
}

TEST(SvgText, SystemFontsCoverWhatTheGivenFontsLack) {
  // The same fallback `vraster text` uses: fontconfig's fonts for the Arabic a Latin font lacks.
  system_font(kAmiri);  // fonts-hosny-amiri must be installed for fontconfig to have an Arabic font
  FontDb db;
  db.add_file(system_font(kNotoSerif));
  ASSERT_GT(db.add_system_fonts(), 0u);
  FontQuery q;
  q.families = {"Noto Serif"};
  const FontList list = db.fonts_for(q, U"Hello مرحبا");
  ASSERT_GE(list.fonts.size(), 2u);
  EXPECT_EQ(list.fonts[0]->family_name(), "Noto Serif");
  EXPECT_TRUE(list.fonts[1]->has_glyph(U'م'));
}

TEST(SvgText, HostileValuesAreBounded) {
  // Huge font sizes, non-finite lists, deep nesting and long strings: errors or warnings, never crashes.
  EXPECT_NO_THROW(parse("<text x='10' y='100' font-size='1e300'>A</text>"));
  EXPECT_NO_THROW(parse("<text x='1e308 1e308' dx='1e308 1e308' y='100'>AAA</text>"));
  EXPECT_NO_THROW(parse("<text x='nan' y='inf' rotate='nan'>A</text>"));
  EXPECT_NO_THROW(parse("<text letter-spacing='1e300'>AAA</text>"));
  std::string deep = "<text>";
  for (int i = 0; i < 200; ++i) deep += "<tspan>";
  deep += "A";
  for (int i = 0; i < 200; ++i) deep += "</tspan>";
  EXPECT_NO_THROW(parse(deep + "</text>"));
  EXPECT_NO_THROW(parse("<text>" + std::string(200000, 'x') + "</text>"));
}

}  // namespace
}  // namespace vraster::text
