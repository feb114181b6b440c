// Drawing the resolved SVG tree on the canvas (svg_subset/include/svg_subset/draw.hpp): small documents whose
// pixels can be worked out by hand. Every image is 100 x 100 px at one user unit per pixel, on transparent.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "svg_subset/draw.hpp"
#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"

namespace vraster::svg {
namespace {

Image draw(const std::string& body, int size = 100) {
  const Tree tree = parse_svg_tree("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\" height=\"100\">" + body +
                                   "</svg>");
  Image image(size, size);
  image.clear(Color::transparent());
  render_tree(tree, image);
  return image;
}

/// Premultiplied RGBA of pixel (x, y) must be within `tol` of (r, g, b, a) on every channel.
void expect_pixel(const Image& image, int x, int y, std::array<int, 4> want, int tol) {
  const std::uint8_t* p = image.pixel(x, y);
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(p[c], want[c], tol) << "pixel (" << x << ", " << y << ") channel " << c << ": got " << int(p[0])
                                    << " " << int(p[1]) << " " << int(p[2]) << " " << int(p[3]);
  }
}

constexpr std::array<int, 4> kClear{0, 0, 0, 0};
constexpr std::array<int, 4> kGreen{0, 128, 0, 255};

TEST(SvgDraw, LinearGradientFollowsTheFormula) {
  // Black at x = 0 to white at x = 100: pixel x's centre has t = (x + 0.5) / 100, each channel 255 t.
  const Image img = draw(
      "<linearGradient id='g' gradientUnits='userSpaceOnUse' x1='0' y1='0' x2='100' y2='0'>"
      "<stop offset='0' stop-color='black'/><stop offset='1' stop-color='white'/></linearGradient>"
      "<rect width='100' height='100' fill='url(#g)'/>");
  for (const int x : {10, 50, 90}) {
    const int v = static_cast<int>(std::lround(255 * (x + 0.5) / 100));
    expect_pixel(img, x, 50, {v, v, v, 255}, 2);
  }
}

TEST(SvgDraw, ObjectBoundingBoxGradientOnAnOffOriginRect) {
  // Red to blue across the rect's own box (x 20..70): t = (x + 0.5 - 20) / 50.
  const Image img = draw(
      "<linearGradient id='g'><stop offset='0' stop-color='red'/><stop offset='1' stop-color='blue'/>"
      "</linearGradient><rect x='20' y='30' width='50' height='40' fill='url(#g)'/>");
  for (const int x : {22, 44, 67}) {
    const double t = (x + 0.5 - 20) / 50;
    expect_pixel(img, x, 50, {int(std::lround(255 * (1 - t))), 0, int(std::lround(255 * t)), 255}, 2);
  }
  expect_pixel(img, 10, 50, kClear, 0);  // outside the rect
  expect_pixel(img, 80, 50, kClear, 0);
  // A box without height (a horizontal line) cannot carry objectBoundingBox units: the stroke is not drawn.
  const Image line = draw(
      "<linearGradient id='g'><stop offset='0' stop-color='red'/><stop offset='1' stop-color='blue'/>"
      "</linearGradient><path d='M10 50 H90' stroke='url(#g)' stroke-width='10'/>");
  expect_pixel(line, 50, 50, kClear, 0);
}

TEST(SvgDraw, ClipPathChildrenFormAUnion) {
  // Two bands of the clip: the rect shows in both (an intersection would show nothing).
  const Image img = draw(
      "<clipPath id='c'><rect width='40' height='100'/><rect x='60' width='40' height='100'/></clipPath>"
      "<rect width='100' height='100' fill='green' clip-path='url(#c)'/>");
  expect_pixel(img, 20, 50, kGreen, 1);
  expect_pixel(img, 50, 50, kClear, 0);
  expect_pixel(img, 80, 50, kGreen, 1);
}

TEST(SvgDraw, ClipPathChildrenAreGeometryWithTheirClipRule) {
  // fill='none' does not matter inside a clipPath, clip-rule does (evenodd: a square ring); a <g> is not a
  // valid child and adds nothing.
  const Image img = draw(
      "<clipPath id='c'><path d='M10 10 H90 V90 H10 Z M30 30 H70 V70 H30 Z' fill='none' clip-rule='evenodd'/>"
      "<g><rect x='40' y='40' width='20' height='20'/></g></clipPath>"
      "<rect width='100' height='100' fill='green' clip-path='url(#c)'/>");
  expect_pixel(img, 20, 50, kGreen, 1);
  expect_pixel(img, 50, 50, kClear, 0);
  expect_pixel(img, 95, 50, kClear, 0);
}

TEST(SvgDraw, ClipPathUnitsObjectBoundingBox) {
  // The right half of the rect's box (x 50..80), and with a nested clip-path on the clipPath, its lower half too.
  const Image img = draw(
      "<clipPath id='c' clipPathUnits='objectBoundingBox'><rect x='0.5' width='0.5' height='1'/></clipPath>"
      "<rect x='20' y='20' width='60' height='60' fill='green' clip-path='url(#c)'/>");
  expect_pixel(img, 35, 50, kClear, 0);
  expect_pixel(img, 65, 50, kGreen, 1);
  expect_pixel(img, 90, 50, kClear, 0);
  const Image nested = draw(
      "<clipPath id='low'><rect y='50' width='100' height='50'/></clipPath>"
      "<clipPath id='c' clipPathUnits='objectBoundingBox' clip-path='url(#low)'>"
      "<rect x='0.5' width='0.5' height='1'/></clipPath>"
      "<rect x='20' y='20' width='60' height='60' fill='green' clip-path='url(#c)'/>");
  expect_pixel(nested, 65, 30, kClear, 0);
  expect_pixel(nested, 65, 70, kGreen, 1);
  expect_pixel(nested, 35, 70, kClear, 0);
}

TEST(SvgDraw, LuminanceMask) {
  // White: fully shown; mid grey #808080 (luminance 128/255): half; black: hidden.
  const Image img = draw(
      "<mask id='m' maskUnits='userSpaceOnUse' x='0' y='0' width='100' height='100'>"
      "<rect width='40' height='100' fill='white'/><rect x='40' width='20' height='100' fill='#808080'/>"
      "<rect x='60' width='40' height='100' fill='black'/></mask>"
      "<rect width='100' height='100' fill='green' mask='url(#m)'/>");
  expect_pixel(img, 20, 50, kGreen, 1);
  expect_pixel(img, 50, 50, {0, 64, 0, 128}, 2);
  expect_pixel(img, 80, 50, kClear, 0);
}

TEST(SvgDraw, GroupOpacityIsOneLayer) {
  // Opacity 0.5 on the group: the overlap of two opaque blue rects is as light as the rest (alpha 128), not
  // 1 - 0.5 * 0.5 = 0.75 as per-shape opacity would give.
  const Image img = draw(
      "<g opacity='0.5'><rect width='60' height='100' fill='blue'/><rect x='40' width='60' height='100' "
      "fill='blue'/></g>");
  expect_pixel(img, 20, 50, {0, 0, 128, 128}, 1);
  expect_pixel(img, 50, 50, {0, 0, 128, 128}, 1);
  expect_pixel(img, 80, 50, {0, 0, 128, 128}, 1);
}

TEST(SvgDraw, MixBlendModeMultiply) {
  // rgb(200, 100, 50) multiplied by rgb(128, 255, 0): channel products / 255 = (100, 100, 0) where they overlap.
  const Image img = draw(
      "<rect width='100' height='100' fill='rgb(200,100,50)'/>"
      "<rect x='50' width='50' height='100' fill='rgb(128,255,0)' style='mix-blend-mode: multiply'/>");
  expect_pixel(img, 25, 50, {200, 100, 50, 255}, 1);
  expect_pixel(img, 75, 50, {100, 100, 0, 255}, 2);
}

TEST(SvgDraw, PatternTileRepeats) {
  // A 20 x 20 tile with a red 10 x 10 square in its top-left corner, repeated over the whole image.
  const Image img = draw(
      "<pattern id='p' patternUnits='userSpaceOnUse' width='20' height='20'>"
      "<rect width='10' height='10' fill='red'/></pattern>"
      "<rect width='100' height='100' fill='url(#p)'/>");
  constexpr std::array<int, 4> kRed{255, 0, 0, 255};
  expect_pixel(img, 5, 5, kRed, 1);
  expect_pixel(img, 15, 5, kClear, 1);
  expect_pixel(img, 45, 45, kRed, 1);
  expect_pixel(img, 85, 65, kRed, 1);
  expect_pixel(img, 85, 75, kClear, 1);
  expect_pixel(img, 94, 94, kClear, 1);
}

TEST(SvgDraw, ContextPaintsUseTheContextElementsSpaceAndBox) {
  // Stripes red on [0, 10) of every 20 user units, given through a use to a rect moved by 5: the stripes stay
  // where they are in the use's space (SVG 2 context-fill), not where they would be in the rect's own space.
  const Image stripes = draw(
      "<pattern id='p' patternUnits='userSpaceOnUse' width='20' height='20'>"
      "<rect width='10' height='20' fill='red'/></pattern>"
      "<defs><rect id='r' width='40' height='40' transform='translate(5 0)' fill='context-fill'/></defs>"
      "<use href='#r' fill='url(#p)'/>");
  constexpr std::array<int, 4> kRed{255, 0, 0, 255};
  expect_pixel(stripes, 7, 20, kRed, 1);
  expect_pixel(stripes, 12, 20, kClear, 1);  // the rect's own space would put red here
  expect_pixel(stripes, 22, 20, kRed, 1);
  expect_pixel(stripes, 42, 20, kRed, 1);
  // An objectBoundingBox gradient spans the use's box (both rects), not each rect's.
  const Image ramp = draw(
      "<linearGradient id='g'><stop offset='0' stop-color='black'/><stop offset='1' stop-color='white'/>"
      "</linearGradient><defs><g id='two'><rect width='50' height='10' fill='context-fill'/>"
      "<rect x='50' y='20' width='50' height='10' fill='context-fill'/></g></defs><use href='#two' fill='url(#g)'/>");
  expect_pixel(ramp, 25, 5, {64, 64, 64, 255}, 3);     // 0.255 of the way
  expect_pixel(ramp, 75, 25, {191, 191, 191, 255}, 3);  // 0.755: in its own box it would be 0.51
}

TEST(SvgDraw, HostileNumbersDrawNothingAndDoNotCrash) {
  // A tile far too large to draw at device resolution (it is drawn smaller), zero-sized boxes with
  // objectBoundingBox units, masks and clips on nothing, a pattern that paints itself.
  const Image img = draw(
      "<pattern id='huge' patternUnits='userSpaceOnUse' width='1e30' height='1e30'>"
      "<rect width='1e30' height='1e30' fill='red'/></pattern>"
      "<pattern id='self' width='0.5' height='0.5'><rect width='5' height='5' fill='url(#self)'/></pattern>"
      "<mask id='m'><rect width='1' height='1' fill='white'/></mask>"
      "<clipPath id='c' clipPathUnits='objectBoundingBox'><rect width='1' height='1'/></clipPath>"
      "<rect width='1e-300' height='1e-300' fill='url(#huge)'/>"
      "<rect width='10' height='10' fill='url(#self)' transform='scale(1e200)'/>"
      "<path d='M10 10 H90' stroke='black' mask='url(#m)'/>"
      "<path d='M10 10 V90' stroke='black' clip-path='url(#c)'/>"
      "<g opacity='0.5' transform='matrix(0 0 0 0 0 0)'><rect width='10' height='10'/></g>");
  expect_pixel(img, 10, 50, kClear, 0);
  expect_pixel(img, 50, 10, kClear, 0);
}

TEST(SvgDraw, ImageIsDrawnIntoItsDestinationAndClipped) {
  // A 2 x 2 image (red, green / blue, white) stretched over (10, 10)-(50, 50), clipped to x < 30: each image
  // pixel becomes a 20 x 20 block, unsmoothed; the right column is clipped away.
  auto pixels = std::make_shared<Image>(2, 2);
  const std::uint8_t rgba[4][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 255, 255}};
  for (int i = 0; i < 4; ++i) std::copy(rgba[i], rgba[i] + 4, pixels->pixel(i % 2, i / 2));
  Tree tree;
  tree.width = tree.height = 100;
  ImageNode node;
  node.image = pixels;
  node.view = node.clip = Rect{10, 10, 30, 50};
  node.dest = Rect{10, 10, 50, 50};
  node.smooth = false;
  tree.root.children.push_back(Node{node});
  tree.root.children.push_back(Node{ImageNode{}});  // no pixels (not decoded): skipped
  Image img(100, 100);
  img.clear(Color::transparent());
  render_tree(tree, img);
  expect_pixel(img, 15, 15, {255, 0, 0, 255}, 0);
  expect_pixel(img, 15, 45, {0, 0, 255, 255}, 0);
  expect_pixel(img, 35, 15, kClear, 0);  // green, clipped
  expect_pixel(img, 5, 5, kClear, 0);
}

TEST(SvgDraw, CoreLimitNamesTheElement) {
  // A stroke whose outline is over the core's limit: a ParseError at the element, also from inside a mask.
  for (const char* wrap : {"%s", "<mask id='m'>%s</mask><rect width='5' height='5' mask='url(#m)'/>"}) {
    std::string body = wrap;
    body.replace(body.find("%s"), 2, "\n<circle r='1e155' stroke='red' stroke-width='1e300'/>");
    const Tree tree = parse_svg_tree("<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'>" + body +
                                     "</svg>", "limit.svg");
    Image image(10, 10);
    try {
      render_tree(tree, image);
      ADD_FAILURE() << "no error for " << body;
    } catch (const ParseError& e) {
      EXPECT_EQ(e.line(), 2) << e.what();
      EXPECT_NE(std::string(e.what()).find("limit.svg:2:1: cannot draw the stroke of this element"), std::string::npos)
          << e.what();
    }
  }
}

TEST(SvgDraw, SixteenBitTargetsGetTheSameDrawing) {
  const Tree tree = parse_svg_tree(
      "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><g opacity='0.5'>"
      "<rect width='10' height='10' fill='blue'/></g></svg>");
  Image16 image(10, 10);
  image.clear(Color::transparent());
  render_tree(tree, image);
  EXPECT_NEAR(image.pixel(5, 5)[2], 32768, 64);
  EXPECT_NEAR(image.pixel(5, 5)[3], 32768, 64);
}

TEST(SvgDraw, HiddenShapesCountInTheGroupsBoundingBox) {
  // The clip keeps the left half of the group's box. The hidden rect makes the box 0..100 (clip at x = 50);
  // without it the box would be 20..60 (clip at x = 40).
  const Image img = draw(
      "<clipPath id='c' clipPathUnits='objectBoundingBox'><rect width='0.5' height='1'/></clipPath>"
      "<g clip-path='url(#c)'><rect width='100' height='100' fill='red' visibility='hidden'/>"
      "<rect x='20' y='20' width='40' height='60' fill='green'/></g>");
  expect_pixel(img, 45, 50, kGreen, 0);
  expect_pixel(img, 55, 50, kClear, 0);
  expect_pixel(img, 10, 50, kClear, 0);  // the hidden rect draws nothing
}

TEST(SvgDraw, RootBackgroundColorFillsTheViewport) {
  const Tree tree = parse_svg_tree("<svg xmlns='http://www.w3.org/2000/svg' width='100' height='100' "
                                   "viewBox='50 50 10 10' style='background-color: blue'>"
                                   "<rect x='50' y='50' width='5' height='5' fill='green'/></svg>");
  Image img(100, 100);
  img.clear(Color::transparent());
  render_tree(tree, img);
  expect_pixel(img, 25, 25, kGreen, 0);
  expect_pixel(img, 75, 75, {0, 0, 255, 255}, 0);  // outside the viewBox content, still the background
  expect_pixel(img, 99, 0, {0, 0, 255, 255}, 0);
}

TEST(SvgDraw, FallbackColourWhereABoundingBoxServerCannotApply) {
  // A vertical line has a box without width: its objectBoundingBox gradient and pattern give way to the
  // fallback colour; without one the stroke paints nothing.
  const Image img = draw(
      "<linearGradient id='g'><stop offset='0' stop-color='red'/><stop offset='1' stop-color='red'/></linearGradient>"
      "<pattern id='p' width='1' height='1'><rect width='50' height='50' fill='red'/></pattern>"
      "<line x1='20' y1='10' x2='20' y2='90' stroke='url(#g) green' stroke-width='4'/>"
      "<line x1='50' y1='10' x2='50' y2='90' stroke='url(#p) green' stroke-width='4'/>"
      "<line x1='80' y1='10' x2='80' y2='90' stroke='url(#g)' stroke-width='4'/>");
  expect_pixel(img, 20, 50, kGreen, 0);
  expect_pixel(img, 50, 50, kGreen, 0);
  expect_pixel(img, 80, 50, kClear, 0);
}

}  // namespace
}  // namespace vraster::svg
