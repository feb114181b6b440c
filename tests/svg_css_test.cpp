// svg_subset's CSS: declarations, selectors, specificity, matching and cascade order, on a hand-made tree.
#include <gtest/gtest.h>

#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "css.hpp"

namespace vraster::svg::css {
namespace {

/// A toy element tree: elements with attributes, parents and previous siblings.
struct Fake {
  std::string name;
  std::map<std::string, std::string> attributes;
  const Fake* previous = nullptr;
  const Fake* next = nullptr;
  bool root = false;
};

struct FakeAdapter {
  static std::string_view name(const Fake* n) { return n->name; }
  static bool attribute(const Fake* n, std::string_view name, std::string_view& value) {
    const auto it = n->attributes.find(std::string(name));
    if (it == n->attributes.end()) return false;
    value = it->second;
    return true;
  }
  static const Fake* previous_element(const Fake* n) { return n->previous; }
  static const Fake* next_element(const Fake* n) { return n->next; }
  static bool is_root(const Fake* n) { return n->root; }
  static bool is_null(const Fake* n) { return n == nullptr; }
};

/// Makes `siblings` one run of element siblings, in order (previous / next links).
void link_siblings(std::initializer_list<Fake*> siblings) {
  Fake* before = nullptr;
  for (Fake* f : siblings) {
    f->previous = before;
    if (before) before->next = f;
    before = f;
  }
}

bool match(std::string_view selector_text, const std::vector<const Fake*>& path) {
  Selector selector;
  EXPECT_TRUE(parse_selector(selector_text, selector)) << selector_text;
  return matches_path<FakeAdapter>(selector, path);
}

Specificity specificity(std::string_view text) {
  Selector selector;
  EXPECT_TRUE(parse_selector(text, selector)) << text;
  return selector.specificity;
}

TEST(SvgCss, Declarations) {
  const auto d = parse_declarations("fill: red ;STROKE:blue !important;; /* c */ opacity:0.5; bad; :x; w:", 100);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].name, "fill");
  EXPECT_EQ(d[0].value, "red");
  EXPECT_FALSE(d[0].important);
  EXPECT_EQ(d[0].offset, 106u);  // where "red" starts, plus the base
  EXPECT_EQ(d[1].name, "stroke");
  EXPECT_EQ(d[1].value, "blue");
  EXPECT_TRUE(d[1].important);
  EXPECT_EQ(d[2].name, "opacity");
}

TEST(SvgCss, DeclarationValuesKeepBracketsAndStrings) {
  const auto d = parse_declarations("fill:url(\"#a;b\") red; font-family:'x;y'");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].value, "url(\"#a;b\") red");
  EXPECT_EQ(d[1].value, "'x;y'");
}

TEST(SvgCss, SpecificityCountsIdsClassesTypes) {
  EXPECT_EQ(specificity("*"), 0u);
  EXPECT_EQ(specificity("rect"), 1u);
  EXPECT_EQ(specificity("g rect"), 2u);
  EXPECT_EQ(specificity(".a"), 0x100u);
  EXPECT_EQ(specificity("rect[fill]:first-child"), 0x201u);
  EXPECT_EQ(specificity("#x"), 0x10000u);
  EXPECT_EQ(specificity("g > #x.a.b rect"), 0x10202u);
  // :not() counts its most specific argument, not itself (Selectors 4, 17); other pseudo-classes count as classes.
  EXPECT_EQ(specificity("rect:not(.a, #b)"), 0x10001u);
  EXPECT_EQ(specificity(":not(rect)"), 1u);
  EXPECT_EQ(specificity(":root > g + rect:last-child"), 0x202u);
}

TEST(SvgCss, UnsupportedSelectorsAreRejected) {
  Selector s;
  EXPECT_FALSE(parse_selector("a:nth-child(2)", s));
  EXPECT_FALSE(parse_selector("a::before", s));
  EXPECT_FALSE(parse_selector("a:first-child(1)", s));
  EXPECT_FALSE(parse_selector("a ~ b", s));
  EXPECT_FALSE(parse_selector("a:not(b c)", s));  // :not takes compounds only
  EXPECT_FALSE(parse_selector("a:not()", s));
  EXPECT_FALSE(parse_selector("a:not(.x", s));
  EXPECT_FALSE(parse_selector("a +", s));
  EXPECT_FALSE(parse_selector("a >", s));
  EXPECT_FALSE(parse_selector("[x=]", s));
  EXPECT_FALSE(parse_selector("", s));
}

TEST(SvgCss, MatchesTypeIdClassAttribute) {
  const Fake root{"svg", {}};
  const Fake first{"rect", {{"id", "r1"}, {"class", " big  red "}, {"lang", "en-US"}}};
  const Fake second{"rect", {{"data", "hello world"}}, &first};
  const std::vector<const Fake*> p1{&root, &first}, p2{&root, &second};
  EXPECT_TRUE(match("rect", p1));
  EXPECT_FALSE(match("circle", p1));
  EXPECT_TRUE(match("*", p1));
  EXPECT_TRUE(match("#r1", p1));
  EXPECT_FALSE(match("#r1", p2));
  EXPECT_TRUE(match(".red", p1));
  EXPECT_TRUE(match("rect.big.red", p1));
  EXPECT_FALSE(match(".bi", p1));
  EXPECT_TRUE(match("[lang|=en]", p1));
  EXPECT_FALSE(match("[lang|=e]", p1));
  EXPECT_TRUE(match("[data~=world]", p2));
  EXPECT_TRUE(match("[data^=hel]", p2));
  EXPECT_TRUE(match("[data$='rld']", p2));
  EXPECT_TRUE(match("[data*=\"o w\"]", p2));
  EXPECT_FALSE(match("[data=hello]", p2));
  EXPECT_TRUE(match("rect:first-child", p1));
  EXPECT_FALSE(match("rect:first-child", p2));
}

TEST(SvgCss, DescendantAndChildCombinators) {
  const Fake svg{"svg", {}};
  const Fake g1{"g", {{"class", "a"}}};
  const Fake g2{"g", {}};
  const Fake rect{"rect", {}};
  const std::vector<const Fake*> path{&svg, &g1, &g2, &rect};
  EXPECT_TRUE(match("svg rect", path));
  EXPECT_TRUE(match(".a rect", path));
  EXPECT_FALSE(match(".a > rect", path));
  EXPECT_TRUE(match(".a > g > rect", path));
  EXPECT_TRUE(match("svg > .a g rect", path));
  EXPECT_FALSE(match("svg > g > rect", path));  // the g whose child the rect is has no svg parent
  EXPECT_TRUE(match("g > rect", path));
  EXPECT_TRUE(match("g g rect", path));
  EXPECT_FALSE(match("g g g rect", path));
  // The nearest g does not have a child-of-svg parent, a farther one does: the matcher must not stop at the first.
  EXPECT_TRUE(match("svg > g rect", path));
}

TEST(SvgCss, StructuralPseudoClassesNotAndUserActions) {
  Fake svg{"svg", {}};
  svg.root = true;
  Fake a{"rect", {{"class", "x"}}}, b{"circle", {}}, c{"rect", {}};
  link_siblings({&a, &b, &c});
  const Fake only{"path", {}};
  Fake link{"a", {{"xlink:href", "#t"}}};
  const std::vector<const Fake*> pa{&svg, &a}, pb{&svg, &b}, pc{&svg, &c}, po{&svg, &only}, pl{&svg, &link};
  EXPECT_TRUE(match("svg:root", {&svg}));
  EXPECT_FALSE(match(":root", pa));
  EXPECT_TRUE(match(":root > rect", pa));
  EXPECT_TRUE(match("rect:last-child", pc));
  EXPECT_FALSE(match("rect:last-child", pa));
  EXPECT_TRUE(match(":only-child", po));
  EXPECT_FALSE(match(":only-child", pb));
  EXPECT_TRUE(match("rect:not(.x)", pc));
  EXPECT_FALSE(match("rect:not(.x)", pa));
  EXPECT_FALSE(match(":not(rect, circle)", pb));
  EXPECT_TRUE(match(":not(rect, circle)", po));
  EXPECT_TRUE(match(":not(:hover)", pa));  // nothing is hovered in a still image
  EXPECT_FALSE(match("rect:hover", pa));
  EXPECT_TRUE(match("a:link", pl));
  EXPECT_FALSE(match(":any-link", pa));
}

TEST(SvgCss, NextSiblingCombinator) {
  Fake svg{"svg", {}};
  svg.root = true;
  Fake g{"g", {{"class", "k"}}}, a{"rect", {{"class", "x"}}}, b{"circle", {}}, c{"rect", {}};
  link_siblings({&a, &b, &c});
  const std::vector<const Fake*> pa{&svg, &g, &a}, pb{&svg, &g, &b}, pc{&svg, &g, &c};
  EXPECT_TRUE(match("rect + circle", pb));
  EXPECT_TRUE(match(".x + circle + rect", pc));
  EXPECT_FALSE(match(".x + rect", pc));       // only the previous element sibling
  EXPECT_FALSE(match("rect + rect", pa));     // the first child has none
  EXPECT_TRUE(match(".k > .x + circle", pb));  // the sibling's parent is the ancestor's
  EXPECT_TRUE(match("svg .x+circle", pb));
  EXPECT_FALSE(match("circle + .x", pa));
  EXPECT_TRUE(match("g > rect:first-child + :not(rect)", pb));
}

TEST(SvgCss, VarSubstitution) {
  const CustomProperties custom{{"--a", "red"}, {"--b", "var(--a) 2px"}, {"--self", "var(--self)"},
                                {"--ping", "var(--pong)"}, {"--pong", "var(--ping)"}};
  std::string out;
  EXPECT_TRUE(substitute_vars("var(--a)", custom, out));
  EXPECT_EQ(out, "red");
  EXPECT_TRUE(substitute_vars("url(#x) VAR( --A )", custom, out));  // names are compared lower-cased
  EXPECT_EQ(out, "url(#x) red");
  EXPECT_TRUE(substitute_vars("0 var(--b)", custom, out));
  EXPECT_EQ(out, "0 red 2px");
  EXPECT_TRUE(substitute_vars("var(--none, var(--a))", custom, out));  // the fallback, itself a reference
  EXPECT_EQ(out, "red");
  EXPECT_TRUE(substitute_vars("var(--none, rgb(1, 2, 3))", custom, out));  // commas inside the fallback
  EXPECT_EQ(out, "rgb(1, 2, 3)");
  EXPECT_TRUE(substitute_vars("avar(--a)", custom, out));  // not a var( function
  EXPECT_EQ(out, "avar(--a)");
  EXPECT_FALSE(substitute_vars("var(--none)", custom, out));
  EXPECT_FALSE(substitute_vars("var(a)", custom, out));
  EXPECT_FALSE(substitute_vars("var(--a", custom, out));
  EXPECT_FALSE(substitute_vars("var(--self)", custom, out));  // cycles are invalid
  EXPECT_FALSE(substitute_vars("var(--ping)", custom, out));
  // References that double at every level: stopped by the size limit, not by memory.
  CustomProperties doubling{{"--l0", "xxxxxxxxxxxxxxxx"}};
  for (int i = 1; i <= 16; ++i)
    doubling["--l" + std::to_string(i)] = "var(--l" + std::to_string(i - 1) + ") var(--l" + std::to_string(i - 1) + ")";
  EXPECT_FALSE(substitute_vars("var(--l16)", doubling, out));
  EXPECT_TRUE(substitute_vars("var(--l8)", doubling, out));
}

TEST(SvgCss, DeepDescendantChainsStayLinear) {
  // 200 nested g elements and a 40-compound descendant selector that fails at the end: a backtracking matcher
  // would take about 200^40 steps.
  std::vector<Fake> nodes(200, Fake{"g", {}});
  std::vector<const Fake*> path;
  for (const Fake& n : nodes) path.push_back(&n);
  std::string selector = "rect";
  for (int i = 0; i < 40; ++i) selector += " g";
  EXPECT_FALSE(match(selector, path));
  EXPECT_TRUE(match("g g g g g g g g g g g g g g g g g g g g", path));
}

TEST(SvgCss, StyleSheetRulesAndAtRules) {
  StyleSheet sheet;
  const auto dropped = sheet.add(
      "<!-- @import url(x.css); @media print { rect { fill: red } } --> rect, .a { fill: green } "
      "a:nth-child(2), b { fill: blue } /* } */ #x { stroke: black; stroke-width: 2 }",
      10);
  ASSERT_EQ(sheet.rules.size(), 3u);
  EXPECT_EQ(sheet.rules[0].selector.compounds[0].parts[0].name, "rect");
  EXPECT_EQ(sheet.rules[1].selector.compounds[0].parts[0].name, "a");
  EXPECT_EQ(sheet.rules[1].declarations[0].value, "green");
  EXPECT_EQ(sheet.rules[2].declarations.size(), 2u);
  EXPECT_EQ(sheet.rules[2].order, 2u);
  ASSERT_EQ(dropped.size(), 1u);  // "a:nth-child(2), b": one unsupported member drops the list
}

TEST(SvgCss, CascadeOrder) {
  const Declaration d;
  std::vector<Cascaded> c{
      {&d, Origin::StyleImportant, 0, 0}, {&d, Origin::Sheet, 0x100, 1}, {&d, Origin::Sheet, 0x1, 5},
      {&d, Origin::StyleAttribute, 0, 0}, {&d, Origin::SheetImportant, 0x1, 2}, {&d, Origin::PresentationAttribute, 0, 9},
      {&d, Origin::Sheet, 0x100, 0},
  };
  sort_cascade(c);
  EXPECT_EQ(c[0].origin, Origin::PresentationAttribute);
  EXPECT_EQ(c[1].specificity, 0x1u);
  EXPECT_EQ(c[2].order, 0u);  // same specificity: source order
  EXPECT_EQ(c[3].order, 1u);
  EXPECT_EQ(c[4].origin, Origin::StyleAttribute);
  EXPECT_EQ(c[5].origin, Origin::SheetImportant);
  EXPECT_EQ(c[6].origin, Origin::StyleImportant);
}

}  // namespace
}  // namespace vraster::svg::css
