// Tests of strokes in the SVG subset: the stroke properties (attributes, style, inheritance, invalid values),
// paint order, rendering through the stroker, and hairline mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "svg_subset/svg.hpp"
#include "vraster/lines.hpp"
#include "vraster/stroke.hpp"

namespace {

using vraster::Color;
using vraster::HairlineMode;
using vraster::IPoint;
using vraster::LineCap;
using vraster::LineJoin;
using vraster::Verb;
using vraster::svg::Document;
using vraster::svg::DrawItem;
using vraster::svg::parse_svg;
using vraster::svg::ParseError;
using vraster::svg::RenderSettings;

std::string svg10(const std::string& body) { return "<svg width=\"10\" height=\"10\">" + body + "</svg>"; }

void expect_rgba(const Color& c, double r, double g, double b, double a = 1.0) {
  EXPECT_NEAR(c.r, r / 255.0, 1e-6);
  EXPECT_NEAR(c.g, g / 255.0, 1e-6);
  EXPECT_NEAR(c.b, b / 255.0, 1e-6);
  EXPECT_NEAR(c.a, a, 1e-6);
}

/// The only stroke item of a document (fails the test when there is not exactly one).
const DrawItem& only_stroke(const Document& doc) {
  static const DrawItem kNone;
  const auto n = std::count_if(doc.items.begin(), doc.items.end(), [](const DrawItem& i) { return i.is_stroke(); });
  EXPECT_EQ(n, 1);
  for (const DrawItem& item : doc.items) {
    if (item.is_stroke()) return item;
  }
  return kNone;
}


/// Pixels with non-zero alpha, sorted (y, then x).
template <class T>
std::vector<IPoint> painted(const vraster::BasicImage<T>& image) {
  std::vector<IPoint> out;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.pixel(x, y)[3] != 0) out.push_back({x, y});
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------------
// Properties

TEST(SvgStroke, DefaultsWhenOnlyStrokeIsGiven) {
  const Document doc = parse_svg(svg10(R"(<rect width="4" height="4" stroke="red"/>)"));
  ASSERT_EQ(doc.items.size(), 2u);
  EXPECT_TRUE(doc.items[0].is_fill());  // fill first (paint-order normal), then stroke
  EXPECT_TRUE(doc.items[1].is_stroke());
  const DrawItem& s = doc.items[1];
  expect_rgba(s.color, 255, 0, 0);
  EXPECT_EQ(s.stroke.width, 1);
  EXPECT_EQ(s.stroke.cap, LineCap::Butt);
  EXPECT_EQ(s.stroke.join, LineJoin::Miter);
  EXPECT_EQ(s.stroke.miter_limit, 4);
  EXPECT_TRUE(s.stroke.dashes.empty());
  EXPECT_EQ(s.stroke.dash_offset, 0);
  EXPECT_TRUE(doc.warnings.empty());
}

TEST(SvgStroke, NoStrokeByDefault) {
  const Document doc = parse_svg(svg10(R"(<rect width="4" height="4" stroke-width="3"/>)"));
  ASSERT_EQ(doc.items.size(), 1u);
  EXPECT_TRUE(doc.items[0].is_fill());
}

TEST(SvgStroke, AllPropertiesAsAttributes) {
  const Document doc = parse_svg(svg10(
      R"(<path fill="none" d="M1 1L5 5" stroke="#00f" stroke-width="3" stroke-linecap="round" stroke-linejoin="bevel"
         stroke-miterlimit="2.5" stroke-dasharray="1, 2 3" stroke-dashoffset="1.5" stroke-opacity="0.5"
         opacity="0.5"/>)"));
  ASSERT_EQ(doc.items.size(), 1u);
  const DrawItem& s = doc.items[0];
  ASSERT_TRUE(s.is_stroke());
  expect_rgba(s.color, 0, 0, 255, 0.25);
  EXPECT_EQ(s.stroke.width, 3);
  EXPECT_EQ(s.stroke.cap, LineCap::Round);
  EXPECT_EQ(s.stroke.join, LineJoin::Bevel);
  EXPECT_EQ(s.stroke.miter_limit, 2.5);
  EXPECT_EQ(s.stroke.dashes, (std::vector<double>{1, 2, 3}));  // odd count: the stroker repeats it
  EXPECT_EQ(s.stroke.dash_offset, 1.5);
  EXPECT_TRUE(doc.warnings.empty());
}

TEST(SvgStroke, AllPropertiesInStyleOverrideAttributes) {
  const Document doc = parse_svg(svg10(
      R"(<path fill="none" d="M1 1L5 5" stroke="red" stroke-width="3" stroke-linecap="round"
         style="stroke: lime; Stroke-Width: 2px; stroke-linecap: square; stroke-linejoin: round;
                stroke-miterlimit: 8; stroke-dasharray: 4px 2; stroke-dashoffset: -1; stroke-opacity: 50%"/>)"));
  const DrawItem& s = only_stroke(doc);
  expect_rgba(s.color, 0, 255, 0, 0.5);
  EXPECT_EQ(s.stroke.width, 2);
  EXPECT_EQ(s.stroke.cap, LineCap::Square);
  EXPECT_EQ(s.stroke.join, LineJoin::Round);
  EXPECT_EQ(s.stroke.miter_limit, 8);
  EXPECT_EQ(s.stroke.dashes, (std::vector<double>{4, 2}));
  EXPECT_EQ(s.stroke.dash_offset, -1);
}

TEST(SvgStroke, InheritedThroughGroups) {
  const Document doc = parse_svg(svg10(R"(
    <g stroke="blue" stroke-width="2" stroke-linejoin="round" stroke-dasharray="3 1" color="#ff0000">
      <g stroke-linecap="round">
        <path fill="none" d="M0 0L5 5"/>
        <path fill="none" d="M0 0L5 5" stroke="currentColor" stroke-dasharray="none" stroke-width="inherit"/>
      </g>
      <path fill="none" d="M0 0L5 5" stroke="none"/>
      <line x1="0" y1="0" x2="3" y2="0"/>
    </g>)"));
  ASSERT_EQ(doc.items.size(), 3u);
  for (const DrawItem& item : doc.items) EXPECT_TRUE(item.is_stroke());
  expect_rgba(doc.items[0].color, 0, 0, 255);
  EXPECT_EQ(doc.items[0].stroke.width, 2);
  EXPECT_EQ(doc.items[0].stroke.cap, LineCap::Round);
  EXPECT_EQ(doc.items[0].stroke.join, LineJoin::Round);
  EXPECT_EQ(doc.items[0].stroke.dashes, (std::vector<double>{3, 1}));
  expect_rgba(doc.items[1].color, 255, 0, 0);  // currentColor
  EXPECT_TRUE(doc.items[1].stroke.dashes.empty());
  EXPECT_EQ(doc.items[1].stroke.width, 2);
  // The <line> is outside the inner group: butt caps again.
  EXPECT_EQ(doc.items[2].stroke.cap, LineCap::Butt);
  EXPECT_EQ(doc.items[2].stroke.width, 2);
}

TEST(SvgStroke, StrokeWidthUnitsAndPercentages) {
  // No viewBox: percentages refer to the normalized diagonal sqrt((30^2 + 40^2) / 2).
  const Document doc = parse_svg(R"(<svg width="30" height="40">
      <path d="M0 0L1 1" fill="none" stroke="red" stroke-width="10%"/>
      <path d="M0 0L1 1" fill="none" stroke="red" stroke-width="3pt" stroke-dasharray="1in, 50%" stroke-dashoffset="1mm"/>
    </svg>)");
  ASSERT_EQ(doc.items.size(), 2u);
  EXPECT_NEAR(doc.items[0].stroke.width, 0.1 * std::sqrt(1250.0), 1e-9);
  EXPECT_NEAR(doc.items[1].stroke.width, 4, 1e-9);
  ASSERT_EQ(doc.items[1].stroke.dashes.size(), 2u);
  EXPECT_NEAR(doc.items[1].stroke.dashes[0], 96, 1e-9);
  EXPECT_NEAR(doc.items[1].stroke.dashes[1], 0.5 * std::sqrt(1250.0), 1e-9);
  EXPECT_NEAR(doc.items[1].stroke.dash_offset, 96 / 25.4, 1e-9);
}

TEST(SvgStroke, InvisibleStrokesGiveNoItem) {
  const Document doc = parse_svg(svg10(R"(
    <path fill="none" d="M0 0L5 5" stroke="red" stroke-width="0"/>
    <path fill="none" d="M0 0L5 5" stroke="red" stroke-opacity="0"/>
    <path fill="none" d="M0 0L5 5" stroke="red" visibility="hidden"/>
    <path fill="none" d="M0 0L5 5" stroke="red" display="none"/>
    <path fill="none" d="M0 0" stroke="red"/>
    <rect width="0" height="5" stroke="red"/>)"));
  EXPECT_TRUE(doc.items.empty());
}

TEST(SvgStroke, OutOfRangeValuesAreIgnoredWithWarnings) {
  const Document doc = parse_svg(
      "<svg width=\"10\" height=\"10\">\n"
      "<g stroke=\"red\" stroke-width=\"3\" stroke-miterlimit=\"6\" stroke-dasharray=\"2 2\">\n"
      "<path d=\"M0 0L5 5\" fill=\"none\" stroke-width=\"-1\"/>\n"
      "<path d=\"M0 0L5 5\" fill=\"none\" stroke-miterlimit=\"0.5\"/>\n"
      "<path d=\"M0 0L5 5\" fill=\"none\" stroke-dasharray=\"1 -2\"/>\n"
      "<path d=\"M0 0L5 5\" fill=\"none\" stroke-linejoin=\"miter-clip\" style=\"stroke-linejoin: arcs\"/>\n"
      "<path d=\"M0 0L5 5\" fill=\"none\" stroke-linejoin=\"miter-clip\"/>\n"
      "</g></svg>");
  ASSERT_EQ(doc.items.size(), 5u);
  EXPECT_EQ(doc.items[0].stroke.width, 3);  // negative width: the inherited value stays
  EXPECT_EQ(doc.items[1].stroke.miter_limit, 6);
  EXPECT_TRUE(doc.items[2].stroke.dashes.empty());  // a negative dash: solid
  EXPECT_EQ(doc.items[3].stroke.join, LineJoin::Miter);  // arcs: not supported, its SVG 2 fallback miter
  EXPECT_EQ(doc.items[4].stroke.join, LineJoin::MiterClip);
  ASSERT_EQ(doc.warnings.size(), 4u);
  EXPECT_EQ(doc.warnings[0].rfind("3:46: invalid stroke-width '-1', ignored", 0), 0u) << doc.warnings[0];
  EXPECT_EQ(doc.warnings[1].rfind("4:51: invalid stroke-miterlimit '0.5', ignored", 0), 0u) << doc.warnings[1];
  EXPECT_EQ(doc.warnings[2].rfind("5:50: negative value in stroke-dasharray", 0), 0u) << doc.warnings[2];
  EXPECT_NE(doc.warnings[3].find("arcs"), std::string::npos) << doc.warnings[3];
}

TEST(SvgStroke, MalformedValuesAreIgnoredWithWarnings) {
  // SVG: an invalid value is treated as if it were not given; the warning names it with its line:column.
  auto check = [](const std::string& attrs, const std::string& warning) {
    const vraster::svg::Document doc = vraster::svg::parse_svg(
        "<svg width=\"10\" height=\"10\">\n<path d=\"M0 0L5 5\" stroke=\"red\" " + attrs + "/></svg>");
    ASSERT_EQ(doc.warnings.size(), 1u) << attrs;
    EXPECT_EQ(doc.warnings[0].rfind(warning, 0), 0u) << doc.warnings[0];
    ASSERT_EQ(doc.items.size(), 2u) << attrs;  // the default fill (black) and the red stroke
    const vraster::StrokeStyle& s = doc.items[1].stroke;
    EXPECT_EQ(s.width, 1);  // every property at its initial value
    EXPECT_EQ(s.cap, vraster::LineCap::Butt);
    EXPECT_EQ(s.join, LineJoin::Miter);
    EXPECT_EQ(s.miter_limit, 4);
    EXPECT_TRUE(s.dashes.empty());
    EXPECT_EQ(s.dash_offset, 0);
    EXPECT_FLOAT_EQ(doc.items[1].color.a, 1.0f);
  };
  check("stroke-width=\"wide\"", "2:47: invalid stroke-width 'wide', ignored");
  check("stroke-linecap=\"miter\"", "2:49: invalid stroke-linecap 'miter', ignored");
  check("stroke-linejoin=\"sharp\"", "2:50: invalid stroke-linejoin 'sharp', ignored");
  check("stroke-miterlimit=\"4px\"", "2:52: invalid stroke-miterlimit '4px', ignored");
  check("stroke-opacity=\"half\"", "2:49: invalid stroke-opacity 'half', ignored");
  check("stroke-dashoffset=\"x\"", "2:52: invalid stroke-dashoffset 'x', ignored");
  check("stroke-dasharray=\"1 2 x\"", "2:51: invalid stroke-dasharray '1 2 x', ignored");
  check("stroke-dasharray=\"1,,2\"", "2:51: invalid stroke-dasharray '1,,2', ignored");
  check("stroke-dasharray=\"1, 2,\"", "2:51: invalid stroke-dasharray '1, 2,', ignored");
  check("stroke-dasharray=\"\"", "2:51: invalid stroke-dasharray '', ignored");
  // An invalid stroke colour: not given, so the stroke is none (the initial value) and only the fill is drawn.
  const vraster::svg::Document doc =
      vraster::svg::parse_svg("<svg width=\"10\" height=\"10\">\n<path d=\"M0 0L5 5\" stroke=\"nocolour\"/></svg>");
  ASSERT_EQ(doc.warnings.size(), 1u);
  EXPECT_EQ(doc.warnings[0], "2:28: invalid stroke 'nocolour', ignored");
  ASSERT_EQ(doc.items.size(), 1u);
  EXPECT_TRUE(doc.items[0].is_fill());
}

TEST(SvgStroke, DashArrayForms) {
  auto dashes = [](const std::string& value) {
    const Document doc = parse_svg(svg10("<path d=\"M0 0L5 5\" stroke=\"red\" stroke-dasharray=\"" + value + "\"/>"));
    return only_stroke(doc).stroke.dashes;
  };
  EXPECT_TRUE(dashes("none").empty());
  EXPECT_EQ(dashes("5"), (std::vector<double>{5}));
  EXPECT_EQ(dashes("5,3"), (std::vector<double>{5, 3}));
  EXPECT_EQ(dashes(" 5 , 3\t2 "), (std::vector<double>{5, 3, 2}));
  EXPECT_EQ(dashes("0 0"), (std::vector<double>{0, 0}));  // all zero: the stroker draws solid
  EXPECT_EQ(dashes("1e1 .5"), (std::vector<double>{10, 0.5}));
}

TEST(SvgStroke, LineIsStrokedNeverFilled) {
  const Document doc = parse_svg(svg10(R"(<line x1="1" y1="2" x2="7" y2="2" stroke="red" fill="blue"/>
      <line x1="1" y1="2" x2="7" y2="2"/>)"));
  ASSERT_EQ(doc.items.size(), 1u);
  const DrawItem& s = doc.items[0];
  ASSERT_TRUE(s.is_stroke());
  ASSERT_EQ(s.path.verbs().size(), 2u);
  EXPECT_EQ(s.path.verbs()[0], Verb::Move);
  EXPECT_EQ(s.path.verbs()[1], Verb::Line);
  EXPECT_EQ(s.path.points()[0].x, 1);
  EXPECT_EQ(s.path.points()[1].x, 7);
  EXPECT_EQ(s.path.points()[1].y, 2);
}

TEST(SvgStroke, ShapesCarryTheirTransform) {
  const Document doc = parse_svg(R"svg(<svg width="20" height="20" viewBox="0 0 10 10">
      <g transform="translate(1 0)"><circle cx="5" cy="5" r="2" stroke="red" fill="none"/></g></svg>)svg");
  const DrawItem& s = only_stroke(doc);
  EXPECT_EQ(s.transform.a, 2);
  EXPECT_EQ(s.transform.d, 2);
  EXPECT_EQ(s.transform.e, 2);
}

// ---------------------------------------------------------------------------------------------------------------
// Rendering

TEST(SvgStrokeRender, StrokePaintedOverFill) {
  // A red 6x6 square with a 2-px blue stroke centred on its edge (x and y from 1 to 3 and 7 to 9).
  const Document doc =
      parse_svg(svg10(R"(<rect x="2" y="2" width="6" height="6" fill="red" stroke="blue" stroke-width="2"/>)"));
  vraster::Image image(doc.width, doc.height);
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, RenderSettings{}, renderer);
  for (const IPoint p : {IPoint{2, 4}, IPoint{1, 4}, IPoint{7, 5}, IPoint{4, 8}, IPoint{2, 2}, IPoint{8, 8}}) {
    const std::uint8_t* px = image.pixel(p.x, p.y);
    EXPECT_EQ(px[0], 0) << p.x << "," << p.y;
    EXPECT_EQ(px[2], 255) << p.x << "," << p.y;
    EXPECT_EQ(px[3], 255) << p.x << "," << p.y;
  }
  const std::uint8_t* inside = image.pixel(4, 4);
  EXPECT_EQ(inside[0], 255);
  EXPECT_EQ(inside[2], 0);
  EXPECT_EQ(image.pixel(0, 0)[3], 0);
  EXPECT_EQ(image.pixel(9, 9)[3], 0);
}

TEST(SvgStrokeRender, HorizontalTwoPixelLineCoversExactlyTwoRows) {
  const Document doc =
      parse_svg(R"(<svg width="8" height="6"><line x1="0" y1="3" x2="8" y2="3" stroke="black" stroke-width="2"/></svg>)");
  for (const auto aa : {vraster::AntiAlias::Analytic, vraster::AntiAlias::None}) {
    vraster::Image image(doc.width, doc.height);
    vraster::Renderer renderer;
    RenderSettings settings;
    settings.aa = aa;
    vraster::svg::render(doc, image, settings, renderer);
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        EXPECT_EQ(image.pixel(x, y)[3], (y == 2 || y == 3) ? 255 : 0) << x << "," << y;
      }
    }
  }
}

TEST(SvgStrokeRender, DashedLineAndSixteenBits) {
  // Dashes of 2 on, 2 off along y = 3 (2 px wide): columns 0-1 and 4-5 of rows 2-3.
  const Document doc = parse_svg(
      R"(<svg width="8" height="6"><line x1="0" y1="3" x2="8" y2="3" stroke="#000" stroke-width="2" stroke-dasharray="2"/></svg>)");
  vraster::Image16 image(doc.width, doc.height);
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, RenderSettings{}, renderer);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool on = (y == 2 || y == 3) && (x % 4) < 2;
      EXPECT_EQ(image.pixel(x, y)[3], on ? 65535 : 0) << x << "," << y;
    }
  }
}

TEST(SvgStrokeRender, HairlineBresenhamMatchesLinePixels) {
  // Vertices at pixel centres of (0, 0) and (9, 6); the stroke's own width is ignored in hairline mode.
  const Document doc = parse_svg(
      R"(<svg width="12" height="8"><path d="M0.5 0.5L9.5 6.5" stroke="red" stroke-width="5" fill="none"/></svg>)");
  HairlineMode mode = HairlineMode::Analytic;
  ASSERT_TRUE(vraster::parse_hairline_mode("bresenham", mode));  // what `vraster render --hairline bresenham` does
  RenderSettings settings;
  settings.hairline = mode;
  std::vector<IPoint> expected = vraster::bresenham_pixels(IPoint{0, 0}, IPoint{9, 6});
  std::sort(expected.begin(), expected.end());

  vraster::Image image(doc.width, doc.height);
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, settings, renderer);
  EXPECT_EQ(painted(image), expected);
  for (const IPoint p : expected) EXPECT_EQ(image.pixel(p.x, p.y)[0], 255);

  vraster::Image16 deep(doc.width, doc.height);
  vraster::svg::render(doc, deep, settings, renderer);
  EXPECT_EQ(painted(deep), expected);
  for (const IPoint p : expected) EXPECT_EQ(deep.pixel(p.x, p.y)[3], 65535);

  // Without hairline mode the 5-px stroke covers much more.
  vraster::Image wide(doc.width, doc.height);
  vraster::svg::render(doc, wide, RenderSettings{}, renderer);
  EXPECT_GT(painted(wide).size(), 3 * expected.size());
}

TEST(SvgStrokeRender, HairlineKeepsDashes) {
  // A horizontal hairline along row 2 with dashes 3 on, 2 off (cut in user space, at pixel boundaries here).
  const Document doc = parse_svg(
      R"(<svg width="10" height="4"><path d="M0 2.5H10" stroke="black" stroke-dasharray="3 2" fill="none"/></svg>)");
  RenderSettings settings;
  settings.hairline = HairlineMode::Analytic;
  vraster::Image image(doc.width, doc.height);
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, settings, renderer);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool on = y == 2 && (x % 5) < 3;
      EXPECT_EQ(image.pixel(x, y)[3], on ? 255 : 0) << x << "," << y;
    }
  }
}

TEST(SvgStrokeRender, HairlineModesParse) {
  for (const char* name : {"bresenham", "dda", "wu", "analytic"}) {
    HairlineMode mode;
    EXPECT_TRUE(vraster::parse_hairline_mode(name, mode)) << name;
    EXPECT_EQ(vraster::to_string(mode), name);
  }
  HairlineMode mode;
  EXPECT_FALSE(vraster::parse_hairline_mode("xiaolin", mode));
}

}  // namespace
