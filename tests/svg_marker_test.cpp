// Markers in the resolved tree (svg_subset/README.md): one instance group per vertex, placed, rotated and scaled
// as SVG says; checked without pixels.
#include <gtest/gtest.h>

#include <string>

#include "markers.hpp"
#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"

namespace vraster::svg {
namespace {

Tree tree(const std::string& body) {
  return parse_svg_tree("<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
                        "width=\"100\" height=\"100\">" + body + "</svg>");
}

void expect_affine(const Affine& m, const Affine& want) {
  EXPECT_NEAR(m.a, want.a, 1e-9);
  EXPECT_NEAR(m.b, want.b, 1e-9);
  EXPECT_NEAR(m.c, want.c, 1e-9);
  EXPECT_NEAR(m.d, want.d, 1e-9);
  EXPECT_NEAR(m.e, want.e, 1e-9);
  EXPECT_NEAR(m.f, want.f, 1e-9);
}

/// The marker instances of the first element: its group holds the path, then a group of instances.
const Group& instances(const Tree& t) {
  const Group& element = std::get<Group>(t.root.children.at(0).value);
  EXPECT_EQ(element.children.size(), 2u);
  EXPECT_TRUE(std::get_if<PathNode>(&element.children.at(0).value)) << "the path comes first";
  return std::get<Group>(element.children.at(1).value);
}

const Group& instance(const Group& all, std::size_t i) { return std::get<Group>(all.children.at(i).value); }

const std::string kMarker =
    "<marker id='m' markerWidth='4' markerHeight='6' refX='1' refY='2' orient='auto'>"
    "<rect width='4' height='6' fill='blue'/></marker>";

TEST(SvgMarker, StartMidEndOnAPolylineWithOrientAuto) {
  const Tree t = tree(kMarker +
                      "<polyline points='10,10 50,10 50,50' fill='none' stroke='black' stroke-width='2' "
                      "marker-start='url(#m)' marker-mid='url(#m)' marker-end='url(#m)'/>");
  const Group& all = instances(t);
  ASSERT_EQ(all.children.size(), 3u);
  // translate(vertex) rotate(angle) scale(stroke width) translate(-ref): right, the bisector of right and
  // down, down.
  const Affine ref = Affine::scale(2) * Affine::translate(-1, -2);
  expect_affine(instance(all, 0).transform, Affine::translate(10, 10) * Affine::rotate(0) * ref);
  expect_affine(instance(all, 1).transform, Affine::translate(50, 10) * Affine::rotate(45) * ref);
  expect_affine(instance(all, 2).transform, Affine::translate(50, 50) * Affine::rotate(90) * ref);
  // Each instance is clipped to the marker viewport and holds the content (no viewBox: identity).
  ASSERT_TRUE(instance(all, 0).clip);
  const Group& content = std::get<Group>(instance(all, 0).children.at(0).value);
  expect_affine(content.transform, Affine{});
  ASSERT_EQ(content.children.size(), 1u);
  for (const std::string& w : t.warnings) ADD_FAILURE() << "unexpected warning " << w;
}

TEST(SvgMarker, MarkerUnitsScaleByStrokeWidthOrNot) {
  const std::string user = "<marker id='u' markerUnits='userSpaceOnUse' markerWidth='4' markerHeight='6' refX='1' "
                           "refY='2'><rect width='4' height='6'/></marker>";
  const Tree t = tree(user + "<line x1='0' y1='0' x2='10' y2='0' stroke='black' stroke-width='5' marker-end='url(#u)'/>");
  const Group& all = instances(t);
  ASSERT_EQ(all.children.size(), 1u);
  expect_affine(instance(all, 0).transform, Affine::translate(10, 0) * Affine::translate(-1, -2));
  const Tree scaled = tree(kMarker + "<line x1='0' y1='0' x2='10' y2='0' stroke='black' stroke-width='5' "
                                     "marker-end='url(#m)'/>");
  expect_affine(instance(instances(scaled), 0).transform,
                Affine::translate(10, 0) * Affine::scale(5) * Affine::translate(-1, -2));
}

TEST(SvgMarker, AutoStartReverseTurnsOnlyTheStart) {
  const std::string m = "<marker id='r' orient='auto-start-reverse' markerUnits='userSpaceOnUse'>"
                        "<rect width='3' height='3'/></marker>";
  const Tree t = tree(m + "<path d='M 0 0 L 0 20' stroke='black' marker-start='url(#r)' marker-end='url(#r)'/>");
  const Group& all = instances(t);
  ASSERT_EQ(all.children.size(), 2u);
  expect_affine(instance(all, 0).transform, Affine::rotate(270));  // down reversed: up
  expect_affine(instance(all, 1).transform, Affine::translate(0, 20) * Affine::rotate(90));
}

TEST(SvgMarker, ViewBoxFixedAngleOverflowAndCssShorthand) {
  const std::string m = "<marker id='v' viewBox='0 0 10 10' markerWidth='5' markerHeight='5' refX='10' refY='0' "
                        "orient='0.25turn' markerUnits='userSpaceOnUse' style='overflow: visible'>"
                        "<rect width='10' height='10'/></marker>";
  const Tree t = tree(m + "<path d='M 30 40 L 90 40' stroke='black' style='marker: url(#v)'/>");
  const Group& all = instances(t);
  ASSERT_EQ(all.children.size(), 2u);  // start and end (no mid vertex)
  // refX 10 in viewBox units is 5 in the viewport (scale 0.5).
  expect_affine(instance(all, 0).transform, Affine::translate(30, 40) * Affine::rotate(90) * Affine::translate(-5, 0));
  EXPECT_FALSE(instance(all, 0).clip);  // overflow: visible
  expect_affine(std::get<Group>(instance(all, 0).children.at(0).value).transform, Affine::scale(0.5));
  // `marker` is a shorthand only in CSS, not a presentation attribute.
  const Tree attr = tree(m + "<path d='M 30 40 L 90 40' stroke='black' marker='url(#v)'/>");
  EXPECT_TRUE(std::get_if<PathNode>(&attr.root.children.at(0).value));
}

TEST(SvgMarker, ContentInheritsFromTheMarkersAncestorsNotFromThePath) {
  const Tree t = tree("<g fill='green'><marker id='m' markerUnits='userSpaceOnUse'><rect width='3' height='3'/>"
                      "</marker></g><path d='M 0 0 L 9 9' fill='red' stroke='black' marker-end='url(#m)'/>");
  const Group& content = std::get<Group>(instance(instances(t), 0).children.at(0).value);
  const PathNode& rect = std::get<PathNode>(content.children.at(0).value);
  ASSERT_TRUE(rect.fill);
  EXPECT_EQ(rect.fill->paint.color.g, Color::rgb8(0, 128, 0).g);
  EXPECT_EQ(rect.fill->paint.color.r, 0);
}

TEST(SvgMarker, ContextPaintsAreTheMarkedShapesPaints) {
  const std::string m = "<marker id='c' markerUnits='userSpaceOnUse'><rect width='3' height='3' "
                        "fill='context-stroke' stroke='context-fill'/></marker>";
  const Tree t = tree(m + "<path d='M 0 0 L 9 9' fill='lime' stroke='blue' marker-end='url(#c)'/>"
                          "<path d='M 0 0 L 9 9' fill='red' stroke='yellow' marker-end='url(#c)'/>");
  for (std::size_t i = 0; i < 2; ++i) {
    const Group& element = std::get<Group>(t.root.children.at(i).value);
    const Group& all = std::get<Group>(element.children.at(1).value);
    const Group& content = std::get<Group>(instance(all, 0).children.at(0).value);
    const PathNode& rect = std::get<PathNode>(content.children.at(0).value);
    ASSERT_TRUE(rect.fill && rect.stroke);
    EXPECT_EQ(rect.fill->paint.color.b, i == 0 ? 1.f : 0.f);    // blue, then yellow
    EXPECT_EQ(rect.stroke->paint.color.r, i == 0 ? 0.f : 1.f);  // lime, then red
  }
}

TEST(SvgMarker, ContextPaintsInUseAreTheUsesPaints) {
  const Tree t = tree("<defs><rect id='r' width='3' height='3' fill='context-stroke' stroke='context-fill'/></defs>"
                      "<use href='#r' fill='blue' stroke='lime'/><rect width='3' height='3' fill='context-fill'/>");
  const Group& use = std::get<Group>(t.root.children.at(0).value);
  const PathNode& rect = std::get<PathNode>(use.children.at(0).value);
  ASSERT_TRUE(rect.fill && rect.stroke);
  EXPECT_EQ(rect.fill->paint.color.g, 1.f);    // lime
  EXPECT_EQ(rect.stroke->paint.color.b, 1.f);  // blue
  // No context element: context-fill is none; the rect paints nothing (it stays for bounding boxes).
  ASSERT_EQ(t.root.children.size(), 2u);
  const PathNode& plain = std::get<PathNode>(t.root.children.at(1).value);
  EXPECT_FALSE(plain.fill || plain.stroke);
}

/// The first PathNode below `g`, depth first.
const PathNode* first_path(const Group& g) {
  for (const Node& child : g.children) {
    if (const PathNode* p = std::get_if<PathNode>(&child.value)) return p;
    if (const Group* sub = std::get_if<Group>(&child.value)) {
      if (const PathNode* p = first_path(*sub)) return p;
    }
  }
  return nullptr;
}

TEST(SvgMarker, ContextServersArePlacedInTheUsesSpaceAndBox) {
  const Tree t = tree("<pattern id='p' patternUnits='userSpaceOnUse' width='4' height='4'><rect width='2' height='2'/>"
                      "</pattern><defs><g id='g'><rect x='10' y='20' width='30' height='40' "
                      "transform='translate(5 0) scale(2)' fill='context-fill' stroke='context-stroke'/></g></defs>"
                      "<use href='#g' x='1' y='2' transform='rotate(30)' fill='url(#p)' stroke='green'/>");
  const PathNode* rect = first_path(t.root);
  ASSERT_TRUE(rect && rect->fill && rect->stroke);
  const Paint& fill = rect->fill->paint;
  ASSERT_EQ(fill.kind, Paint::Kind::Pattern);
  EXPECT_FALSE(fill.from_context);
  // The use's user space (its transform, before translate(x, y)) into the rect's: translate(1 2) translate(5 0)
  // scale(2), inverted.
  ASSERT_TRUE(fill.context);
  expect_affine(fill.context->space, Affine{0.5, 0, 0, 0.5, -3, -1});
  EXPECT_NEAR(fill.context->box.x0, 26, 1e-9);
  EXPECT_NEAR(fill.context->box.y0, 42, 1e-9);
  EXPECT_NEAR(fill.context->box.x1, 86, 1e-9);
  EXPECT_NEAR(fill.context->box.y1, 122, 1e-9);
  // A colour needs no space.
  EXPECT_EQ(rect->stroke->paint.kind, Paint::Kind::Color);
  EXPECT_FALSE(rect->stroke->paint.context);
}

TEST(SvgMarker, ContextServersArePlacedInTheMarkedShapesSpaceAndBox) {
  const Tree t = tree("<linearGradient id='lg'><stop offset='0' stop-color='red'/><stop offset='1' stop-color='blue'/>"
                      "</linearGradient><marker id='m' markerUnits='userSpaceOnUse' refX='1' refY='1'>"
                      "<rect width='3' height='3' fill='context-fill'/></marker>"
                      "<path d='M 10 20 L 50 80' fill='url(#lg)' stroke='black' marker-end='url(#m)'/>");
  const PathNode* rect = first_path(instance(instances(t), 0));
  ASSERT_TRUE(rect && rect->fill);
  const Paint& fill = rect->fill->paint;
  ASSERT_EQ(fill.kind, Paint::Kind::Gradient);
  ASSERT_TRUE(fill.context);
  expect_affine(fill.context->space, Affine::translate(-49, -79));  // the instance sits at translate(49 79)
  EXPECT_EQ(fill.context->box.x0, 10);
  EXPECT_EQ(fill.context->box.y0, 20);
  EXPECT_EQ(fill.context->box.x1, 50);
  EXPECT_EQ(fill.context->box.y1, 80);
}

TEST(SvgMarker, AMarkerIsLeftOutInsideItsOwnContent) {
  // The marker's content carries markers of its own (here the marker itself): a loop if they were expanded.
  const Tree t = tree("<marker id='m' markerUnits='userSpaceOnUse' overflow='visible'><path d='M 0 0 L 2 2' "
                      "stroke='black' marker-start='url(#m)' marker-end='url(#m)'/></marker>"
                      "<path d='M 0 0 L 9 9' stroke='black' marker-start='url(#m)'/>");
  const Group& all = instances(t);
  ASSERT_EQ(all.children.size(), 1u);
  const Group& content = std::get<Group>(instance(all, 0).children.at(0).value);
  ASSERT_EQ(content.children.size(), 1u);
  EXPECT_TRUE(std::get_if<PathNode>(&content.children[0].value));  // the path alone, no marker group
}

TEST(SvgMarker, MarkersNestUntilAMarkerComesBack) {
  // a's content has b at its end; b's content has a (being built: left out) and c; c's content has b (left out).
  const Tree t = tree(
      "<marker id='a' markerUnits='userSpaceOnUse'><path d='M 0 0 L 2 0' stroke='black' marker-end='url(#b)'/></marker>"
      "<marker id='b' markerUnits='userSpaceOnUse'><path d='M 0 0 L 2 0' stroke='black' marker-start='url(#a)' "
      "marker-end='url(#c)'/></marker>"
      "<marker id='c' markerUnits='userSpaceOnUse'><path d='M 0 0 L 2 0' stroke='black' marker-end='url(#b)'/></marker>"
      "<path d='M 0 0 L 9 0' stroke='black' marker-end='url(#a)'/>");
  auto content_of = [](const Group& inst) -> const Group& { return std::get<Group>(inst.children.at(0).value); };
  // The marker content of a marked path: its element group holds the path, then the instances.
  auto nested = [&](const Group& content) -> const Group* {
    const Group* element = std::get_if<Group>(&content.children.at(0).value);
    if (!element) return nullptr;  // a bare path: no markers
    return &std::get<Group>(element->children.at(1).value);
  };
  const Group& a = content_of(instance(instances(t), 0));
  const Group* in_a = nested(a);
  ASSERT_NE(in_a, nullptr);
  ASSERT_EQ(in_a->children.size(), 1u);  // b at the end
  const Group* in_b = nested(content_of(instance(*in_a, 0)));
  ASSERT_NE(in_b, nullptr);
  ASSERT_EQ(in_b->children.size(), 1u);  // c only: a is being built
  const Group& c = content_of(instance(*in_b, 0));
  EXPECT_EQ(nested(c), nullptr);  // b is being built: c's path has no markers
}

TEST(SvgMarker, AUseInsideAMarkerMayInstanceTheMarkedShape) {
  // The marker instances the shape it marks: not a use loop (marker content is drawn apart), and the marker
  // is left out inside itself.
  const Tree t = tree("<marker id='m' markerUnits='userSpaceOnUse'><use href='#p'/></marker>"
                      "<path id='p' d='M 0 0 L 9 0' stroke='black' marker-end='url(#m)'/>");
  EXPECT_TRUE(t.warnings.empty()) << t.warnings.front();
  const Group& all = instances(t);
  ASSERT_EQ(all.children.size(), 1u);
  const Group& content = std::get<Group>(instance(all, 0).children.at(0).value);
  const Group& use = std::get<Group>(content.children.at(0).value);
  EXPECT_TRUE(std::get_if<PathNode>(&use.children.at(0).value));  // the path, without markers
}

TEST(SvgMarker, PaintOrderPutsMarkersFirstOrBetween) {
  const std::string m = "<marker id='m' markerUnits='userSpaceOnUse'><rect width='3' height='3'/></marker>";
  const Tree first = tree(m + "<path d='M 0 0 L 9 9 L 0 9' fill='red' stroke='black' paint-order='markers' "
                              "marker-end='url(#m)'/>");
  const Group& a = std::get<Group>(first.root.children.at(0).value);
  ASSERT_EQ(a.children.size(), 2u);
  EXPECT_TRUE(std::get_if<Group>(&a.children[0].value));
  const Tree between = tree(m + "<path d='M 0 0 L 9 9 L 0 9' fill='red' stroke='black' "
                                "paint-order='stroke markers' marker-end='url(#m)'/>");
  const Group& b = std::get<Group>(between.root.children.at(0).value);
  ASSERT_EQ(b.children.size(), 3u);  // stroke, markers, fill
  const PathNode& stroke = std::get<PathNode>(b.children[0].value);
  const PathNode& fill = std::get<PathNode>(b.children[2].value);
  EXPECT_TRUE(stroke.stroke && !stroke.fill);
  EXPECT_TRUE(fill.fill && !fill.stroke);
}

TEST(SvgMarker, VertexAnglesOnCurvesClosedPathsAndZeroLengthSegments) {
  Path p;
  p.move_to(0, 0).line_to(10, 0).line_to(10, 0).line_to(10, 10).close();
  const auto v = detail::marker_vertices(p);
  ASSERT_EQ(v.size(), 5u);  // start, three segment ends, the closing vertex
  EXPECT_EQ(v[0].kind, detail::MarkerVertex::Kind::Start);
  EXPECT_NEAR(v[0].angle, 0, 1e-9);
  EXPECT_NEAR(v[1].angle, 45, 1e-9);  // the zero-length segment after it takes the next direction
  EXPECT_NEAR(v[2].angle, 45, 1e-9);
  EXPECT_NEAR(v[3].angle, 90 + 67.5, 1e-9);  // down, then back along the diagonal to the start (225)
  EXPECT_EQ(v[4].kind, detail::MarkerVertex::Kind::End);
  EXPECT_NEAR(v[4].angle, 225, 1e-9);  // the last vertex looks only backwards
  Path curve;
  curve.move_to(0, 0).cubic_to({0, 0}, {10, 10}, {20, 10});
  const auto c = detail::marker_vertices(curve);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].angle, 45, 1e-9);  // the first control point equals the start: the second one counts
  EXPECT_NEAR(c[1].angle, 0, 1e-9);
}

}  // namespace
}  // namespace vraster::svg
