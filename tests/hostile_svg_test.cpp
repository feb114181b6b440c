// Hostile SVG input (issue 12): each example of the issue as a named regression test, plus the mechanisms
// behind them (XML well-formedness, linear style parsing, safe messages, warning summaries, dash checks).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"
#include "vraster/error.hpp"
#include "vraster/files.hpp"
#include "vraster/stroke.hpp"

namespace {

using vraster::DashVerdict;
using vraster::Path;
using vraster::svg::Document;
using vraster::svg::parse_svg;
using vraster::svg::ParseError;

/// Parses `svg`, expecting a ParseError at line:column whose message contains `text`.
void expect_error_at(const std::string& svg, int line, int column, const std::string& text) {
  try {
    parse_svg(svg, "hostile.svg");
    ADD_FAILURE() << "no error for:\n" << svg;
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    EXPECT_NE(e.message().find(text), std::string::npos) << e.what();
  }
}

/// Parses `svg`, expecting no error and a warning at line:column whose message contains `text`.
void expect_warning_at(const std::string& svg, int line, int column, const std::string& text) {
  const Document doc = parse_svg(svg, "hostile.svg");
  const std::string prefix = std::to_string(line) + ":" + std::to_string(column) + ": ";
  for (const std::string& w : doc.warnings) {
    if (w.rfind(prefix, 0) == 0 && w.find(text) != std::string::npos) return;
  }
  ADD_FAILURE() << "no warning " << prefix << text << " among " << doc.warnings.size() << " warnings";
}

bool has_control_bytes(const std::string& s) {
  return std::any_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

const std::string kOpen = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">";

// ---- malformed XML (the four cases, then what must stay accepted) ----

TEST(HostileXml, TwoRootElements) {
  expect_error_at(kOpen + "</svg>\n<svg width=\"1\" height=\"1\"/>", 2, 1, "second root element");
}

TEST(HostileXml, ContentAfterClosingSvg) {
  expect_error_at(kOpen + "</svg>\n  junk", 2, 3, "text after the end of the root element");
  expect_error_at(kOpen + "</svg>&amp;", 1, 70, "outside the root element");
}

TEST(HostileXml, DuplicateAttributes) {
  expect_error_at(kOpen + "\n<rect width=\"1\" height=\"2\" width=\"3\"/></svg>", 2, 28, "duplicate attribute 'width'");
  // Also on elements that are never drawn.
  expect_error_at(kOpen + "<defs><g\n id=\"a\" id=\"b\"/></defs></svg>", 2, 9, "duplicate attribute 'id'");
}

TEST(HostileXml, UndefinedEntities) {
  expect_error_at(kOpen + "\n<rect fill=\"&nbsp;\" width=\"1\" height=\"1\"/></svg>", 2, 13, "undefined entity '&nbsp;'");
  expect_error_at(kOpen + "<desc>a &foo; b</desc></svg>", 1, 72, "undefined entity '&foo;'");
  expect_error_at(kOpen + "<desc>AT&T</desc></svg>", 1, 72, "'&' that does not start an entity reference");
  expect_error_at(kOpen + "<desc>&#0;</desc></svg>", 1, 70, "character reference '&#0;'");
  expect_error_at("<!DOCTYPE svg [<!ENTITY ns 'x'>]>" + kOpen + "<g id=\"&other;\"/></svg>", 1, 104,
                  "not declared in the DOCTYPE's internal subset");
}

// ---- entities declared in the DOCTYPE's internal subset: expanded, within limits ----

TEST(HostileXml, InternalEntitiesAreExpandedInAttributesAndContent) {
  const std::string text = "<!DOCTYPE svg [\n<!-- a comment -->\n<!ENTITY fill \"lime\">\n"
                           "<!ENTITY shape \"<rect width='5' height='5' fill='&fill;'/>\">\n"
                           "<!ENTITY fill 'red'><!ENTITY % pe 'ignored'><!ATTLIST svg a CDATA '>'>]>\n" +
                           kOpen + "&shape;<g>&shape;</g><rect width='1' height='1' fill='&fill;'/>"
                           "<!-- &shape; --><desc><![CDATA[&shape;]]></desc></svg>";
  const vraster::svg::Tree tree = vraster::svg::parse_svg_tree(text);
  ASSERT_EQ(tree.root.children.size(), 3u);  // the comment and the CDATA section are left alone
  const auto& first = std::get<vraster::svg::PathNode>(tree.root.children[0].value);
  EXPECT_EQ(first.fill->paint.color.g, 1.f);  // the first declaration of `fill` binds: lime
  EXPECT_EQ(first.fill->paint.color.r, 0.f);
}

TEST(HostileXml, EntityExpansionLimits) {
  // A billion laughs: ten levels of ten references stop at 1 MiB of growth, naming the entity in the document.
  std::string laughs = "<!DOCTYPE svg [<!ENTITY a 'lol'>";
  for (char c = 'b'; c <= 'k'; ++c) {
    laughs += std::string("<!ENTITY ") + c + " '";
    for (int i = 0; i < 10; ++i) laughs += std::string("&") + char(c - 1) + ";";
    laughs += "'>";
  }
  laughs += "]>";
  const int column = static_cast<int>(laughs.size() + kOpen.size() + 7);
  expect_error_at(laughs + kOpen + "<desc>&k;</desc></svg>", 1, column, "expanding entity '&k;' makes the document");
  // Loops, nesting past the limit, external entities.
  expect_error_at("<!DOCTYPE svg [<!ENTITY a '&b;'><!ENTITY b '&a;'>]>\n" + kOpen + "&a;</svg>", 2, 64,
                  "entity '&a;' refers to itself");
  std::string deep = "<!DOCTYPE svg [<!ENTITY e0 'x'>";
  for (int i = 1; i <= 17; ++i) deep += "<!ENTITY e" + std::to_string(i) + " '&e" + std::to_string(i - 1) + ";'>";
  expect_error_at(deep + "]>\n" + kOpen + "&e17;</svg>", 2, 64, "entity '&e17;' nests entities too deeply");
  expect_error_at("<!DOCTYPE svg [<!ENTITY x SYSTEM 'http://example.org/x.ent'>]>\n" + kOpen + "<desc>&x;</desc></svg>",
                  2, 70, "external entities are never loaded");
  std::string many = "<!DOCTYPE svg [";
  std::size_t last = 0;  // where the declaration over the limit starts
  for (int i = 0; i <= 10000; ++i) {
    last = many.size();
    many += "<!ENTITY n" + std::to_string(i) + " ''>";
  }
  expect_error_at(many + "]>" + kOpen + "</svg>", 1, static_cast<int>(last + 1), "too many entity declarations");
}

TEST(HostileXml, LessThanInAttributeValue) {
  expect_error_at(kOpen + "<g id=\"a<b\"/></svg>", 1, 72, "'<' inside an attribute value");
}

TEST(HostileXml, WellFormedExtrasStayAccepted) {
  const std::string text = "\xEF\xBB\xBF<?xml version=\"1.0\"?>\n<!-- before -->\n<!DOCTYPE svg [ <!ATTLIST svg a CDATA '>'> ]>\n" +
                           kOpen +
                           "<desc><![CDATA[ & < > ]]> &lt;&gt;&amp;&apos;&quot;&#65;&#x1F600;</desc>"
                           "<rect width=\"5\" height=\"5\" id=\"a&amp;b&#x3e;\"/></svg>\n<!-- after -->\n<?pi x?>\n";
  const Document doc = parse_svg(text, "ok.svg");
  EXPECT_EQ(doc.items.size(), 1u);
}

// ---- linear time ----

TEST(HostileStyle, StyleAttributeWith300000Declarations) {
  // Each declaration used to re-walk the attribute from its start to find its position (quadratic: > 20 s).
  // The position of an error in the last declaration is still exact.
  std::string style;
  for (int i = 0; i < 300000; ++i) style += "fill:red;";
  const Document doc = parse_svg(kOpen + "<rect width=\"5\" height=\"5\" style=\"" + style + "\"/></svg>");
  ASSERT_EQ(doc.items.size(), 1u);
  EXPECT_FLOAT_EQ(doc.items[0].color.r, 1.0f);
  const std::string prefix = kOpen + "\n<rect width=\"5\" height=\"5\" style=\"";
  expect_warning_at(prefix + style + "fill:bad\"/></svg>", 2, 35 + static_cast<int>(style.size()) + 5,
                    "invalid fill 'bad'");
}

TEST(HostileStyle, ManyMalformedDeclarationsWarnBriefly) {
  std::string style;
  for (int i = 0; i < 100000; ++i) style += "junk;";
  const Document doc = parse_svg(kOpen + "<rect width=\"5\" height=\"5\" style=\"" + style + "\"/></svg>");
  EXPECT_EQ(doc.warnings.size(), 21u);
}

// ---- messages: sanitised and capped, repeated warnings summarised ----

TEST(HostileMessages, PrintableEscapesControlCharactersAndCaps) {
  EXPECT_EQ(vraster::printable("a\x1b[31mb\x07\n"), "a\\x1b[31mb\\x07\\n");
  EXPECT_EQ(vraster::printable("\xc2\x9b" "2J"), "\\x9b2J");              // C1 CSI, UTF-8 encoded
  EXPECT_EQ(vraster::printable("\xe2\x80\xae" "abc"), "\\u{202e}abc");    // right-to-left override
  EXPECT_EQ(vraster::printable("\xff\xfe ok"), "\\xff\\xfe ok");          // not UTF-8
  EXPECT_EQ(vraster::printable("caf\xc3\xa9"), "caf\xc3\xa9");            // UTF-8 text stays
  EXPECT_EQ(vraster::printable(std::string(100000, '9'), 10), "9999999999...");
  EXPECT_EQ(vraster::quoted("x"), "'x'");
}

TEST(HostileMessages, ControlCharactersInAttributeValueAreEscaped) {
  const Document doc = parse_svg(kOpen + "<rect fill=\"\x1b]0;pwned\x07\" width=\"1\" height=\"1\"/></svg>");
  ASSERT_EQ(doc.warnings.size(), 1u);
  EXPECT_FALSE(has_control_bytes(doc.warnings[0])) << doc.warnings[0];
  EXPECT_NE(doc.warnings[0].find("\\x1b]0;pwned\\x07"), std::string::npos) << doc.warnings[0];
}

TEST(HostileMessages, HundredKilobyteNumberIsNotEchoedWhole) {
  const std::string number = "1" + std::string(100000, '0');
  for (const std::string& body : {"<path d=\"M" + number + " 0 L1 1\"/>", "<rect width=\"" + number + "x\" height=\"1\"/>",
                                  "<rect width=\"1\" height=\"1\" stroke-dasharray=\"" + number + "q\"/>"}) {
    // Each is ignored (the path up to its error) with one short warning.
    const Document doc = parse_svg(kOpen + body + "</svg>");
    ASSERT_EQ(doc.warnings.size(), 1u) << body.substr(0, 30);
    EXPECT_LT(doc.warnings[0].size(), 300u) << doc.warnings[0].substr(0, 300);
  }
}

TEST(HostileMessages, MillionIgnoredElementsGiveASummary) {
  // 10^5 here (10^6 would be at the element limit): the first 20 warnings, then one line for the rest.
  std::string body;
  for (int i = 0; i < 100000; ++i) body += "<foo/>";
  const Document doc = parse_svg(kOpen + body + "</svg>");
  ASSERT_EQ(doc.warnings.size(), 21u);
  EXPECT_EQ(doc.warnings[0], "1:64: element <foo> is not supported yet, ignored");
  EXPECT_EQ(doc.warnings[20], "1:184: ... and 99980 more warnings about unsupported elements (not shown)");
}

// ---- use: nested instances multiply (SvgTree.BillionLaughsOfUsesStops), uses written in the file do not ----

TEST(HostileLimits, ManyUsesWrittenInTheFileAreNotALaugh) {
  // A scatter plot as drawing programs export it: one marker shape, one use per point, more uses than the nested
  // instance limit. Each use is an element of the file: it parses, and every point is drawn.
  constexpr int kPoints = 100'050;
  std::string body = "<defs><rect id=\"dot\" width=\"1\" height=\"1\"/></defs>";
  for (int i = 0; i < kPoints; ++i) body += "<use href=\"#dot\" x=\"" + std::to_string(i % 10) + "\"/>";
  const vraster::svg::Tree tree = vraster::svg::parse_svg_tree(kOpen + body + "</svg>", "scatter.svg");
  EXPECT_TRUE(tree.warnings.empty()) << tree.warnings.front();
  EXPECT_EQ(tree.root.children.size(), static_cast<std::size_t>(kPoints));
}

// ---- dashes ----

Path ten_px_line() {
  Path p;
  p.move_to({0, 5}).line_to({10, 5});
  return p;
}

TEST(HostileDashes, DashArray1e308WithNegativeOffsetDrawsSolid) {
  // The odd pattern doubled to [1e308, 1e308] sums to infinity; the offset loop never ended.
  EXPECT_EQ(vraster::check_dashes(ten_px_line(), {1e308}), DashVerdict::Invalid);
  const Document doc = parse_svg(kOpen + "<path d=\"M0 5 L10 5\" stroke=\"red\" stroke-dasharray=\"1e308\" "
                                         "stroke-dashoffset=\"-1\"/></svg>");
  ASSERT_EQ(doc.warnings.size(), 1u);
  EXPECT_NE(doc.warnings[0].find("drawn solid"), std::string::npos) << doc.warnings[0];
  vraster::Image image(10, 10);
  image.clear(vraster::Color::transparent());
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, {}, renderer);
  for (int x = 0; x < 10; ++x) EXPECT_EQ(image.pixel(x, 4)[3], 128) << x;  // solid: half of rows 4 and 5
  // dash_polylines itself, given such a pattern directly, copies the pieces unchanged instead of looping.
  std::vector<vraster::StrokePolyline> pieces, out;
  vraster::flatten_for_stroke(ten_px_line(), 0.1, pieces);
  vraster::dash_polylines(pieces, {1e308, 1e308}, -1, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].points.size(), 2u);
}

TEST(HostileDashes, TinyDashesOnWideStrokeDrawSolidWithWarning) {
  // stroke-width 100, dashes of 0.0000477: 2 * 10 / 0.0000954 = 209,644 pattern elements, over the limit.
  EXPECT_EQ(vraster::check_dashes(ten_px_line(), {0.0000477, 0.0000477}), DashVerdict::TooMany);
  EXPECT_EQ(vraster::check_dashes(ten_px_line(), {1, 1}), DashVerdict::Dashed);
  EXPECT_EQ(vraster::check_dashes(ten_px_line(), {0, 0}), DashVerdict::Invalid);
  EXPECT_EQ(vraster::check_dashes(ten_px_line(), {}), DashVerdict::None);
  const Document doc = parse_svg(kOpen + "<path d=\"M0 5 L10 5\" stroke=\"red\" stroke-width=\"100\" "
                                         "stroke-dasharray=\"0.0000477 0.0000477\"/></svg>");
  ASSERT_EQ(doc.warnings.size(), 1u);
  EXPECT_NE(doc.warnings[0].find("more than 65536"), std::string::npos) << doc.warnings[0];
  vraster::Image image(10, 10);
  image.clear(vraster::Color::transparent());
  vraster::Renderer renderer;
  vraster::svg::render(doc, image, {}, renderer);
  EXPECT_EQ(image.pixel(5, 5)[3], 255);  // solid
}

}  // namespace

namespace {

TEST(HostileInput, RenderDevZeroStopsAtTheSizeCap) {
  // `vraster render /dev/zero` read until memory ran out; every input is read through read_file_limited.
  try {
    vraster::read_file_limited("/dev/zero", 1 << 20, "SVG file");
    FAIL() << "no error";
  } catch (const vraster::Error& e) {
    EXPECT_EQ(std::string(e.what()), "SVG file '/dev/zero' is larger than the limit of 1 MiB");
  }
  try {
    vraster::read_file_limited("/", 1 << 20, "font");
    FAIL() << "no error";
  } catch (const vraster::Error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read font '/': it is a directory");
  }
}

}  // namespace
