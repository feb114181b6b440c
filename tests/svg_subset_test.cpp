// Tests of the SVG subset: path data, colours, transforms, documents and rendering.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <string>

#include "svg_subset/svg.hpp"

namespace {

using vraster::Affine;
using vraster::Color;
using vraster::Error;
using vraster::FillRule;
using vraster::Path;
using vraster::Point;
using vraster::Verb;
using vraster::svg::Document;
using vraster::svg::parse_color;
using vraster::svg::parse_path_data;
using vraster::svg::parse_svg;
using vraster::svg::parse_transform;
using vraster::svg::parse_css_transform;
using vraster::svg::ParseError;
using vraster::svg::PathDataError;

// ---------------------------------------------------------------------------------------------------------------
// Helpers

Path parse_d(std::string_view d) {
  Path p;
  parse_path_data(d, p);
  return p;
}

/// The verbs of a path as letters: M L Q C Z.
std::string verbs(const Path& p) {
  std::string s;
  for (Verb v : p.verbs()) {
    switch (v) {
      case Verb::Move:
        s += 'M';
        break;
      case Verb::Line:
        s += 'L';
        break;
      case Verb::Quad:
        s += 'Q';
        break;
      case Verb::Cubic:
        s += 'C';
        break;
      case Verb::Close:
        s += 'Z';
        break;
    }
  }
  return s;
}

void expect_points(const Path& p, std::initializer_list<Point> expected) {
  const auto points = p.points();
  ASSERT_EQ(points.size(), expected.size());
  std::size_t i = 0;
  for (const Point& e : expected) {
    EXPECT_NEAR(points[i].x, e.x, 1e-9) << "point " << i;
    EXPECT_NEAR(points[i].y, e.y, 1e-9) << "point " << i;
    ++i;
  }
}

/// Parses `d`, expecting a PathDataError at `offset` whose message contains `text`; returns the partial path.
Path expect_path_error(std::string_view d, std::size_t offset, const std::string& text) {
  Path p;
  try {
    parse_path_data(d, p);
    ADD_FAILURE() << "no error for \"" << d << "\"";
  } catch (const PathDataError& e) {
    EXPECT_EQ(e.offset(), offset) << "for \"" << d << "\": " << e.message();
    EXPECT_NE(e.message().find(text), std::string::npos) << "message: " << e.message();
    EXPECT_NE(std::string(e.what()).find(e.message()), std::string::npos);
  }
  return p;
}

void expect_color(std::optional<Color> c, double r, double g, double b, double a = 1.0) {
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->r * 255.0, r, 1e-3);
  EXPECT_NEAR(c->g * 255.0, g, 1e-3);
  EXPECT_NEAR(c->b * 255.0, b, 1e-3);
  EXPECT_NEAR(c->a, a, 1e-6);
}

void expect_affine(const Affine& m, double a, double b, double c, double d, double e, double f) {
  EXPECT_NEAR(m.a, a, 1e-12);
  EXPECT_NEAR(m.b, b, 1e-12);
  EXPECT_NEAR(m.c, c, 1e-12);
  EXPECT_NEAR(m.d, d, 1e-12);
  EXPECT_NEAR(m.e, e, 1e-12);
  EXPECT_NEAR(m.f, f, 1e-12);
}

/// Parses SVG text expecting a ParseError; checks its position and that the message contains `text`.
void expect_svg_error(const std::string& svg, int line, int column, const std::string& text) {
  try {
    parse_svg(svg, "test.svg");
    ADD_FAILURE() << "no error for:\n" << svg;
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    EXPECT_NE(e.message().find(text), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()),
              "test.svg:" + std::to_string(line) + ":" + std::to_string(column) + ": " + e.message());
  }
}

/// Parses SVG text expecting no error and a warning at line:column whose text contains `text`.
void expect_svg_warning(const std::string& svg, int line, int column, const std::string& text) {
  const Document doc = parse_svg(svg, "test.svg");
  const std::string prefix = std::to_string(line) + ":" + std::to_string(column) + ": ";
  for (const std::string& w : doc.warnings) {
    if (w.rfind(prefix, 0) == 0 && w.find(text) != std::string::npos) return;
  }
  std::string all;
  for (const std::string& w : doc.warnings) all += "\n  " + w;
  ADD_FAILURE() << "no warning '" << prefix << "..." << text << "' among:" << all;
}

std::string svg10(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">" + body + "</svg>";
}

// ---------------------------------------------------------------------------------------------------------------
// Path data: commands

TEST(SvgPathData, MoveAndLineAbsoluteAndRelative) {
  Path p = parse_d("M 10 20 L 30 40 l 5 -5");
  EXPECT_EQ(verbs(p), "MLL");
  expect_points(p, {{10, 20}, {30, 40}, {35, 35}});

  // m after M is relative to the M's point (the Path merges the two consecutive moves).
  p = parse_d("m 10 20 l 5 5 M 1 1 m 2 2 L 0 0");
  EXPECT_EQ(verbs(p), "MLML");
  expect_points(p, {{10, 20}, {15, 25}, {3, 3}, {0, 0}});
}

TEST(SvgPathData, ImplicitRepetition) {
  // Extra pairs after M are L, after m are l.
  Path p = parse_d("M 1 2 3 4 5 6");
  EXPECT_EQ(verbs(p), "MLL");
  expect_points(p, {{1, 2}, {3, 4}, {5, 6}});
  p = parse_d("m 1 2 3 4 5 6");
  EXPECT_EQ(verbs(p), "MLL");
  expect_points(p, {{1, 2}, {4, 6}, {9, 12}});
  // Other commands repeat themselves.
  p = parse_d("M0 0 l 1 0 0 1 h 2 3 v 1,1");
  EXPECT_EQ(verbs(p), "MLLLLLL");
  expect_points(p, {{0, 0}, {1, 0}, {1, 1}, {3, 1}, {6, 1}, {6, 2}, {6, 3}});
  p = parse_d("M0 0 Q 1 1 2 0 3 -1 4 0");
  EXPECT_EQ(verbs(p), "MQQ");
  expect_points(p, {{0, 0}, {1, 1}, {2, 0}, {3, -1}, {4, 0}});
}

TEST(SvgPathData, HorizontalAndVertical) {
  const Path p = parse_d("M 1 2 H 5 V 7 h -1 v -2");
  EXPECT_EQ(verbs(p), "MLLLL");
  expect_points(p, {{1, 2}, {5, 2}, {5, 7}, {4, 7}, {4, 5}});
}

TEST(SvgPathData, CubicAbsoluteAndRelative) {
  const Path p = parse_d("M 0 0 C 1 2 3 4 5 6 c 1 1 2 2 3 3");
  EXPECT_EQ(verbs(p), "MCC");
  // Relative control points are relative to the segment's start, not to the previous control point.
  expect_points(p, {{0, 0}, {1, 2}, {3, 4}, {5, 6}, {6, 7}, {7, 8}, {8, 9}});
}

TEST(SvgPathData, SmoothCubicReflectsPreviousCubic) {
  Path p = parse_d("M0 0 C 1 1 2 1 3 0 S 5 -1 6 0");
  EXPECT_EQ(verbs(p), "MCC");
  expect_points(p, {{0, 0}, {1, 1}, {2, 1}, {3, 0}, {4, -1}, {5, -1}, {6, 0}});

  p = parse_d("M0 0 C 1 1 2 1 3 0 s 2 -1 3 0");
  expect_points(p, {{0, 0}, {1, 1}, {2, 1}, {3, 0}, {4, -1}, {5, -1}, {6, 0}});

  // A repeated S reflects the previous S.
  p = parse_d("M0 0 C 0 1 1 1 1 0 S 2 -1 2 0 3 1 4 0");
  EXPECT_EQ(verbs(p), "MCCC");
  expect_points(p, {{0, 0}, {0, 1}, {1, 1}, {1, 0}, {1, -1}, {2, -1}, {2, 0}, {2, 1}, {3, 1}, {4, 0}});
}

TEST(SvgPathData, SmoothCubicWithoutPreviousCubicUsesCurrentPoint) {
  Path p = parse_d("M 1 1 S 2 3 4 5");
  expect_points(p, {{1, 1}, {1, 1}, {2, 3}, {4, 5}});
  p = parse_d("M 0 0 L 1 1 s 1 2 3 4");
  expect_points(p, {{0, 0}, {1, 1}, {1, 1}, {2, 3}, {4, 5}});
  // A quadratic does not count.
  p = parse_d("M0 0 Q 1 1 2 0 S 3 1 4 0");
  expect_points(p, {{0, 0}, {1, 1}, {2, 0}, {2, 0}, {3, 1}, {4, 0}});
}

TEST(SvgPathData, QuadraticAbsoluteAndRelative) {
  const Path p = parse_d("M0 0 Q 1 1 2 0 q 1 1 2 0");
  EXPECT_EQ(verbs(p), "MQQ");
  expect_points(p, {{0, 0}, {1, 1}, {2, 0}, {3, 1}, {4, 0}});
}

TEST(SvgPathData, SmoothQuadraticReflection) {
  Path p = parse_d("M0 0 Q 1 1 2 0 T 4 0 t 2 0");
  EXPECT_EQ(verbs(p), "MQQQ");
  expect_points(p, {{0, 0}, {1, 1}, {2, 0}, {3, -1}, {4, 0}, {5, 1}, {6, 0}});
  // Without a previous quadratic the control point is the current point.
  p = parse_d("M 1 1 T 3 3");
  EXPECT_EQ(verbs(p), "MQ");
  expect_points(p, {{1, 1}, {1, 1}, {3, 3}});
  p = parse_d("M0 0 C 1 1 2 1 3 0 T 5 0");
  expect_points(p, {{0, 0}, {1, 1}, {2, 1}, {3, 0}, {3, 0}, {5, 0}});
}

TEST(SvgPathData, ArcAbsoluteAndRelative) {
  // Half circle of radius 1 from (0,0) to (2,0); sweep=1 goes through (1,-1) (angles increase, y down).
  Path p = parse_d("M0 0 A 1 1 0 0 1 2 0");
  ASSERT_GE(p.verbs().size(), 2u);
  std::string expected(p.verbs().size(), 'C');  // (not "M" + std::string(...): a GCC 12 -Wrestrict false positive)
  expected[0] = 'M';
  EXPECT_EQ(verbs(p), expected);
  EXPECT_NEAR(p.points().back().x, 2, 1e-9);
  EXPECT_NEAR(p.points().back().y, 0, 1e-9);
  EXPECT_NEAR(p.bounds().y0, -1, 1e-6);
  EXPECT_NEAR(p.bounds().y1, 0, 1e-6);

  p = parse_d("M0 0 A 1 1 0 0 0 2 0");
  EXPECT_NEAR(p.bounds().y0, 0, 1e-6);
  EXPECT_NEAR(p.bounds().y1, 1, 1e-6);

  p = parse_d("M 1 1 a 1 1 0 0 0 2 0");
  EXPECT_EQ(p.current_point(), (Point{3, 1}));
  EXPECT_NEAR(p.bounds().y1, 2, 1e-6);
}

TEST(SvgPathData, ArcLargeArcFlag) {
  // Quarter-circle chord of a unit circle: the small arc spans 1x1, the large one 2x2.
  const Path small = parse_d("M0 0 A 1 1 0 0 1 1 1");
  const Path large = parse_d("M0 0 A 1 1 0 1 1 1 1");
  EXPECT_NEAR(small.bounds().width(), 1, 1e-6);
  EXPECT_NEAR(small.bounds().height(), 1, 1e-6);
  EXPECT_NEAR(large.bounds().width(), 2, 1e-6);
  EXPECT_NEAR(large.bounds().height(), 2, 1e-6);
}

TEST(SvgPathData, CompactArcFlags) {
  // rx=1 ry=1 rotation=0 large=0 sweep=0 x=.5 y=.5
  const Path compact = parse_d("M0 0 a1 1 0 00.5.5");
  const Path spaced = parse_d("M 0 0 a 1 1 0 0 0 0.5 0.5");
  EXPECT_EQ(compact.current_point(), (Point{0.5, 0.5}));
  EXPECT_EQ(verbs(compact), verbs(spaced));
  ASSERT_EQ(compact.points().size(), spaced.points().size());
  for (std::size_t i = 0; i < compact.points().size(); ++i) EXPECT_EQ(compact.points()[i], spaced.points()[i]);

  // Flags followed directly by a signed number, and commas everywhere.
  const Path p = parse_d("M0,0A1,1,0,1,1-1,-1");
  EXPECT_EQ(p.current_point(), (Point{-1, -1}));
  EXPECT_NEAR(p.bounds().width(), 2, 1e-6);
}

TEST(SvgPathData, CompactNumbers) {
  expect_points(parse_d("M1e-3-2"), {{0.001, -2}});
  expect_points(parse_d("M.5.5"), {{0.5, 0.5}});
  expect_points(parse_d("M-.5e+2 1"), {{-50, 1}});
  expect_points(parse_d("M1.5.5"), {{1.5, 0.5}});
  expect_points(parse_d("M1E2,2e1"), {{100, 20}});
  expect_points(parse_d("M1.e1-0"), {{10, 0}});
  expect_points(parse_d("M+1+2"), {{1, 2}});
  expect_points(parse_d("M0-1-2-3"), {{0, -1}, {-2, -3}});
  // Too small for a double rounds to zero (only overflow is an error).
  expect_points(parse_d("M1e-999 5"), {{0, 5}});
}

TEST(SvgPathData, WhitespaceAndCommas) {
  const Path p = parse_d(" \t\r\n M 1 , 2\nL\t3,4 ,5 6 \n");
  EXPECT_EQ(verbs(p), "MLL");
  expect_points(p, {{1, 2}, {3, 4}, {5, 6}});
  EXPECT_TRUE(parse_d("").empty());
  EXPECT_TRUE(parse_d("   \n ").empty());
}

TEST(SvgPathData, CloseThenRelativeUsesSubpathStart) {
  Path p = parse_d("M 1 1 L 5 1 L 5 5 Z l 1 0");
  EXPECT_EQ(verbs(p), "MLLZML");
  expect_points(p, {{1, 1}, {5, 1}, {5, 5}, {1, 1}, {2, 1}});

  p = parse_d("M 1 1 L 5 1 z m 2 2 l 1 0");
  EXPECT_EQ(verbs(p), "MLZML");
  expect_points(p, {{1, 1}, {5, 1}, {3, 3}, {4, 3}});

  // Without Z, a relative moveto is relative to the current point.
  p = parse_d("M 1 1 L 5 5 m 1 1");
  expect_points(p, {{1, 1}, {5, 5}, {6, 6}});

  // The second subpath's start is used by its own Z.
  p = parse_d("M 0 0 L 1 0 Z M 10 10 L 11 10 Z l 0 1");
  EXPECT_EQ(p.current_point(), (Point{10, 11}));
}

// ---------------------------------------------------------------------------------------------------------------
// Path data: errors (offset, message, and the partial path SVG says to draw)

TEST(SvgPathDataError, MustBeginWithMoveto) {
  expect_path_error("L 1 2", 0, "path data must begin with a moveto");
  expect_path_error("  10 10", 2, "path data must begin with a moveto");
}

TEST(SvgPathDataError, UnexpectedCharacter) {
  const Path p = expect_path_error("M 1 2 X 3", 6, "unexpected character 'X'");
  expect_points(p, {{1, 2}});
  expect_path_error("M 1 2 L 3 4 #", 12, "unexpected character '#'");
}

TEST(SvgPathDataError, MissingNumber) {
  expect_path_error("M 1 2 L", 7, "expected a number after 'L'");
  expect_path_error("M 1 2 L x", 8, "expected a number after 'L'");
  expect_path_error("M", 1, "expected a number after 'M'");
}

TEST(SvgPathDataError, IncompleteCoordinateSetKeepsEarlierSegments) {
  Path p = expect_path_error("M 1 2 L 3 4 L 5", 15, "expected a number after 'L'");
  EXPECT_EQ(verbs(p), "ML");
  expect_points(p, {{1, 2}, {3, 4}});

  p = expect_path_error("M 1 2 C 1 2 3 4 5", 17, "6 numbers per segment, got 5");
  EXPECT_EQ(verbs(p), "M");

  // The second of two implicit sets is incomplete: the first one is kept.
  p = expect_path_error("M0 0 L 1 1 2", 12, "got 1");
  expect_points(p, {{0, 0}, {1, 1}});
}

TEST(SvgPathDataError, BadArcFlag) {
  Path p = expect_path_error("M0 0 A 1 1 0 2 0 1 1", 13, "arc flag must be 0 or 1");
  EXPECT_EQ(verbs(p), "M");
  // "0.5" is not a flag: the flag is the single character '0', then '.' is not one.
  expect_path_error("M0 0 a1 1 0 0.5 1 1", 13, "arc flag must be 0 or 1, found '.'");
  expect_path_error("M0 0 A 1 1 0", 12, "expected an arc flag after 'A'");
}

TEST(SvgPathDataError, NumberOutOfRange) {
  expect_path_error("M 1e999 0", 2, "number out of range");
  expect_path_error("M 0 0 L 1 -1e400", 10, "number out of range");
  // Finite numbers whose sum overflows.
  const Path p = expect_path_error("M 1e308 0 l 1e308 0", 12, "out of range");
  expect_points(p, {{1e308, 0}});
}

TEST(SvgPathDataError, TrailingCommaAndArgumentsAfterClose) {
  expect_path_error("M 1 2,", 6, "expected a number after ','");
  expect_path_error("M 0 0 Z 1 2", 8, "unexpected number after 'Z'");
  expect_path_error("M 0 0 L 1 1, Z", 13, "expected a number after ','");
}

TEST(SvgPathDataError, WhatIncludesOffset) {
  try {
    parse_d("M 0 0 L");
    FAIL();
  } catch (const PathDataError& e) {
    EXPECT_NE(std::string(e.what()).find("7"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Colours

TEST(SvgColor, Hex) {
  bool none = true;
  expect_color(parse_color("#f00", none), 255, 0, 0);
  EXPECT_FALSE(none);
  expect_color(parse_color("#aBc", none), 0xaa, 0xbb, 0xcc);
  expect_color(parse_color("#FF8000", none), 255, 128, 0);
  expect_color(parse_color("  #102030\n", none), 0x10, 0x20, 0x30);
  expect_color(parse_color("#10203080", none), 0x10, 0x20, 0x30, 128 / 255.0);
}

TEST(SvgColor, Named) {
  bool none = true;
  expect_color(parse_color("red", none), 255, 0, 0);
  expect_color(parse_color("CornflowerBlue", none), 100, 149, 237);
  expect_color(parse_color(" navy ", none), 0, 0, 128);
  expect_color(parse_color("aliceblue", none), 240, 248, 255);
  expect_color(parse_color("yellowgreen", none), 154, 205, 50);
  expect_color(parse_color("grey", none), 128, 128, 128);
  expect_color(parse_color("LightGoldenrodYellow", none), 250, 250, 210);
  expect_color(parse_color("transparent", none), 0, 0, 0, 0);
  EXPECT_FALSE(none);
}

TEST(SvgColor, RgbFunction) {
  bool none = true;
  expect_color(parse_color("rgb(255, 0, 128)", none), 255, 0, 128);
  expect_color(parse_color("rgb( 10 ,20,30 )", none), 10, 20, 30);
  expect_color(parse_color("RGB(100%, 50%, 0%)", none), 255, 127.5, 0);
  expect_color(parse_color("rgb(300, -5, 0)", none), 255, 0, 0);  // clamped, as CSS says
  expect_color(parse_color("rgba(0, 0, 255, 0.25)", none), 0, 0, 255, 0.25);
  EXPECT_FALSE(none);
}

TEST(SvgColor, RgbMixesNumbersAndPercentagesOnlyWithoutCommas) {
  // CSS Color 4: the legacy comma form takes three numbers or three percentages; the space form may mix them.
  bool none = true;
  EXPECT_FALSE(parse_color("rgba(0, 50%, 0, 0.5)", none).has_value());
  EXPECT_FALSE(parse_color("rgb(100%, 0, 0)", none).has_value());
  expect_color(parse_color("rgb(0 50% 0 / 0.5)", none), 0, 127.5, 0, 0.5);
  expect_color(parse_color("rgba(0%, 50%, 0%, 50%)", none), 0, 127.5, 0, 0.5);  // alpha may be either
}

TEST(SvgTransform, CssTransformSyntax) {
  // CSS Transforms 1: units on lengths and angles, commas between arguments, functions SVG lacks.
  Affine m;
  ASSERT_TRUE(parse_css_transform("translate(10px, 1in) rotate(0.25turn)", m));
  EXPECT_NEAR(m.a, 0, 1e-12);
  EXPECT_NEAR(m.b, 1, 1e-12);
  EXPECT_NEAR(m.e, 10, 1e-12);
  EXPECT_NEAR(m.f, 96, 1e-12);
  ASSERT_TRUE(parse_css_transform("scaleX(2) translateY(3px) skew(45deg)", m));
  EXPECT_NEAR(m.a, 2, 1e-12);
  EXPECT_NEAR(m.c, 2, 1e-12);  // scaleX(2) * skewX(45deg): tan 45 = 1, times 2
  EXPECT_NEAR(m.f, 3, 1e-12);
  ASSERT_TRUE(parse_css_transform("none", m));
  EXPECT_TRUE(m.is_identity());
  ASSERT_TRUE(parse_css_transform("rotate(0)", m));  // a bare zero needs no unit
  for (const char* bad : {"rotate(45)", "translate(10 20)", "translate(10, 20)", "scale(2px)", "translate(5%)",
                          "scale (2)", "matrix(1,0,0,1,0)", "", "skew(1deg, 2deg, 3deg)"}) {
    EXPECT_FALSE(parse_css_transform(bad, m)) << bad;
  }
}

TEST(SvgColor, None) {
  bool none = false;
  EXPECT_FALSE(parse_color("none", none).has_value());
  EXPECT_TRUE(none);
  EXPECT_FALSE(parse_color(" NONE ", none).has_value());
  EXPECT_TRUE(none);
  // is_none is reset by the next call.
  expect_color(parse_color("red", none), 255, 0, 0);
  EXPECT_FALSE(none);
}

TEST(SvgColor, Garbage) {
  for (const char* text : {"", "   ", "#", "#12", "#12345", "#ggg", "#fff f", "reddish", "red blue", "rgb(1,2)",
                           "rgb(1,2,3", "rgb(1,2,3,)", "rgb(a,b,c)", "rgb(1,2,3,4,5)", "12", "currentColor"}) {
    bool none = true;
    EXPECT_FALSE(parse_color(text, none).has_value()) << text;
    EXPECT_FALSE(none) << text;
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Transforms

TEST(SvgTransform, EachFunction) {
  Affine m;
  ASSERT_TRUE(parse_transform("matrix(1 2 3 4 5 6)", m));
  expect_affine(m, 1, 2, 3, 4, 5, 6);
  ASSERT_TRUE(parse_transform("translate(10)", m));
  expect_affine(m, 1, 0, 0, 1, 10, 0);
  ASSERT_TRUE(parse_transform("translate(10, -20)", m));
  expect_affine(m, 1, 0, 0, 1, 10, -20);
  ASSERT_TRUE(parse_transform("scale(2)", m));
  expect_affine(m, 2, 0, 0, 2, 0, 0);
  ASSERT_TRUE(parse_transform("scale(2 3)", m));
  expect_affine(m, 2, 0, 0, 3, 0, 0);
  ASSERT_TRUE(parse_transform("rotate(90)", m));
  expect_affine(m, 0, 1, -1, 0, 0, 0);
  ASSERT_TRUE(parse_transform("skewX(45)", m));
  expect_affine(m, 1, 0, 1, 1, 0, 0);
  ASSERT_TRUE(parse_transform("skewY(45)", m));
  expect_affine(m, 1, 1, 0, 1, 0, 0);
}

TEST(SvgTransform, RotateAboutPoint) {
  Affine m;
  ASSERT_TRUE(parse_transform("rotate(90 10 10)", m));
  const Point c = m.apply({10, 10});
  const Point q = m.apply({20, 10});
  EXPECT_NEAR(c.x, 10, 1e-12);
  EXPECT_NEAR(c.y, 10, 1e-12);
  EXPECT_NEAR(q.x, 10, 1e-12);
  EXPECT_NEAR(q.y, 20, 1e-12);
}

TEST(SvgTransform, ListsComposeLeftToRight) {
  Affine m;
  // "translate scale": the scale applies first.
  ASSERT_TRUE(parse_transform("translate(10 0) scale(2)", m));
  EXPECT_EQ(m.apply({1, 1}), (Point{12, 2}));
  ASSERT_TRUE(parse_transform("scale(2),translate(10 0)", m));
  EXPECT_EQ(m.apply({1, 1}), (Point{22, 2}));
  ASSERT_TRUE(parse_transform("  translate(1)scale(2) ,\n rotate ( 0 ) ", m));
  expect_affine(m, 2, 0, 0, 2, 1, 0);
  ASSERT_TRUE(parse_transform("translate(1e-3-2)", m));
  expect_affine(m, 1, 0, 0, 1, 0.001, -2);
  ASSERT_TRUE(parse_transform("", m));
  EXPECT_TRUE(m.is_identity());
}

TEST(SvgTransform, BadSyntax) {
  for (const char* text :
       {"translate(1 2 3)", "rotate(1 2)", "scale()", "foo(1)", "translate(1", "translate 1", "translate(1,)",
        "translate(,1)", "translate(1),", "matrix(1 2 3 4 5)", "translate(1e999)", "Translate(1)", "translate(1)x",
        "(1)", "skewX(1 2)", "matrix(1 2 3 4 5 6 7)", "translate(a)"}) {
    Affine m = Affine::translate(7, 8);
    EXPECT_FALSE(parse_transform(text, m)) << text;
    expect_affine(m, 1, 0, 0, 1, 7, 8);  // untouched on failure
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Documents

TEST(SvgDocument, SizeAndPlainPath) {
  const Document doc = parse_svg(svg10("<path d=\"M0 0 L10 0 L10 10 Z\"/>"));
  EXPECT_EQ(doc.width, 10);
  EXPECT_EQ(doc.height, 10);
  ASSERT_EQ(doc.items.size(), 1u);
  const auto& item = doc.items[0];
  EXPECT_TRUE(item.transform.is_identity());
  expect_color(item.color, 0, 0, 0);  // default fill black
  EXPECT_EQ(item.rule, FillRule::NonZero);
  EXPECT_EQ(verbs(item.path), "MLLZ");
  EXPECT_TRUE(doc.warnings.empty());
}

TEST(SvgDocument, ViewBoxMeetCentres) {
  // 10x10 user units into 200x100: scale 10, centred horizontally.
  Document doc = parse_svg(R"(<svg width="200" height="100px" viewBox="0 0 10 10"><path d="M0 0h1v1z"/></svg>)");
  EXPECT_EQ(doc.width, 200);
  EXPECT_EQ(doc.height, 100);
  ASSERT_EQ(doc.items.size(), 1u);
  expect_affine(doc.items[0].transform, 10, 0, 0, 10, 50, 0);

  doc = parse_svg(R"(<svg width="100" height="100" viewBox="5,5,10,10"><path d="M0 0h1v1z"/></svg>)");
  expect_affine(doc.items[0].transform, 10, 0, 0, 10, -50, -50);
}

TEST(SvgDocument, PreserveAspectRatio) {
  Document doc = parse_svg(
      R"(<svg width="200" height="100" viewBox="0 0 10 10" preserveAspectRatio="none"><path d="M0 0h1v1z"/></svg>)");
  expect_affine(doc.items[0].transform, 20, 0, 0, 10, 0, 0);
  doc = parse_svg(
      R"(<svg width="200" height="100" viewBox="0 0 10 10" preserveAspectRatio="xMinYMax slice"><path d="M0 0h1v1z"/></svg>)");
  expect_affine(doc.items[0].transform, 20, 0, 0, 20, 0, -100);
  doc = parse_svg(
      R"(<svg width="200" height="100" viewBox="0 0 10 10" preserveAspectRatio="xMaxYMid"><path d="M0 0h1v1z"/></svg>)");
  expect_affine(doc.items[0].transform, 10, 0, 0, 10, 100, 0);
}

TEST(SvgDocument, SizeFromViewBox) {
  Document doc = parse_svg(R"(<svg viewBox="0 0 30 40"/>)");
  EXPECT_EQ(doc.width, 30);
  EXPECT_EQ(doc.height, 40);
  // One size given: the other follows the viewBox aspect ratio.
  doc = parse_svg(R"(<svg width="60" viewBox="0 0 30 40"/>)");
  EXPECT_EQ(doc.width, 60);
  EXPECT_EQ(doc.height, 80);
  // Percentages have no viewport to refer to: the viewBox size is used, with a warning.
  doc = parse_svg(R"(<svg width="100%" height="100%" viewBox="0 0 30 40"/>)");
  EXPECT_EQ(doc.width, 30);
  EXPECT_EQ(doc.height, 40);
  EXPECT_EQ(doc.warnings.size(), 2u);
}

TEST(SvgDocument, SizeUnits) {
  const Document doc = parse_svg(R"(<svg width="1in" height="75pt"/>)");
  EXPECT_EQ(doc.width, 96);
  EXPECT_EQ(doc.height, 100);
  EXPECT_EQ(parse_svg(R"(<svg width="10.2" height="3"/>)").width, 11);  // rounded up
}

TEST(SvgDocument, MissingOrBadSize) {
  expect_svg_error("<svg><path d=\"M0 0\"/></svg>", 1, 1, "needs width and height");
  expect_svg_error("\n  <svg width=\"10\"/>", 2, 3, "needs a height");
  expect_svg_error(R"(<svg width="abc" height="10"/>)", 1, 13, "invalid width 'abc'");
  expect_svg_error(R"(<svg width="10" height="0"/>)", 1, 25, "height must be positive");
  expect_svg_error(R"(<svg width="100000" height="10"/>)", 1, 13, "too large");
  // An invalid viewBox is ignored (the size is known without it), as browsers do.
  expect_svg_warning(R"(<svg width="10" height="10" viewBox="0 0 -1 10"/>)", 1, 38, "invalid viewBox");
  expect_svg_warning(R"(<svg width="10" height="10" viewBox="0 0 1"/>)", 1, 38, "invalid viewBox");
  expect_svg_error(R"(<svg viewBox="0 0 1"/>)", 1, 1, "needs width and height");
}

TEST(SvgDocument, InheritanceThroughGroups) {
  const Document doc = parse_svg(svg10(R"svg(
    <g fill="red" fill-rule="evenodd" fill-opacity="0.5" transform="translate(10 0)">
      <g transform="scale(2)">
        <path d="M0 0h1v1z"/>
        <path fill="blue" fill-rule="nonzero" d="M0 0h1v1z"/>
      </g>
    </g>
    <path d="M0 0h1v1z"/>)svg"));
  ASSERT_EQ(doc.items.size(), 3u);
  expect_color(doc.items[0].color, 255, 0, 0, 0.5);
  EXPECT_EQ(doc.items[0].rule, FillRule::EvenOdd);
  expect_affine(doc.items[0].transform, 2, 0, 0, 2, 10, 0);
  expect_color(doc.items[1].color, 0, 0, 255, 0.5);
  EXPECT_EQ(doc.items[1].rule, FillRule::NonZero);
  // Outside the group: defaults again.
  expect_color(doc.items[2].color, 0, 0, 0, 1);
  EXPECT_TRUE(doc.items[2].transform.is_identity());
}

TEST(SvgDocument, StyleAttributeOverridesPresentationAttributes) {
  const Document doc = parse_svg(svg10(
      R"(<path fill="red" fill-rule="nonzero" style=" fill : #00f ; fill-rule:evenodd;fill-opacity: 50% " d="M0 0h1v1z"/>)"
      R"(<g style="fill:lime"><path d="M0 0h1v1z"/></g>)"));
  ASSERT_EQ(doc.items.size(), 2u);
  expect_color(doc.items[0].color, 0, 0, 255, 0.5);
  EXPECT_EQ(doc.items[0].rule, FillRule::EvenOdd);
  expect_color(doc.items[1].color, 0, 255, 0);
}

TEST(SvgDocument, NoneDisplayAndCurrentColor) {
  const Document doc = parse_svg(svg10(R"(
    <path fill="none" d="M0 0h1v1z"/>
    <g display="none"><path d="M0 0h1v1z"/></g>
    <g color="teal"><path fill="currentColor" d="M0 0h1v1z"/></g>)"));
  ASSERT_EQ(doc.items.size(), 1u);
  expect_color(doc.items[0].color, 0, 128, 128);
}

TEST(SvgDocument, NothingToDraw) {
  const Document doc = parse_svg(svg10(R"(
    <path d="M0 0 M 5 5"/>
    <path d=""/>
    <path/>
    <g visibility="hidden"><path d="M0 0h1v1z"/><path visibility="visible" fill="red" d="M0 0h1v1z"/></g>
    <path fill-opacity="0" d="M0 0h1v1z"/>)"));
  ASSERT_EQ(doc.items.size(), 1u);
  expect_color(doc.items[0].color, 255, 0, 0);
}

TEST(SvgDocument, PaintServersAndUnsupportedPropertiesWarn) {
  const Document doc = parse_svg(
      "<svg width=\"10\" height=\"10\">\n"
      "<path fill=\"url(#grad)\" d=\"M0 0h1v1z\"/>\n"
      "<path fill=\"url(#grad) lime\" d=\"M0 0h1v1z\"/>\n"
      "<path filter=\"url(#f)\" d=\"M0 0h1v1z\"/>\n"
      "<path filter=\"url(#f)\" d=\"M0 0h1v1z\"/>\n"
      "</svg>");
  // A missing paint server is none (with a warning), or the fallback colour when one is given (silently).
  ASSERT_EQ(doc.items.size(), 3u);
  expect_color(doc.items[0].color, 0, 255, 0);
  ASSERT_EQ(doc.warnings.size(), 2u);
  EXPECT_EQ(doc.warnings[0].rfind("2:13: no paint server with id 'grad'", 0), 0u) << doc.warnings[0];
  EXPECT_EQ(doc.warnings[1], "4:15: filter is not supported yet, ignored (reported once)");
}

TEST(SvgDocument, OpacityMultipliesWithWarningForGroups) {
  const Document doc =
      parse_svg(svg10("<g opacity=\"0.5\">\n<path opacity=\"0.5\" fill-opacity=\"0.8\" d=\"M0 0h1v1z\"/></g>"));
  ASSERT_EQ(doc.items.size(), 1u);
  expect_color(doc.items[0].color, 0, 0, 0, 0.2);
  EXPECT_TRUE(doc.warnings.empty());  // one child with one paint: multiplying is exact
  const Document two = parse_svg(svg10("<g opacity=\"0.5\"><path d=\"M0 0h1v1z\"/><path d=\"M0 0h1v1z\"/></g>"));
  ASSERT_EQ(two.items.size(), 2u);
  expect_color(two.items[1].color, 0, 0, 0, 0.5);
  ASSERT_EQ(two.warnings.size(), 1u);
  EXPECT_NE(two.warnings[0].find("group opacity is approximated"), std::string::npos) << two.warnings[0];
}

TEST(SvgDocument, MalformedPathDataPosition) {
  const std::string text =
      "<svg width=\"10\" height=\"10\">\n"
      "  <g>\n"
      "    <path d=\"M 1 2\n"
      "             L 3 x\"/>\n"
      "  </g>\n"
      "</svg>\n";
  // SVG: the path is drawn up to the first error, with a warning.
  expect_svg_warning(text, 4, 18, "path data: expected a number after 'L'");
  EXPECT_TRUE(parse_svg(text).items.empty());  // "M 1 2" alone draws nothing
  const Document doc = parse_svg(svg10("<path d=\"M 1 2 L 3 4 L 5 x\"/>"));
  ASSERT_EQ(doc.items.size(), 1u);
  EXPECT_EQ(verbs(doc.items[0].path), "ML");
}

TEST(SvgDocument, MalformedPathDataPositionAfterEntityAndCrLf) {
  // &#x4C; is 'L' (6 source bytes, 1 decoded); CR LF is 2 source bytes, 1 decoded.
  const std::string text = "<svg width=\"10\" height=\"10\">\r\n<path d=\"M 1 2\r\n&#x4C; 3 x\"/></svg>";
  expect_svg_warning(text, 3, 10, "expected a number after 'L'");
}

TEST(SvgDocument, MalformedXml) {
  expect_svg_error("<svg width=\"1\" height=\"1\">\n  <g>\n</svg>", 3, 3, "malformed XML");
  expect_svg_error("<svg width=\"1\" height=\"1\">\n<path d=\"M0 0/>\n", 2, 10, "malformed XML");
  expect_svg_error("", 1, 1, "malformed XML");
}

TEST(SvgDocument, RootMustBeSvg) { expect_svg_error("\n<html/>", 2, 1, "expected <svg>"); }

TEST(SvgDocument, BadAttributeValues) {
  // Invalid values are treated as not given, with a warning whose column points at the value's first character.
  expect_svg_warning(svg10("\n<path fill=\"blurple\" d=\"M0 0h1v1z\"/>"), 2, 13, "invalid fill 'blurple', ignored");
  expect_svg_warning(svg10("\n<g transform=\"rotate(1 2)\"/>"), 2, 15, "invalid transform 'rotate(1 2)'");
  expect_svg_warning(svg10("\n<path fill-rule=\"odd\" d=\"M0 0h1v1z\"/>"), 2, 18, "invalid fill-rule 'odd'");
  expect_svg_warning(svg10("\n<path fill-opacity=\"half\" d=\"M0 0h1v1z\"/>"), 2, 21, "invalid fill-opacity 'half'");
  // Inside a style attribute, the position is the declaration's value.
  expect_svg_warning(svg10("\n<path style=\"fill-rule: evenodd; fill:  bad\" d=\"M0 0h1v1z\"/>"), 2, 41,
                     "invalid fill 'bad'");
  expect_svg_warning(svg10("\n<rect width=\"1x\" height=\"1\"/>"), 2, 14, "invalid length for width: '1x'");
  // "As if not given": the fill stays the inherited one, the rule stays evenodd.
  const Document doc = parse_svg(svg10("<g fill=\"red\"><path fill=\"blurple\" fill-rule=\"evenodd\" "
                                       "style=\"fill-rule: odd\" d=\"M0 0h1v1z\"/></g>"));
  ASSERT_EQ(doc.items.size(), 1u);
  expect_color(doc.items[0].color, 255, 0, 0);
  EXPECT_EQ(doc.items[0].rule, vraster::FillRule::EvenOdd);
}

TEST(SvgDocument, UnsupportedElementWarning) {
  const Document doc = parse_svg(
      "<svg width=\"10\" height=\"10\">\n"
      "  <foreignObject x=\"1\">hi</foreignObject>\n"
      "  <defs><path d=\"M0 0h1v1z\"/></defs>\n"
      "  <path d=\"M0 0h1v1z\"/>\n"
      "</svg>");
  ASSERT_EQ(doc.warnings.size(), 1u);
  EXPECT_EQ(doc.warnings[0], "2:3: element <foreignObject> is not supported yet, ignored");
  EXPECT_EQ(doc.items.size(), 1u);  // defs are not drawn
}

TEST(SvgDocument, BasicShapes) {
  const Document doc = parse_svg(svg10(R"(
    <rect x="1" y="2" width="3" height="4"/>
    <rect x="1" y="2" width="4" height="4" rx="1"/>
    <circle cx="5" cy="5" r="2"/>
    <ellipse cx="5" cy="5" rx="3" ry="1"/>
    <polygon points="0,0 4,0 4,4"/>
    <polyline points="0 0 1 0 1 1"/>
    <line x1="0" y1="0" x2="5" y2="5"/>
    <rect width="0" height="5"/>
    <circle r="-1"/>)"));
  ASSERT_EQ(doc.items.size(), 6u);
  auto expect_bounds = [](const Path& p, double x0, double y0, double x1, double y1) {
    const vraster::Rect b = p.bounds();
    EXPECT_NEAR(b.x0, x0, 1e-6);
    EXPECT_NEAR(b.y0, y0, 1e-6);
    EXPECT_NEAR(b.x1, x1, 1e-6);
    EXPECT_NEAR(b.y1, y1, 1e-6);
  };
  expect_bounds(doc.items[0].path, 1, 2, 4, 6);
  expect_bounds(doc.items[1].path, 1, 2, 5, 6);
  EXPECT_GT(doc.items[1].path.verbs().size(), doc.items[0].path.verbs().size());  // rounded corners
  expect_bounds(doc.items[2].path, 3, 3, 7, 7);
  expect_bounds(doc.items[3].path, 2, 4, 8, 6);
  expect_bounds(doc.items[4].path, 0, 0, 4, 4);
  EXPECT_EQ(verbs(doc.items[4].path), "MLLZ");
  EXPECT_EQ(verbs(doc.items[5].path), "MLL");
  EXPECT_EQ(doc.warnings.size(), 1u);  // the negative radius
}

TEST(SvgDocument, NestingAndElementLimits) {
  std::string deep = "<svg width=\"1\" height=\"1\">";
  for (int i = 0; i < 300; ++i) deep += "<g>";
  for (int i = 0; i < 300; ++i) deep += "</g>";
  deep += "</svg>";
  // The 256th level is the 255th <g>, which starts at column 27 + 255 * 3.
  expect_svg_error(deep, 1, 27 + 255 * 3, "nested too deeply");
}

TEST(SvgDocument, TooManyElements) {
  std::string many = "<svg width=\"1\" height=\"1\">";
  many.reserve(4'100'000);
  for (int i = 0; i < 1'000'000; ++i) many += "<g/>";
  many += "</svg>";
  expect_svg_error(many, 1, 27 + 999'999 * 4, "too many elements");
}

TEST(SvgDocument, LoadSvg) {
  try {
    vraster::svg::load_svg("/nonexistent/dir/x.svg");
    FAIL();
  } catch (const ParseError&) {
    FAIL() << "a missing file is not a parse error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read SVG file '/nonexistent/dir/x.svg': No such file or directory");
  }

  const std::string path = ::testing::TempDir() + "svg_subset_test_load.svg";
  {
    std::ofstream out(path, std::ios::binary);
    out << "<svg width=\"7\" height=\"5\">\n<path d=\"M0 0 L\"/></svg>";
  }
  {
    // Bad path data is drawn up to the error, with a warning at its position.
    const Document partial = vraster::svg::load_svg(path);
    ASSERT_EQ(partial.warnings.size(), 1u);
    EXPECT_EQ(partial.warnings[0].rfind("2:16: path data", 0), 0u) << partial.warnings[0];
  }
  {
    std::ofstream out(path, std::ios::binary);
    out << "<svg width=\"7\">\n<path d=\"M0 0 L\"/></svg>";
  }
  try {
    vraster::svg::load_svg(path);
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":1:1: ", 0), 0u) << e.what();
  }
  {
    std::ofstream out(path, std::ios::binary);
    out << "<svg width=\"7\" height=\"5\"><path d=\"M0 0h1v1z\"/></svg>";
  }
  const Document doc = vraster::svg::load_svg(path);
  EXPECT_EQ(doc.width, 7);
  EXPECT_EQ(doc.height, 5);
  EXPECT_EQ(doc.items.size(), 1u);
  std::remove(path.c_str());
}

// ---------------------------------------------------------------------------------------------------------------
// Rendering

TEST(SvgRender, FillsItemsInOrder) {
  // Red square over the whole image, then a blue left half.
  const Document doc = parse_svg(R"(<svg width="4" height="4" viewBox="0 0 2 2">
      <rect width="2" height="2" fill="red"/><path d="M0 0H1V2H0z" fill="#0000ff"/></svg>)");
  vraster::Image image(doc.width, doc.height);
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, vraster::svg::RenderSettings{}, renderer);
  const auto* left = image.pixel(0, 0);
  const auto* right = image.pixel(3, 3);
  EXPECT_EQ(left[0], 0);
  EXPECT_EQ(left[2], 255);
  EXPECT_EQ(left[3], 255);
  EXPECT_EQ(right[0], 255);
  EXPECT_EQ(right[2], 0);
  EXPECT_EQ(right[3], 255);
}

TEST(SvgRender, RuleOverrideAndSixteenBits) {
  // Two nested squares, same direction: nonzero fills the hole, evenodd leaves it empty.
  const Document doc =
      parse_svg(R"(<svg width="6" height="6"><path fill-rule="nonzero" d="M0 0h6v6h-6z M2 2h2v2h-2z"/></svg>)");
  vraster::Image16 image(doc.width, doc.height);
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, vraster::svg::RenderSettings{}, renderer);
  EXPECT_EQ(image.pixel(3, 3)[3], 65535);

  vraster::Image16 hole(doc.width, doc.height);
  vraster::svg::RenderSettings settings;
  settings.rule_override = FillRule::EvenOdd;
  vraster::svg::render(doc, hole, settings, renderer);
  EXPECT_EQ(hole.pixel(3, 3)[3], 0);
  EXPECT_EQ(hole.pixel(0, 0)[3], 65535);
}

}  // namespace
