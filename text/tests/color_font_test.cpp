// Colour bitmap glyphs (CBDT/CBLC; sbix goes the same way through FreeType's FT_LOAD_COLOR): the font's strike
// images, their place in the resolved tree (an ImageNode in a group that places it like the glyph) and their
// pixels, against FreeType's own bitmap of the glyph read here directly.
#include <ft2build.h>
#include FT_FREETYPE_H
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "svg_subset/draw.hpp"
#include "svg_subset/tree.hpp"
#include "text_support.hpp"
#include "vraster/canvas.hpp"
#include "vraster/scene.hpp"
#include "vraster_text/font.hpp"
#include "vraster_text/font_db.hpp"

namespace vraster::text {
namespace {

using svg::Group;
using svg::ImageNode;
using svg::Node;
using svg::PathNode;
using testing::system_font;

using testing::kNotoColorEmoji;  // CBDT/CBLC: one strike of 109 pixels per em, no outlines
constexpr testing::SystemFont kNotoSans{"/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf", "fonts-noto-core"};
constexpr char32_t kGrinning = 0x1F600;  // 😀
constexpr double kStrikePpem = 109;

/// FreeType's own colour bitmap of a code point (straight from the strike, BGRA premultiplied), as RGBA, with the
/// bitmap's left and top bearings.
struct Reference {
  Image image;
  int left = 0, top = 0;
};
Reference freetype_bitmap(const std::string& path, char32_t c) {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  Reference out;
  if (FT_Init_FreeType(&library) != 0) throw std::runtime_error("FreeType did not start");
  if (FT_New_Face(library, path.c_str(), 0, &face) == 0 && FT_Select_Size(face, 0) == 0 &&
      FT_Load_Glyph(face, FT_Get_Char_Index(face, c), FT_LOAD_COLOR) == 0) {
    const FT_Bitmap& b = face->glyph->bitmap;
    out.image = Image(static_cast<int>(b.width), static_cast<int>(b.rows));
    for (unsigned y = 0; y < b.rows; ++y)
      for (unsigned x = 0; x < b.width; ++x) {
        const unsigned char* s = b.buffer + y * static_cast<unsigned>(b.pitch) + x * 4;
        std::uint8_t* d = out.image.pixel(static_cast<int>(x), static_cast<int>(y));
        d[0] = s[2], d[1] = s[1], d[2] = s[0], d[3] = s[3];
      }
    out.left = face->glyph->bitmap_left;
    out.top = face->glyph->bitmap_top;
  }
  if (face) FT_Done_Face(face);
  FT_Done_FreeType(library);
  return out;
}

std::shared_ptr<FontDb> emoji_fonts() {
  auto db = std::make_shared<FontDb>();
  db->add_file(system_font(kNotoSans));
  db->add_file(system_font(kNotoColorEmoji));
  db->set_generic_family(GenericFamily::SansSerif, "Noto Sans");
  return db;
}

svg::Tree parse(const std::string& body) {
  svg::ParseOptions options;
  options.fonts = emoji_fonts();
  return svg::parse_svg_tree("<svg xmlns='http://www.w3.org/2000/svg' width='300' height='200'>" + body + "</svg>",
                             "<test>", options);
}

/// The children of the first <text>'s group.
const std::vector<Node>& text_children(const svg::Tree& tree) {
  for (const Node& n : tree.root.children) {
    if (const auto* g = std::get_if<Group>(&n.value)) return g->children;
  }
  throw std::runtime_error("no text group in the tree");
}

/// The group holding a colour glyph's image, and the image.
std::pair<const Group*, const ImageNode*> image_glyph(const Node& n) {
  const auto* g = std::get_if<Group>(&n.value);
  if (!g || g->children.size() != 1) return {nullptr, nullptr};
  return {g, std::get_if<ImageNode>(&g->children[0].value)};
}

TEST(ColorFont, StrikeImageIsFreeTypesBitmapPremultiplied) {
  const std::shared_ptr<Font> emoji = Font::load_file(system_font(kNotoColorEmoji));
  const std::shared_ptr<Font> sans = Font::load_file(system_font(kNotoSans));
  EXPECT_TRUE(emoji->has_color_bitmaps());
  EXPECT_FALSE(sans->has_color_bitmaps());
  EXPECT_EQ(sans->color_bitmap(sans->glyph_index('A')), nullptr);
  const ColorBitmap* b = emoji->color_bitmap(emoji->glyph_index(kGrinning));
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b, emoji->color_bitmap(emoji->glyph_index(kGrinning)));  // cached: the same object
  const Reference ref = freetype_bitmap(kNotoColorEmoji.path, kGrinning);
  ASSERT_GT(ref.image.width, 0);
  EXPECT_EQ(b->ppem, kStrikePpem);
  EXPECT_EQ(b->left, ref.left);
  EXPECT_EQ(b->top, -ref.top);
  ASSERT_EQ(b->image->width, ref.image.width);
  ASSERT_EQ(b->image->height, ref.image.height);
  EXPECT_EQ(b->image->data, ref.image.data);
  // The face is yellow in the middle (an independent look at the channel order), and premultiplied everywhere.
  const std::uint8_t* centre = b->image->pixel(b->image->width / 2, b->image->height / 3);
  EXPECT_EQ(centre[3], 255);
  EXPECT_GT(centre[0], 200);
  EXPECT_GT(centre[1], 150);
  EXPECT_LT(centre[2], 100);
  for (std::size_t i = 0; i < b->image->data.size(); i += 4)
    for (int k = 0; k < 3; ++k) ASSERT_LE(b->image->data[i + k], b->image->data[i + 3]);
}

TEST(ColorFont, BitmapGlyphIsAnImagePlacedLikeItsOutlineWouldBe) {
  // Font size 54.5 is half the strike: the image is scaled by 1/2, its top-left corner at the bearings.
  const svg::Tree tree = parse("<text x='20' y='150' font-size='54.5' font-family='Noto Color Emoji'>&#x1F600;</text>");
  const std::vector<Node>& children = text_children(tree);
  ASSERT_EQ(children.size(), 1u);
  const auto [group, image] = image_glyph(children[0]);
  ASSERT_NE(image, nullptr);
  const Reference ref = freetype_bitmap(kNotoColorEmoji.path, kGrinning);
  EXPECT_EQ(image->dest.x0, ref.left);
  EXPECT_EQ(image->dest.y0, -ref.top);
  EXPECT_EQ(image->dest.width(), ref.image.width);
  EXPECT_EQ(image->dest.height(), ref.image.height);
  const Point origin = group->transform.apply({0, 0});
  const Point unit = group->transform.apply({1, 0});
  EXPECT_NEAR(origin.x, 20, 1e-9);
  EXPECT_NEAR(origin.y, 150, 1e-9);
  EXPECT_NEAR(unit.x - origin.x, 0.5, 1e-9);
  EXPECT_EQ(group->opacity, 1.f);
}

TEST(ColorFont, RotatedBitmapGlyphTurnsWithItsTransform) {
  const svg::Tree tree =
      parse("<text x='100' y='100' rotate='90' font-size='109' font-family='Noto Color Emoji'>&#x1F600;</text>");
  const auto [group, image] = image_glyph(text_children(tree).at(0));
  ASSERT_NE(image, nullptr);
  const Point origin = group->transform.apply({0, 0});
  const Point along = group->transform.apply({1, 0});
  EXPECT_NEAR(origin.x, 100, 1e-9);
  EXPECT_NEAR(origin.y, 100, 1e-9);
  EXPECT_NEAR(along.x - origin.x, 0, 1e-9);  // image x runs down the page
  EXPECT_NEAR(along.y - origin.y, 1, 1e-9);
}

TEST(ColorFont, BitmapGlyphsSitBetweenOutlinesInTextOrderAndFollowTheFill) {
  // Noto Sans lacks the emoji: it falls back to the colour font, between the outlines of A and B.
  const svg::Tree tree = parse("<text x='10' y='100' font-family='Noto Sans' fill-opacity='0.5'>A&#x1F600;B</text>");
  const std::vector<Node>& children = text_children(tree);
  ASSERT_EQ(children.size(), 3u);
  EXPECT_NE(std::get_if<PathNode>(&children[0].value), nullptr);
  const auto [group, image] = image_glyph(children[1]);
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(group->opacity, 0.5f);  // fill-opacity
  EXPECT_NE(std::get_if<PathNode>(&children[2].value), nullptr);
  // Without a fill the bitmap, which takes the fill's place, is not drawn.
  const svg::Tree unfilled = parse("<text x='10' y='100' fill='none' stroke='black'>A&#x1F600;B</text>");
  for (const Node& n : text_children(unfilled)) EXPECT_EQ(image_glyph(n).second, nullptr);
}

TEST(ColorFont, PixelsAtTheStrikeSizeAreTheStrikeImage) {
  // At the strike's size on whole pixels the image is drawn one to one: the pixels are FreeType's bitmap.
  const Reference ref = freetype_bitmap(kNotoColorEmoji.path, kGrinning);
  ASSERT_GT(ref.image.width, 0);
  const int x = 20, y = 150;
  const svg::Tree tree = parse("<text x='" + std::to_string(x) + "' y='" + std::to_string(y) +
                               "' font-size='109' font-family='Noto Color Emoji'>&#x1F600;</text>");
  Image out(300, 200);
  svg::render_tree(tree, out);
  int differing = 0;
  for (int py = 0; py < out.height; ++py)
    for (int px = 0; px < out.width; ++px) {
      const int rx = px - x - ref.left, ry = py - (y - ref.top);
      const bool inside = rx >= 0 && ry >= 0 && rx < ref.image.width && ry < ref.image.height;
      for (int k = 0; k < 4; ++k) {
        const int want = inside ? ref.image.pixel(rx, ry)[k] : 0;
        differing += std::abs(out.pixel(px, py)[k] - want) > 1;
      }
    }
  EXPECT_EQ(differing, 0);
}

TEST(ColorFont, RecordingCanvasSharesADrawnImage) {
  // A glyph image drawn many times is stored once in a recorded scene, not copied per draw call.
  auto image = std::make_shared<const Image>(Image(64, 64));
  Scene scene;
  scene.width = 100;
  scene.height = 100;
  Canvas canvas(scene);
  canvas.draw_image(image, 0, 0, 10, 10);
  canvas.draw_image(image, 20, 0, 10, 10);
  ASSERT_EQ(scene.commands.size(), 2u);
  EXPECT_EQ(scene.commands[0].image.get(), image.get());
  EXPECT_EQ(scene.commands[1].image.get(), image.get());
}

}  // namespace
}  // namespace vraster::text
