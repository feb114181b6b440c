// svg_subset: the CSS that SVG files use: <style> sheets and style attributes, selectors, specificity, cascade.
//
// Supported selectors (CSS Selectors Level 3 and 4 subset): type, universal `*`, `#id`, `.class`, attribute
// (`[a]`, `[a=v]`, `[a~=v]`, `[a|=v]`, `[a^=v]`, `[a$=v]`, `[a*=v]`), `:first-child`, `:last-child`,
// `:only-child`, `:root`, `:link` / `:any-link` (an `a` with a link), `:not(list of compounds)`, the user-action
// pseudo-classes (`:hover`, `:active`, `:focus`, `:focus-within`, `:focus-visible`, `:visited`, `:target`: valid,
// never matching in a still image), and the descendant (whitespace), child (`>`) and next-sibling (`+`)
// combinators, in comma-separated lists. A selector with anything else (other pseudo-classes such as
// `:nth-child`, pseudo-elements, `~`) is unsupported and its rule is dropped, as browsers drop invalid ones.
// At-rules (`@media`, `@import`, ...) are skipped whole. Every pass over the text is linear in its length, and
// matching one element looks at its ancestors and their adjacent siblings only.
#pragma once

#include <cstddef>
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace vraster::svg::css {

/// One `name: value` pair. `offset` is the byte offset of the value in the parsed text.
struct Declaration {
  std::string name;   ///< lower-cased
  std::string value;  ///< trimmed, without `!important`
  bool important = false;
  std::size_t offset = 0;
};

/// Parses a declaration block ("fill: red; stroke: blue !important"). Malformed declarations are skipped (CSS
/// error recovery: up to the next ';' outside brackets and strings); `bad` receives the offset of each one.
std::vector<Declaration> parse_declarations(std::string_view text, std::size_t base_offset = 0,
                                            std::vector<std::size_t>* bad = nullptr);

/// One simple selector inside a compound one.
struct SimpleSelector {
  enum class Kind : std::uint8_t {
    Type, Universal, Id, Class, Attribute, FirstChild, LastChild, OnlyChild, Root, Link,
    Never,  ///< a user-action pseudo-class (:hover, ...): nothing is hovered in a still image
    Not,    ///< :not(...): matches when none of `alternatives` does
  };
  /// How an attribute selector compares: [a], [a=v], [a~=v], [a|=v], [a^=v], [a$=v], [a*=v].
  enum class Match : std::uint8_t { Exists, Equals, Includes, DashMatch, Prefix, Suffix, Substring };
  Kind kind = Kind::Universal;
  Match match = Match::Exists;
  std::string name;   ///< element type, id, class or attribute name
  std::string value;  ///< the attribute value compared with
  std::vector<std::vector<SimpleSelector>> alternatives;  ///< Not: its argument list, one compound each
};

/// A compound selector and the combinator that joins it to the one before (none for the first).
struct Compound {
  enum class Combinator : std::uint8_t { None, Descendant, Child, NextSibling };
  Combinator combinator = Combinator::None;
  std::vector<SimpleSelector> parts;
};

/// CSS specificity (a, b, c) packed for comparison: ids, classes/attributes/pseudo-classes, types.
using Specificity = std::uint32_t;

/// A complex selector, left to right (the subject is the last compound).
struct Selector {
  std::vector<Compound> compounds;
  Specificity specificity = 0;
};

/// A style rule: a selector (one per member of the comma list) with its declarations; `order` is its position
/// among all rules of the document.
struct Rule {
  Selector selector;
  std::vector<Declaration> declarations;
  std::size_t order = 0;
};

/// The rules of every <style> element of a document, in document order.
struct StyleSheet {
  std::vector<Rule> rules;
  /// Adds the rules of one style sheet text; `base_offset` is where it starts in the document. Returns the
  /// offsets of rules dropped for an invalid or unsupported selector.
  std::vector<std::size_t> add(std::string_view text, std::size_t base_offset = 0);
};

/// Parses a selector (list members one by one: no commas). Returns false for one we do not support.
bool parse_selector(std::string_view text, Selector& out);

/// What selector matching needs from an element. `Node` is a cheap handle (the SVG reader uses pugi::xml_node);
/// an adapter provides these static functions.
///   static std::string_view name(Node);           element type (local name)
///   static bool attribute(Node, std::string_view name, std::string_view& value);
///   static Node previous_element(Node);           the previous element sibling, or null
///   static Node next_element(Node);               the next element sibling, or null
///   static bool is_root(Node);                    no parent element (the document's root element)
///   static bool is_null(Node);

// ---- implementation of the template ----

namespace detail {

bool attribute_matches(const SimpleSelector& s, std::string_view value);
bool class_list_contains(std::string_view classes, std::string_view name);

template <class Adapter, class Node>
bool matches_parts(const std::vector<SimpleSelector>& parts, Node node) {
  for (const SimpleSelector& s : parts) {
    std::string_view value;
    switch (s.kind) {
      case SimpleSelector::Kind::Universal:
        break;
      case SimpleSelector::Kind::Type:
        if (Adapter::name(node) != s.name) return false;
        break;
      case SimpleSelector::Kind::Id:
        if (!Adapter::attribute(node, "id", value) || value != s.name) return false;
        break;
      case SimpleSelector::Kind::Class:
        if (!Adapter::attribute(node, "class", value) || !class_list_contains(value, s.name)) return false;
        break;
      case SimpleSelector::Kind::Attribute:
        if (!Adapter::attribute(node, s.name, value) || !attribute_matches(s, value)) return false;
        break;
      case SimpleSelector::Kind::FirstChild:
        if (!Adapter::is_null(Adapter::previous_element(node))) return false;
        break;
      case SimpleSelector::Kind::LastChild:
        if (!Adapter::is_null(Adapter::next_element(node))) return false;
        break;
      case SimpleSelector::Kind::OnlyChild:
        if (!Adapter::is_null(Adapter::previous_element(node)) || !Adapter::is_null(Adapter::next_element(node)))
          return false;
        break;
      case SimpleSelector::Kind::Root:
        if (!Adapter::is_root(node)) return false;
        break;
      case SimpleSelector::Kind::Link:
        if (Adapter::name(node) != "a" || !(Adapter::attribute(node, "href", value) ||
                                            Adapter::attribute(node, "xlink:href", value)))
          return false;
        break;
      case SimpleSelector::Kind::Never:
        return false;
      case SimpleSelector::Kind::Not:
        for (const std::vector<SimpleSelector>& alternative : s.alternatives) {
          if (matches_parts<Adapter>(alternative, node)) return false;
        }
        break;
    }
  }
  return true;
}

template <class Adapter, class Node>
bool matches_compound(const Compound& compound, Node node) {
  return matches_parts<Adapter>(compound.parts, node);
}

}  // namespace detail

/// Matches a selector against the element path[path.size() - 1] whose ancestors are path[0 .. size - 2] (root
/// first). Right to left, it keeps the positions where each compound can match with everything to its right
/// satisfied: a child combinator steps one up, a descendant one allows any ancestor of the deepest position so far,
/// a next-sibling one stays at the same depth on the previous sibling. Each depth holds one element at a time
/// (`at`: the ancestor itself, or after n `+` its n-th previous sibling; every position has taken the same number
/// of `+` steps since the last `>` or descendant step). That is O(compounds x depth), never the exponential
/// backtracking of a naive descendant matcher.
template <class Adapter, class Node>
bool matches_path(const Selector& selector, const std::vector<Node>& path) {
  if (selector.compounds.empty() || path.empty()) return false;
  std::vector<char> ok(path.size(), 0), next(path.size(), 0);
  std::vector<Node> at(path);
  std::size_t i = selector.compounds.size() - 1;
  if (!detail::matches_compound<Adapter>(selector.compounds[i], path.back())) return false;
  ok.back() = 1;
  while (i > 0) {
    const Compound::Combinator combinator = selector.compounds[i].combinator;
    const Compound& left = selector.compounds[i - 1];
    std::fill(next.begin(), next.end(), 0);
    bool any = false;
    if (combinator == Compound::Combinator::NextSibling) {
      for (std::size_t j = 0; j < path.size(); ++j) {
        if (!ok[j]) continue;
        at[j] = Adapter::previous_element(at[j]);
        if (!Adapter::is_null(at[j]) && detail::matches_compound<Adapter>(left, at[j])) next[j] = 1, any = true;
      }
    } else if (combinator == Compound::Combinator::Child) {
      std::copy(path.begin(), path.end(), at.begin());  // the parent of a sibling is the parent of the ancestor
      for (std::size_t j = 1; j < path.size(); ++j) {
        if (ok[j] && detail::matches_compound<Adapter>(left, path[j - 1])) next[j - 1] = 1, any = true;
      }
    } else {
      std::copy(path.begin(), path.end(), at.begin());
      std::size_t top = 0;  // the deepest position that matched: any ancestor of it will do
      for (std::size_t j = 0; j < path.size(); ++j) {
        if (ok[j]) top = j;
      }
      for (std::size_t j = 0; j < top; ++j) {
        if (detail::matches_compound<Adapter>(left, path[j])) next[j] = 1, any = true;
      }
    }
    if (!any) return false;
    ok.swap(next);
    --i;
  }
  return true;
}



/// Custom properties in force on an element (`--name: value`, names lower-cased like every property name here).
using CustomProperties = std::unordered_map<std::string, std::string>;

/// Replaces every `var(--name)` and `var(--name, fallback)` in `value` (CSS Custom Properties 1, section 3) with
/// the custom property's value, else the fallback, else returns false: the declaration is then invalid at
/// computed-value time. References inside what is substituted are replaced too; a cycle, nesting deeper than 16 or
/// a result over 64 KiB (references that double at each level) is invalid as well.
bool substitute_vars(std::string_view value, const CustomProperties& custom, std::string& out);

/// Whether `value` holds a var( function (any letter case): what substitute_vars would replace.
bool has_var(std::string_view value);

/// Where a declaration in the cascade came from, lowest precedence first.
enum class Origin : std::uint8_t { PresentationAttribute, Sheet, StyleAttribute, SheetImportant, StyleImportant };

/// A declaration with its place in the cascade.
struct Cascaded {
  const Declaration* declaration;
  Origin origin;
  Specificity specificity;
  std::size_t order;
};

/// Sorts declarations into cascade order (SVG 2 section 6.4, CSS Cascade 4): presentation attributes first
/// (specificity 0, before every author rule), then sheet rules by specificity and source order, then the style
/// attribute, then !important sheet rules, then !important style attribute declarations. Applying them in this
/// order, last one wins, gives each property its cascaded value.
void sort_cascade(std::vector<Cascaded>& declarations);

}  // namespace vraster::svg::css
