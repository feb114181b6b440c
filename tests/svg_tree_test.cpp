// The resolved SVG tree (svg_subset/include/svg_subset/tree.hpp), checked without pixels: one test per feature.
#include <gtest/gtest.h>

#include <string>

#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"

namespace vraster::svg {
namespace {

Tree tree(const std::string& body, const std::string& root_attrs = "width=\"100\" height=\"100\"") {
  return parse_svg_tree("<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" " +
                        root_attrs + ">" + body + "</svg>");
}

const Group& group_at(const Group& g, std::size_t i) {
  EXPECT_LT(i, g.children.size());
  const Group* sub = std::get_if<Group>(&g.children.at(i).value);
  EXPECT_NE(sub, nullptr) << "child " << i << " is not a group";
  return *sub;
}

const PathNode& path_at(const Group& g, std::size_t i) {
  EXPECT_LT(i, g.children.size());
  const PathNode* p = std::get_if<PathNode>(&g.children.at(i).value);
  EXPECT_NE(p, nullptr) << "child " << i << " is not a path";
  return *p;
}

void expect_rgba(const Color& c, int r, int g, int b, double a = 1) {
  EXPECT_NEAR(c.r * 255, r, 0.6);
  EXPECT_NEAR(c.g * 255, g, 0.6);
  EXPECT_NEAR(c.b * 255, b, 0.6);
  EXPECT_NEAR(c.a, a, 1e-3);
}

void expect_affine(const Affine& m, double a, double b, double c, double d, double e, double f) {
  EXPECT_NEAR(m.a, a, 1e-9);
  EXPECT_NEAR(m.b, b, 1e-9);
  EXPECT_NEAR(m.c, c, 1e-9);
  EXPECT_NEAR(m.d, d, 1e-9);
  EXPECT_NEAR(m.e, e, 1e-9);
  EXPECT_NEAR(m.f, f, 1e-9);
}

TEST(SvgTree, StyleSheetCascadeAndPrecedence) {
  const Tree t = tree(
      "<style>rect { fill: red } .a { fill: lime } #r3 { fill: blue } g > rect { stroke: black }"
      " rect:first-child { stroke-width: 3 } [data-x] { fill: yellow !important }</style>"
      "<g><rect width='1' height='1' fill='green'/>"                      // type rule beats the attribute
      "<rect class='a' width='1' height='1'/>"                            // class beats type
      "<rect id='r3' class='a' width='1' height='1' style='fill: aqua'/>"  // style attribute beats id
      "<rect data-x='1' width='1' height='1' style='fill: aqua'/></g>"    // !important beats style
      "<rect width='1' height='1'/>");                                    // not a child of g: no stroke
  const Group& g = group_at(t.root, 0);
  ASSERT_EQ(g.children.size(), 4u);
  expect_rgba(path_at(g, 0).fill->paint.color, 255, 0, 0);
  expect_rgba(path_at(g, 1).fill->paint.color, 0, 255, 0);
  expect_rgba(path_at(g, 2).fill->paint.color, 0, 255, 255);
  expect_rgba(path_at(g, 3).fill->paint.color, 255, 255, 0);
  ASSERT_TRUE(path_at(g, 0).stroke);
  EXPECT_EQ(path_at(g, 0).stroke->style.width, 3);  // :first-child
  ASSERT_TRUE(path_at(g, 1).stroke);
  EXPECT_EQ(path_at(g, 1).stroke->style.width, 1);
  EXPECT_FALSE(path_at(t.root, 1).stroke);
}

TEST(SvgTree, SelectorsBeyondLevelTwo) {
  // :root, :not(), :last-child, the next-sibling combinator, and a user-action pseudo-class that never matches.
  const Tree t = tree(
      "<style>:root > g rect { fill: red } rect:not(.a) { stroke: black } g > .a + rect { fill: lime }"
      " rect:last-child { stroke-width: 4 } rect:hover { fill: blue } g:not(:hover) > .a { fill: yellow }</style>"
      "<g><rect class='a' width='1' height='1'/><rect width='1' height='1'/><rect width='1' height='1'/></g>");
  const Group& g = group_at(t.root, 0);
  ASSERT_EQ(g.children.size(), 3u);
  expect_rgba(path_at(g, 0).fill->paint.color, 255, 255, 0);  // :not(:hover) beats the type rule (more specific)
  expect_rgba(path_at(g, 1).fill->paint.color, 0, 255, 0);    // right after .a (and later than the red rule)
  expect_rgba(path_at(g, 2).fill->paint.color, 255, 0, 0);    // not right after .a, not hovered
  EXPECT_FALSE(path_at(g, 0).stroke);
  ASSERT_TRUE(path_at(g, 1).stroke && path_at(g, 2).stroke);
  EXPECT_EQ(path_at(g, 1).stroke->style.width, 1);
  EXPECT_EQ(path_at(g, 2).stroke->style.width, 4);  // :last-child
  EXPECT_TRUE(t.warnings.empty()) << t.warnings.front();
}

TEST(SvgTree, CustomPropertiesAndVar) {
  // Declared on :root and overridden on a group, inherited, with fallbacks, references inside custom properties,
  // and a reference with no value and no fallback: the winning declaration is then `unset`, not the one it beat.
  const Tree t = tree(
      "<style>:root { --main: #00ff00; --w: 3 } .b { --main: blue; --dash: var(--w) 1 }"
      " rect { fill: var(--main); stroke: var(--edge, red); stroke-width: var(--w) }"
      " .c { fill: VAR( --missing ) } .d { stroke-dasharray: var(--dash) }</style>"
      "<rect width='1' height='1'/><g class='b'><rect width='1' height='1'/>"
      "<rect class='c d' width='1' height='1' style='--edge: #000080'/></g>");
  expect_rgba(path_at(t.root, 0).fill->paint.color, 0, 255, 0);
  expect_rgba(path_at(t.root, 0).stroke->paint.color, 255, 0, 0);  // the fallback
  EXPECT_EQ(path_at(t.root, 0).stroke->style.width, 3);
  const Group& g = group_at(t.root, 1);
  expect_rgba(path_at(g, 0).fill->paint.color, 0, 0, 255);  // the group's own --main, inherited
  expect_rgba(path_at(g, 1).fill->paint.color, 0, 0, 0);  // var(--missing), no fallback: unset, the g's black
  expect_rgba(path_at(g, 1).stroke->paint.color, 0, 0, 128);
  EXPECT_EQ(path_at(g, 1).stroke->style.dashes, (std::vector<double>{3, 1}));  // a reference inside a reference
  bool warned = false;
  for (const std::string& w : t.warnings) warned = warned || w.find("--missing") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(SvgTree, UnitsResolveToUserUnits) {
  const Tree t = tree("<rect x='1in' y='12pt' width='25.4mm' height='50%' stroke='black' stroke-width='1pc'/>"
                      "<circle r='2em' cx='1cm'/>",
                      "width='200' height='100'");
  const Rect r = path_at(t.root, 0).path.bounds();
  EXPECT_NEAR(r.x0, 96, 1e-9);
  EXPECT_NEAR(r.y0, 16, 1e-9);
  EXPECT_NEAR(r.x1 - r.x0, 96, 1e-9);
  EXPECT_NEAR(r.y1 - r.y0, 50, 1e-9);  // % of the viewport height
  EXPECT_EQ(path_at(t.root, 0).stroke->style.width, 16);
  const Rect c = path_at(t.root, 1).path.bounds();
  EXPECT_NEAR(c.x1 - c.x0, 64, 1e-6);  // r = 2em at the default 16 px
  EXPECT_NEAR((c.x0 + c.x1) / 2, 96 / 2.54, 1e-6);
}

TEST(SvgTree, ColourForms) {
  const Tree t = tree(
      "<rect width='1' height='1' fill='hsl(120, 100%, 25%)'/>"
      "<rect width='1' height='1' fill='hsla(240, 100%, 50%, 0.5)'/>"
      "<rect width='1' height='1' fill='#f008'/>"
      "<rect width='1' height='1' fill='#11223344'/>"
      "<rect width='1' height='1' color='rgb(10, 20, 30)' fill='currentColor'/>"
      "<rect width='1' height='1' fill='hsl(480, 200%, 25%)'/>");
  ASSERT_EQ(t.root.children.size(), 6u);
  expect_rgba(path_at(t.root, 0).fill->paint.color, 0, 128, 0);
  expect_rgba(path_at(t.root, 1).fill->paint.color, 0, 0, 255, 0.5);
  expect_rgba(path_at(t.root, 2).fill->paint.color, 255, 0, 0, 0x88 / 255.0);
  expect_rgba(path_at(t.root, 3).fill->paint.color, 0x11, 0x22, 0x33, 0x44 / 255.0);
  expect_rgba(path_at(t.root, 4).fill->paint.color, 10, 20, 30);
  expect_rgba(path_at(t.root, 5).fill->paint.color, 0, 128, 0);  // hue wraps, saturation clamps
}

TEST(SvgTree, UseIsExpandedWithTranslate) {
  const Tree t = tree("<defs><rect id='r' width='10' height='5' fill='blue'/></defs>"
                      "<use xlink:href='#r' x='3' y='4' transform='scale(2)' fill='red'/>");
  ASSERT_EQ(t.root.children.size(), 1u);
  const Group& use = group_at(t.root, 0);
  expect_affine(use.transform, 2, 0, 0, 2, 6, 8);  // transform, then translate(x, y)
  expect_rgba(path_at(use, 0).fill->paint.color, 0, 0, 255);
}

TEST(SvgTree, TransformOriginMovesTheFixedPoint) {
  // rotate(90) around (10, 20): translate(10 20) rotate(90) translate(-10 -20) = [0 1 -1 0 30 10].
  const Tree t = tree("<rect width='5' height='5' transform='rotate(90)' transform-origin='10 20'/>"
                      "<rect width='5' height='5' transform='scale(2)' transform-origin='right bottom'/>"
                      "<rect width='5' height='5' transform='scale(2)' transform-origin='top 25%'/>"
                      "<rect width='5' height='5' transform='scale(2)' transform-origin='bogus'/>"
                      "<linearGradient id='g' gradientTransform='scale(2)' transform-origin='0.5 0.5'/>",
                      "viewBox='0 0 200 100'");
  ASSERT_EQ(t.root.children.size(), 4u);
  expect_affine(group_at(t.root, 0).transform, 0, 1, -1, 0, 30, 10);
  expect_affine(group_at(t.root, 1).transform, 2, 0, 0, 2, -200, -100);  // right bottom = (200, 100)
  expect_affine(group_at(t.root, 2).transform, 2, 0, 0, 2, -50, 0);      // y keyword first: (25%, top)
  expect_affine(group_at(t.root, 3).transform, 2, 0, 0, 2, 0, 0);        // invalid: ignored
  bool warned = false;
  for (const std::string& w : t.warnings) warned = warned || w.find("transform-origin") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(SvgTree, UseOfSymbolMakesAViewport) {
  const Tree t = tree("<symbol id='s' viewBox='0 0 10 10'><rect width='10' height='10'/></symbol>"
                      "<use href='#s' x='5' width='20' height='40'/>");
  const Group& use = group_at(t.root, 0);
  expect_affine(use.transform, 1, 0, 0, 1, 5, 0);
  const Group& symbol = group_at(use, 0);
  ASSERT_TRUE(symbol.clip);  // overflow: hidden
  const Group& inner = group_at(symbol, 0);
  expect_affine(inner.transform, 2, 0, 0, 2, 0, 10);  // xMidYMid meet of 10x10 into 20x40
}

TEST(SvgTree, NestedSvgViewportAndPreserveAspectRatio) {
  const Tree t = tree("<svg x='10' y='20' width='50' height='20' viewBox='0 0 10 10' preserveAspectRatio='xMaxYMin slice'>"
                      "<rect width='10' height='10'/></svg>"
                      "<svg width='50' height='20' viewBox='0 0 10 10' preserveAspectRatio='none' overflow='visible'>"
                      "<rect width='10' height='10'/></svg>");
  const Group& a = group_at(t.root, 0);
  ASSERT_TRUE(a.clip);
  EXPECT_EQ(a.clip->content->children.size(), 1u);
  expect_affine(group_at(a, 0).transform, 5, 0, 0, 5, 10, 20);  // slice: scale 5, xMax: 50 - 50 = 0 shift
  const Group& b = group_at(t.root, 1);
  EXPECT_FALSE(b.clip);
  expect_affine(group_at(b, 0).transform, 5, 0, 0, 2, 0, 0);
}

TEST(SvgTree, SwitchTakesTheFirstChildThatPasses) {
  const Tree t = tree("<switch>"
                      "<rect systemLanguage='fr' width='1' height='1' fill='red'/>"
                      "<rect requiredExtensions='http://example.org/x' width='1' height='1' fill='red'/>"
                      "<rect systemLanguage='de, en-GB' width='1' height='1' fill='lime'/>"
                      "<rect width='1' height='1' fill='blue'/></switch>");
  const Group& s = group_at(t.root, 0);
  ASSERT_EQ(s.children.size(), 1u);
  expect_rgba(path_at(s, 0).fill->paint.color, 0, 255, 0);
}

TEST(SvgTree, GradientHrefChainInheritsAttributesAndStops) {
  const Tree t = tree(
      "<linearGradient id='base' x1='10%' x2='0.9' spreadMethod='reflect' gradientTransform='rotate(90)'>"
      "<stop offset='0.2' stop-color='red'/><stop offset='10%' stop-color='hsl(240,100%,50%)' stop-opacity='0.5'/>"
      "<stop offset='2' style='stop-color: lime'/></linearGradient>"
      "<linearGradient id='child' xlink:href='#base' y2='1'/>"
      "<radialGradient id='rad' xlink:href='#child' gradientUnits='userSpaceOnUse' cx='50' r='20' fx='40'/>"
      "<linearGradient id='one'><stop stop-color='#123456'/></linearGradient>"
      "<rect width='1' height='1' fill='url(#child)'/><rect width='1' height='1' fill='url(#rad)'/>"
      "<rect width='1' height='1' fill='url(#one)'/>");
  ASSERT_EQ(t.root.children.size(), 3u);
  const Paint& p = path_at(t.root, 0).fill->paint;
  ASSERT_EQ(p.kind, Paint::Kind::Gradient);
  const Gradient& g = *p.gradient;
  EXPECT_EQ(g.kind, Gradient::Kind::Linear);
  EXPECT_EQ(g.units, Units::ObjectBoundingBox);
  EXPECT_EQ(g.spread, Spread::Reflect);
  EXPECT_NEAR(g.x1, 0.1, 1e-12);
  EXPECT_NEAR(g.x2, 0.9, 1e-12);
  EXPECT_NEAR(g.y2, 1, 1e-12);
  expect_affine(g.transform, 0, 1, -1, 0, 0, 0);
  ASSERT_EQ(g.stops.size(), 3u);
  EXPECT_NEAR(g.stops[0].offset, 0.2, 1e-12);
  EXPECT_NEAR(g.stops[1].offset, 0.2, 1e-12);  // never below the previous stop
  EXPECT_NEAR(g.stops[2].offset, 1, 1e-12);    // clamped
  expect_rgba(g.stops[1].color, 0, 0, 255, 0.5);
  expect_rgba(g.stops[2].color, 0, 255, 0);
  const Gradient& r = *path_at(t.root, 1).fill->paint.gradient;
  EXPECT_EQ(r.kind, Gradient::Kind::Radial);
  EXPECT_EQ(r.units, Units::UserSpaceOnUse);
  EXPECT_EQ(r.spread, Spread::Reflect);  // through two links
  EXPECT_EQ(r.cx, 50);
  EXPECT_EQ(r.r, 20);
  EXPECT_EQ(r.fx, 40);
  EXPECT_EQ(r.fy, 50);  // fy defaults to cy: 50% of the viewport
  EXPECT_EQ(r.stops.size(), 3u);
  const Paint& one = path_at(t.root, 2).fill->paint;
  EXPECT_EQ(one.kind, Paint::Kind::Color);  // a single stop is a solid colour
  expect_rgba(one.color, 0x12, 0x34, 0x56);
}

TEST(SvgTree, PaintFallbacksAndMissingServers) {
  const Tree t = tree("<rect id='notpaint' width='1' height='1'/>"
                      "<rect width='1' height='1' fill='url(#missing) lime'/>"
                      "<rect width='1' height='1' fill='url(#notpaint) blue' stroke='url(#missing)'/>");
  ASSERT_EQ(t.root.children.size(), 3u);
  expect_rgba(path_at(t.root, 1).fill->paint.color, 0, 255, 0);
  expect_rgba(path_at(t.root, 2).fill->paint.color, 0, 0, 255);
  EXPECT_FALSE(path_at(t.root, 2).stroke);  // a missing server without fallback is none
}

TEST(SvgTree, FallbackAfterAnUnusableServer) {
  // A gradient without stops cannot paint: the fallback applies (currentColor resolved), else none. A usable
  // server keeps its fallback for shapes it cannot apply to (objectBoundingBox units on a line).
  const Tree t = tree("<linearGradient id='empty'/>"
                      "<linearGradient id='g'><stop offset='0' stop-color='red'/><stop offset='1'/></linearGradient>"
                      "<rect width='1' height='1' color='lime' fill='url(#empty) currentColor'/>"
                      "<rect width='1' height='1' fill='url(#empty)' stroke='black'/>"
                      "<line x2='10' stroke='url(#g) blue'/><line x2='10' stroke='url(#g) none'/>");
  ASSERT_EQ(t.root.children.size(), 4u);
  expect_rgba(path_at(t.root, 0).fill->paint.color, 0, 255, 0);
  EXPECT_FALSE(path_at(t.root, 1).fill);
  const Paint& blue = path_at(t.root, 2).stroke->paint;
  EXPECT_EQ(blue.kind, Paint::Kind::Gradient);
  ASSERT_TRUE(blue.fallback);
  expect_rgba(*blue.fallback, 0, 0, 255);
  ASSERT_TRUE(path_at(t.root, 3).stroke->paint.fallback);
  EXPECT_EQ(path_at(t.root, 3).stroke->paint.fallback->a, 0);  // none: transparent
}

TEST(SvgTree, GradientGeometryComesOnlyFromTheSameKind) {
  const Tree t = tree("<radialGradient id='r' y2='1' cx='0.2' spreadMethod='reflect' gradientUnits='userSpaceOnUse'/>"
                      "<linearGradient id='l' href='#r' x2='0.7'><stop offset='0'/><stop offset='1'/></linearGradient>"
                      "<rect width='1' height='1' fill='url(#l)'/>");
  const Gradient& g = *path_at(t.root, 0).fill->paint.gradient;
  EXPECT_EQ(g.spread, Spread::Reflect);           // common attributes come through
  EXPECT_EQ(g.units, Units::UserSpaceOnUse);
  EXPECT_EQ(g.y2, 0);                             // the radial gradient's y2 is not one of its attributes
  EXPECT_NEAR(g.x2, 0.7, 1e-12);
}

TEST(SvgTree, PatternRecord) {
  const Tree t = tree("<pattern id='p' width='10' height='20' patternUnits='userSpaceOnUse' viewBox='0 0 1 1'>"
                      "<rect width='1' height='1' fill='red'/></pattern>"
                      "<pattern id='q' xlink:href='#p' patternTransform='translate(1 2)'/>"
                      "<rect width='1' height='1' fill='url(#q)'/>");
  const Paint& p = path_at(t.root, 0).fill->paint;
  ASSERT_EQ(p.kind, Paint::Kind::Pattern);
  EXPECT_EQ(p.pattern->units, Units::UserSpaceOnUse);
  EXPECT_EQ(p.pattern->rect.x1, 10);
  EXPECT_EQ(p.pattern->rect.y1, 20);
  ASSERT_TRUE(p.pattern->view_box);
  EXPECT_EQ(p.pattern->view_box->x1, 1);
  expect_affine(p.pattern->transform, 1, 0, 0, 1, 1, 2);
  ASSERT_EQ(p.pattern->content->children.size(), 1u);  // the content comes through the href chain
}

TEST(SvgTree, ClipPathAndMaskRecords) {
  const Tree t = tree("<clipPath id='c' clipPathUnits='objectBoundingBox' transform='scale(2)'>"
                      "<rect width='1' height='1' clip-rule='evenodd'/></clipPath>"
                      "<mask id='m' maskUnits='userSpaceOnUse' x='1' y='2' width='3' height='4' mask-type='alpha'>"
                      "<rect width='1' height='1' fill='white'/></mask>"
                      "<rect width='5' height='5' clip-path='url(#c)' mask='url(#m)' opacity='0.5'/>");
  const Group& g = group_at(t.root, 0);
  EXPECT_FLOAT_EQ(g.opacity, 0.5f);
  EXPECT_TRUE(g.needs_layer());
  ASSERT_TRUE(g.clip);
  EXPECT_EQ(g.clip->units, Units::ObjectBoundingBox);
  expect_affine(g.clip->transform, 2, 0, 0, 2, 0, 0);
  ASSERT_EQ(g.clip->content->children.size(), 1u);
  ASSERT_TRUE(g.mask);
  EXPECT_EQ(g.mask->units, Units::UserSpaceOnUse);
  EXPECT_FALSE(g.mask->luminance);
  EXPECT_EQ(g.mask->rect.x0, 1);
  EXPECT_EQ(g.mask->rect.y1, 6);
}

TEST(SvgTree, AReferenceLoopDropsOnlyTheReferenceThatClosesIt) {
  // clip c's child refers back to c: that reference is ignored, so c clips to its child's rectangle. A mask on
  // itself likewise masks with its content.
  const Tree t = tree("<clipPath id='c'><rect width='1' height='1' clip-path='url(#c)'/></clipPath>"
                      "<mask id='m' mask='url(#m)'><rect width='5' height='5' fill='white'/></mask>"
                      "<rect width='5' height='5' clip-path='url(#c)'/><rect width='5' height='5' mask='url(#m)'/>");
  const Group& clipped = group_at(t.root, 0);
  ASSERT_TRUE(clipped.clip);
  ASSERT_NE(clipped.clip->content, nullptr);
  ASSERT_EQ(clipped.clip->content->children.size(), 1u);
  EXPECT_FALSE(path_at(*clipped.clip->content, 0).path.empty());
  const Group& masked = group_at(t.root, 1);
  ASSERT_TRUE(masked.mask);
  ASSERT_NE(masked.mask->content, nullptr);
  EXPECT_EQ(masked.mask->mask, nullptr);
  int loops = 0;
  for (const std::string& w : t.warnings) loops += w.find("reference loop") != std::string::npos;
  EXPECT_EQ(loops, 2);
}

TEST(SvgTree, UseLoopsAreSkippedWithAWarning) {
  const Tree t = tree("<use id='u' xlink:href='#u'/><g id='g'><use xlink:href='#g'/></g>"
                      "<use id='a' href='#b'/><use id='b' href='#a'/><rect width='1' height='1'/>");
  // The drawable rect survives; every looping use is dropped.
  EXPECT_EQ(to_document(t).items.size(), 1u);
  EXPECT_GE(t.warnings.size(), 3u);
}

TEST(SvgTree, BillionLaughsOfUsesStops) {
  std::string body = "<rect id='l0' width='1' height='1'/>";
  for (int i = 1; i <= 9; ++i) {
    body += "<g id='l" + std::to_string(i) + "'>";
    for (int k = 0; k < 10; ++k) body += "<use href='#l" + std::to_string(i - 1) + "'/>";
    body += "</g>";
  }
  try {
    tree(body);
    FAIL() << "no error";
  } catch (const ParseError& e) {
    EXPECT_NE(e.message().find("too many <use> instances"), std::string::npos) << e.what();
    EXPECT_GT(e.line(), 0);
  }
}

TEST(SvgTree, ForeignNamespacesAreSkippedSilently) {
  const Tree t = parse_svg_tree(
      "<svg xmlns='http://www.w3.org/2000/svg' xmlns:inkscape='http://www.inkscape.org/namespaces/inkscape' "
      "xmlns:sodipodi='http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd' "
      "xmlns:rdf='http://www.w3.org/1999/02/22-rdf-syntax-ns#' width='10' height='10'>"
      "<sodipodi:namedview inkscape:zoom='1'/><metadata><rdf:RDF><rdf:Description/></rdf:RDF></metadata>"
      "<g inkscape:label='Layer 1' inkscape:groupmode='layer'><rect width='1' height='1'/></g></svg>");
  EXPECT_TRUE(t.warnings.empty()) << t.warnings[0];
  EXPECT_EQ(to_document(t).items.size(), 1u);
}

TEST(SvgTree, SvgNamespacePrefix) {
  const Tree t = parse_svg_tree("<svg:svg xmlns:svg='http://www.w3.org/2000/svg' width='10' height='10'>"
                                "<svg:rect width='1' height='1'/></svg:svg>");
  EXPECT_EQ(t.root.children.size(), 1u);
}

TEST(SvgTree, DisplayVisibilityAndPaintOrder) {
  const Tree t = tree("<g display='none'><rect width='1' height='1'/></g>"
                      "<g visibility='hidden'><rect width='1' height='1'/><rect visibility='visible' width='1' height='1'"
                      " stroke='red' paint-order='stroke' shape-rendering='crispEdges'/></g>");
  ASSERT_EQ(t.root.children.size(), 1u);
  const Group& g = group_at(t.root, 0);
  ASSERT_EQ(g.children.size(), 2u);
  // The hidden rect paints nothing but keeps its geometry (it counts in the group's bounding box).
  EXPECT_FALSE(path_at(g, 0).fill || path_at(g, 0).stroke);
  EXPECT_FALSE(path_at(g, 0).path.empty());
  EXPECT_TRUE(path_at(g, 1).stroke_first);
  EXPECT_TRUE(path_at(g, 1).crisp_edges);
}

TEST(SvgTree, ResourcesInheritFromTheirOwnAncestors) {
  // clip-rule into a clipPath, color into stops (currentColor) and mask-type given in `style`: a resource takes
  // its inherited properties from where it is in the document, not from the element that refers to it.
  const Tree t = tree("<g clip-rule='evenodd' color='lime'><clipPath id='c'><rect width='5' height='5'/></clipPath>"
                      "<defs><linearGradient id='lg'><stop offset='0' stop-color='yellow'/>"
                      "<stop offset='1' stop-color='currentColor'/></linearGradient></defs></g>"
                      "<mask id='m' style='mask-type: alpha'><rect width='5' height='5' fill='white'/></mask>"
                      "<rect width='5' height='5' color='red' clip-path='url(#c)' mask='url(#m)' fill='url(#lg)'/>");
  const Group& g = group_at(t.root, 0);
  ASSERT_TRUE(g.clip && g.clip->content);
  EXPECT_EQ(path_at(*g.clip->content, 0).fill->rule, FillRule::EvenOdd);
  ASSERT_TRUE(g.mask);
  EXPECT_FALSE(g.mask->luminance);
  const Paint& fill = path_at(g, 0).fill->paint;
  ASSERT_EQ(fill.kind, Paint::Kind::Gradient);
  expect_rgba(fill.gradient->stops.at(1).color, 0, 255, 0);  // the g's colour, not the rect's red
}

TEST(SvgTree, TransformFromCssBeatsTheAttribute) {
  const Tree t = tree("<style>#s { transform: translate(10px, 5px) rotate(90deg) }</style>"
                      "<rect width='1' height='1' transform='translate(3)' style='transform: scale(2)'/>"
                      "<rect id='s' width='1' height='1' transform='translate(3)'/>"
                      "<rect width='1' height='1' transform='translate(3)' style='transform: rotate(90)'/>"
                      "<rect width='1' height='1' transform='translate(3)' style='transform: none'/>");
  ASSERT_EQ(t.root.children.size(), 4u);
  expect_affine(group_at(t.root, 0).transform, 2, 0, 0, 2, 0, 0);
  expect_affine(group_at(t.root, 1).transform, 0, 1, -1, 0, 10, 5);
  // CSS wants a unit on a non-zero angle: the declaration is dropped and the attribute applies.
  expect_affine(group_at(t.root, 2).transform, 1, 0, 0, 1, 3, 0);
  EXPECT_FALSE(t.warnings.empty());
  // transform: none wins over the attribute: the rect has no transform and needs no group.
  EXPECT_NE(std::get_if<PathNode>(&t.root.children.at(3).value), nullptr);
}

TEST(SvgTree, EmAndExFollowTheElementsFontSize) {
  const Tree t = tree("<g font-size='20'><rect x='1em' y='1ex' width='2em' height='2ex' stroke='black'"
                      " stroke-width='0.5em' stroke-dashoffset='1em'/>"
                      "<rect font-size='2em' width='1em' height='1em'/></g>",
                      "width='200' height='200' font-size='10'");
  const Group& g = group_at(t.root, 0);
  const PathNode& r = path_at(g, 0);
  const Rect b = r.path.bounds();
  EXPECT_NEAR(b.x0, 20, 1e-9);
  EXPECT_NEAR(b.y0, 10, 1e-9);  // ex: half the font size
  EXPECT_NEAR(b.x1, 60, 1e-9);
  EXPECT_NEAR(b.y1, 30, 1e-9);
  EXPECT_EQ(r.stroke->style.width, 10);
  EXPECT_EQ(r.stroke->style.dash_offset, 20);
  // font-size in em is the parent's; the rect's other lengths then use its own size (40).
  EXPECT_NEAR(path_at(g, 1).path.bounds().x1, 40, 1e-9);
}

TEST(SvgTree, OverflowInheritsFromTheDocumentOnAMarker) {
  // The UA style sheet hides overflow on markers; `inherit` takes the parent's value, which for the root is the
  // initial one, visible.
  const std::string body = "<marker id='m' overflow='inherit'><rect width='9' height='9'/></marker>"
                           "<path d='M 10 10 L 50 10' stroke='black' marker-start='url(#m)'/>";
  for (const std::string& root : {std::string("width='100' height='100'"),
                                  std::string("width='100' height='100' overflow='visible'")}) {
    const Tree t = tree(body, root);
    const Group& instances = group_at(group_at(t.root, 0), 1);
    EXPECT_FALSE(group_at(instances, 0).clip) << root;
  }
  const Tree hidden = tree(body, "width='100' height='100' overflow='hidden'");
  EXPECT_TRUE(group_at(group_at(group_at(hidden.root, 0), 1), 0).clip);
}

TEST(SvgTree, RootBackgroundColorFromCssOnly) {
  const Tree t = tree("<rect width='1' height='1'/>", "width='10' height='10' style='background-color: #0000ff80'");
  ASSERT_TRUE(t.background);
  expect_rgba(*t.background, 0, 0, 255, 0x80 / 255.0);
  EXPECT_FALSE(tree("", "width='10' height='10' background-color='blue'").background);  // not an attribute
  EXPECT_FALSE(tree("<g style='background-color: blue'/>").background);  // only the root's
}

TEST(SvgTree, NamespacesAreResolvedPerElement) {
  // The nearest xmlns declaration decides: a default namespace redeclared on a prefixed SVG element puts its
  // unprefixed children outside SVG.
  const Tree t = tree("<s:g xmlns='http://www.example.org/notsvg' xmlns:s='http://www.w3.org/2000/svg'>"
                      "<s:rect width='1' height='1' fill='lime'/><rect width='2' height='2' fill='red'/></s:g>"
                      "<g xmlns='http://www.w3.org/2000/svg'><rect width='3' height='3'/></g>");
  ASSERT_EQ(t.root.children.size(), 2u);
  const Group& g = group_at(t.root, 0);
  ASSERT_EQ(g.children.size(), 1u);
  expect_rgba(path_at(g, 0).fill->paint.color, 0, 255, 0);
  EXPECT_EQ(group_at(t.root, 1).children.size(), 1u);
}

TEST(SvgTree, SwitchPassesOverElementsThatAreNotGraphics) {
  const Tree t = tree("<switch><random/><linearGradient id='x'/><rect width='1' height='1' fill='lime'/>"
                      "<rect width='1' height='1' fill='red'/></switch>");
  const Group& s = group_at(t.root, 0);
  ASSERT_EQ(s.children.size(), 1u);
  expect_rgba(path_at(s, 0).fill->paint.color, 0, 255, 0);
}

TEST(SvgTree, InvalidValuesAreAsIfNotGiven) {
  const Tree t = tree("<g fill='red' stroke-width='3'>"
                      "<polygon points='0 0 10 0 10 10 5' fill='bad' stroke='blue' stroke-width='2mmx' opacity='0.1mm'"
                      " stroke-linecap='miter'/><path d='M 0 0 L 10 0 A 5 5 0 -1 0 1 1'/></g>");
  const Group& g = group_at(t.root, 0);
  ASSERT_EQ(g.children.size(), 2u);
  const PathNode& poly = path_at(g, 0);
  expect_rgba(poly.fill->paint.color, 255, 0, 0);
  EXPECT_EQ(poly.stroke->style.width, 3);
  EXPECT_EQ(poly.stroke->style.cap, LineCap::Butt);
  const Rect b = poly.path.bounds();
  EXPECT_EQ(b.y1, 10);  // the odd coordinate is dropped
  EXPECT_EQ(path_at(g, 1).path.verbs().size(), 2u);  // drawn up to the bad arc flag: M L
  EXPECT_EQ(t.warnings.size(), 6u);
}

}  // namespace
}  // namespace vraster::svg
