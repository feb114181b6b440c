// svg_subset: CSS style sheets, declarations and selectors (see css.hpp).
#include "css.hpp"

#include <algorithm>
#include <tuple>

namespace vraster::svg::css {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
         static_cast<unsigned char>(c) >= 0x80;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

/// The text with comments replaced by spaces (same length, so offsets stay valid); strings are kept.
std::string without_comments(std::string_view text) {
  std::string out(text);
  char quote = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char c = out[i];
    if (quote) {
      if (c == '\\') {
        ++i;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '/' && i + 1 < out.size() && out[i + 1] == '*') {
      const std::size_t end = out.find("*/", i + 2);
      const std::size_t stop = end == std::string::npos ? out.size() : end + 2;
      std::fill(out.begin() + static_cast<std::ptrdiff_t>(i), out.begin() + static_cast<std::ptrdiff_t>(stop), ' ');
      i = stop - 1;
    }
  }
  return out;
}

/// Scans from `i` to the first `stop` character outside strings and brackets (or the end); returns its index.
std::size_t scan_to(std::string_view s, std::size_t i, std::string_view stops) {
  char quote = 0;
  int depth = 0;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (quote) {
      if (c == '\\') {
        ++i;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '(' || c == '[') {
      ++depth;
    } else if ((c == ')' || c == ']') && depth > 0) {
      --depth;
    } else if (depth == 0 && stops.find(c) != std::string_view::npos) {
      return i;
    }
  }
  return s.size();
}

/// Parses declarations of `text` (comments already blanked), offsets relative to `base`.
void declarations_of(std::string_view text, std::size_t base, std::vector<Declaration>& out,
                     std::vector<std::size_t>* bad) {
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t end = scan_to(text, i, ";");
    const std::string_view item = text.substr(i, end - i);
    const std::size_t colon = item.find(':');
    if (!trim(item).empty()) {
      const std::string_view name = colon == std::string_view::npos ? std::string_view{} : trim(item.substr(0, colon));
      bool name_ok = !name.empty() && std::all_of(name.begin(), name.end(), is_name_char);
      std::string_view value = colon == std::string_view::npos ? std::string_view{} : item.substr(colon + 1);
      const std::size_t value_start = static_cast<std::size_t>(trim(value).data() - text.data());
      value = trim(value);
      bool important = false;
      const std::size_t bang = value.rfind('!');
      if (bang != std::string_view::npos) {
        const std::string_view flag = trim(value.substr(bang + 1));
        if (lower(flag) == "important") {
          important = true;
          value = trim(value.substr(0, bang));
        }
      }
      if (name_ok && !value.empty()) {
        out.push_back(Declaration{lower(name), std::string(value), important, base + value_start});
      } else if (bad) {
        bad->push_back(base + i + static_cast<std::size_t>(trim(item).data() - item.data()));
      }
    }
    i = end + 1;
  }
}

/// Reads an identifier (CSS escapes are not supported: a backslash ends it).
std::string_view read_name(std::string_view s, std::size_t& i) {
  const std::size_t start = i;
  while (i < s.size() && is_name_char(s[i])) ++i;
  return s.substr(start, i - start);
}

bool parse_attribute_selector(std::string_view s, std::size_t& i, SimpleSelector& out) {
  // s[i] is just past '['.
  while (i < s.size() && is_space(s[i])) ++i;
  out.kind = SimpleSelector::Kind::Attribute;
  out.name = std::string(read_name(s, i));
  if (out.name.empty()) return false;
  while (i < s.size() && is_space(s[i])) ++i;
  if (i < s.size() && s[i] == ']') {
    ++i;
    out.match = SimpleSelector::Match::Exists;
    return true;
  }
  using M = SimpleSelector::Match;
  if (i < s.size() && s[i] == '=') {
    out.match = M::Equals;
    ++i;
  } else if (i + 1 < s.size() && s[i + 1] == '=') {
    switch (s[i]) {
      case '~': out.match = M::Includes; break;
      case '|': out.match = M::DashMatch; break;
      case '^': out.match = M::Prefix; break;
      case '$': out.match = M::Suffix; break;
      case '*': out.match = M::Substring; break;
      default: return false;
    }
    i += 2;
  } else {
    return false;
  }
  while (i < s.size() && is_space(s[i])) ++i;
  if (i < s.size() && (s[i] == '"' || s[i] == '\'')) {
    const char quote = s[i++];
    const std::size_t end = s.find(quote, i);
    if (end == std::string_view::npos) return false;
    out.value = std::string(s.substr(i, end - i));
    i = end + 1;
  } else {
    out.value = std::string(read_name(s, i));
    if (out.value.empty()) return false;
  }
  while (i < s.size() && is_space(s[i])) ++i;
  if (i >= s.size() || s[i] != ']') return false;
  ++i;
  return true;
}

}  // namespace

std::vector<Declaration> parse_declarations(std::string_view text, std::size_t base_offset,
                                            std::vector<std::size_t>* bad) {
  const std::string clean = without_comments(text);
  std::vector<Declaration> out;
  declarations_of(clean, base_offset, out, bad);
  return out;
}

namespace {

/// Specificity counts of one compound: ids, classes (attributes and pseudo-classes too), types.
struct Counts {
  std::uint32_t ids = 0, classes = 0, types = 0;
  Specificity packed() const {
    return std::min<std::uint32_t>(ids, 255) << 16 | std::min<std::uint32_t>(classes, 255) << 8 |
           std::min<std::uint32_t>(types, 255);
  }
};

bool parse_parts(std::string_view s, std::size_t& i, std::vector<SimpleSelector>& parts, Counts& counts, int depth);

/// The argument of :not( ... ), s[i] just past '(': a comma list of compounds (Selectors 4), up to the matching ')'.
/// Its specificity is that of its most specific member.
bool parse_not(std::string_view s, std::size_t& i, SimpleSelector& out, Counts& counts, int depth) {
  const std::size_t close = scan_to(s, i, ")");
  if (close >= s.size() || depth > 4) return false;  // unclosed, or :not nested in :not in ... (nobody writes it)
  const std::string_view list = s.substr(i, close - i);
  Counts most;
  std::size_t p = 0;
  while (p <= list.size()) {
    const std::size_t comma = scan_to(list, p, ",");
    const std::string_view item = trim(list.substr(p, comma - p));
    std::vector<SimpleSelector> parts;
    Counts item_counts;
    std::size_t k = 0;
    if (item.empty() || !parse_parts(item, k, parts, item_counts, depth + 1) || k != item.size()) return false;
    if (item_counts.packed() > most.packed()) most = item_counts;
    out.alternatives.push_back(std::move(parts));
    p = comma + 1;
  }
  counts.ids += most.ids;
  counts.classes += most.classes;
  counts.types += most.types;
  out.kind = SimpleSelector::Kind::Not;
  i = close + 1;
  return true;
}

/// One compound from s[i]: an optional type or '*', then any number of #id .class [attr] :pseudo-class. Stops at
/// whitespace, a combinator or the end; false for anything it does not support.
bool parse_parts(std::string_view s, std::size_t& i, std::vector<SimpleSelector>& parts, Counts& counts, int depth) {
  if (i < s.size() && s[i] == '*') {
    parts.push_back({SimpleSelector::Kind::Universal, {}, {}, {}, {}});
    ++i;
  } else if (i < s.size() && is_name_char(s[i])) {
    parts.push_back({SimpleSelector::Kind::Type, {}, std::string(read_name(s, i)), {}, {}});
    ++counts.types;
  }
  while (i < s.size() && !is_space(s[i]) && s[i] != '>' && s[i] != '+' && s[i] != '~') {
    SimpleSelector part;
    const char c = s[i++];
    if (c == '#' || c == '.') {
      part.kind = c == '#' ? SimpleSelector::Kind::Id : SimpleSelector::Kind::Class;
      part.name = std::string(read_name(s, i));
      if (part.name.empty()) return false;
      ++(c == '#' ? counts.ids : counts.classes);
    } else if (c == '[') {
      if (!parse_attribute_selector(s, i, part)) return false;
      ++counts.classes;
    } else if (c == ':') {
      const std::string name = lower(read_name(s, i));
      if (name == "not" && i < s.size() && s[i] == '(') {
        ++i;
        if (!parse_not(s, i, part, counts, depth)) return false;
        parts.push_back(std::move(part));
        continue;
      }
      static constexpr std::string_view kNever[] = {"hover", "active", "focus", "focus-within", "focus-visible",
                                                   "visited", "target"};
      if (name == "first-child") {
        part.kind = SimpleSelector::Kind::FirstChild;
      } else if (name == "last-child") {
        part.kind = SimpleSelector::Kind::LastChild;
      } else if (name == "only-child") {
        part.kind = SimpleSelector::Kind::OnlyChild;
      } else if (name == "root") {
        part.kind = SimpleSelector::Kind::Root;
      } else if (name == "link" || name == "any-link") {
        part.kind = SimpleSelector::Kind::Link;
      } else if (std::find(std::begin(kNever), std::end(kNever), name) != std::end(kNever)) {
        part.kind = SimpleSelector::Kind::Never;
      } else {
        return false;  // other pseudo-classes (:nth-child, ...), pseudo-elements ("::" reads an empty name)
      }
      if (i < s.size() && s[i] == '(') return false;  // :first-child(...) and the like
      ++counts.classes;
    } else {
      return false;  // ',' (lists are split before), ')' or garbage
    }
    parts.push_back(std::move(part));
  }
  return !parts.empty();
}

}  // namespace

bool parse_selector(std::string_view text, Selector& out) {
  out = Selector{};
  const std::string_view s = trim(text);
  if (s.empty()) return false;
  Counts counts;
  std::size_t i = 0;
  Compound::Combinator pending = Compound::Combinator::None;
  while (i < s.size()) {
    Compound compound;
    compound.combinator = pending;
    if (!parse_parts(s, i, compound.parts, counts, 0)) return false;
    out.compounds.push_back(std::move(compound));
    // A combinator: whitespace (descendant), or '>' (child) / '+' (next sibling) with optional whitespace.
    bool space = false;
    while (i < s.size() && is_space(s[i])) ++i, space = true;
    if (i < s.size() && (s[i] == '>' || s[i] == '+')) {
      pending = s[i] == '>' ? Compound::Combinator::Child : Compound::Combinator::NextSibling;
      ++i;
      while (i < s.size() && is_space(s[i])) ++i;
      if (i >= s.size()) return false;
    } else if (i < s.size() && s[i] == '~') {
      return false;  // subsequent-sibling combinator: not supported
    } else if (space) {
      pending = Compound::Combinator::Descendant;
    }
  }
  if (out.compounds.empty()) return false;
  out.specificity = counts.packed();
  return true;
}

std::vector<std::size_t> StyleSheet::add(std::string_view text, std::size_t base_offset) {
  std::vector<std::size_t> dropped;
  const std::string clean = without_comments(text);
  const std::string_view s = clean;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    if (i >= s.size()) break;
    if (s.compare(i, 4, "<!--") == 0 || s.compare(i, 3, "-->") == 0) {  // CDO / CDC tokens are ignored
      i += s[i] == '<' ? 4 : 3;
      continue;
    }
    if (s[i] == '@') {
      // An at-rule: up to ';' or through its block (nested braces counted).
      const std::size_t end = scan_to(s, i, ";{");
      if (end < s.size() && s[end] == '{') {
        int depth = 0;
        std::size_t j = end;
        for (; j < s.size(); ++j) {
          if (s[j] == '{') ++depth;
          if (s[j] == '}' && --depth == 0) break;
        }
        i = j + 1;
      } else {
        i = end + 1;
      }
      continue;
    }
    const std::size_t open = scan_to(s, i, "{");
    if (open >= s.size()) {
      dropped.push_back(base_offset + i);
      break;
    }
    const std::size_t close = scan_to(s, open + 1, "}");
    const std::string_view prelude = s.substr(i, open - i);
    const std::string_view block = s.substr(open + 1, close - open - 1);
    std::vector<Declaration> declarations;
    declarations_of(block, base_offset + open + 1, declarations, nullptr);
    // A selector list is dropped whole when one member is invalid (CSS Selectors 4, section 4.1).
    std::vector<Selector> selectors;
    bool valid = true;
    std::size_t p = 0;
    while (p <= prelude.size()) {
      const std::size_t comma = scan_to(prelude, p, ",");
      Selector selector;
      if (!parse_selector(prelude.substr(p, comma - p), selector)) valid = false;
      selectors.push_back(std::move(selector));
      p = comma + 1;
    }
    if (!valid) {
      dropped.push_back(base_offset + i);
    } else {
      for (Selector& selector : selectors) {
        rules.push_back(Rule{std::move(selector), declarations, rules.size()});
      }
    }
    i = close + 1;
  }
  return dropped;
}

namespace {

constexpr int kMaxVarDepth = 16;
constexpr std::size_t kMaxVarResult = 64 * 1024;

/// Whether the bracket at v[paren] opens a var( function: "var" (any case) right before it, not the end of a
/// longer name.
bool is_var_call(std::string_view v, std::size_t paren) {
  return paren >= 3 && lower(v.substr(paren - 3, 3)) == "var" && (paren == 3 || !is_name_char(v[paren - 4]));
}

bool substitute_at(std::string_view v, const CustomProperties& custom, std::string& out, int depth) {
  if (depth > kMaxVarDepth) return false;
  std::size_t i = 0;
  while (i < v.size()) {
    const std::size_t at = v.find('(', i);
    const bool is_var = at != std::string_view::npos && at >= i + 3 && is_var_call(v, at);
    if (!is_var) {
      const std::size_t end = at == std::string_view::npos ? v.size() : at + 1;
      out.append(v.substr(i, end - i));
      i = end;
      continue;
    }
    out.append(v.substr(i, at - 3 - i));
    const std::size_t close = scan_to(v, at + 1, ")");
    if (close >= v.size()) return false;
    const std::string_view inside = v.substr(at + 1, close - at - 1);
    const std::size_t comma = scan_to(inside, 0, ",");
    const std::string name = lower(trim(inside.substr(0, comma)));
    if (name.size() < 3 || name[0] != '-' || name[1] != '-') return false;
    const auto it = custom.find(name);
    if (it != custom.end()) {
      if (!substitute_at(it->second, custom, out, depth + 1)) return false;
    } else if (comma < inside.size()) {
      if (!substitute_at(trim(inside.substr(comma + 1)), custom, out, depth + 1)) return false;
    } else {
      return false;
    }
    if (out.size() > kMaxVarResult) return false;
    i = close + 1;
  }
  return true;
}

}  // namespace

bool has_var(std::string_view value) {
  for (std::size_t at = value.find('('); at != std::string_view::npos; at = value.find('(', at + 1)) {
    if (is_var_call(value, at)) return true;
  }
  return false;
}

bool substitute_vars(std::string_view value, const CustomProperties& custom, std::string& out) {
  out.clear();
  return substitute_at(value, custom, out, 0);
}

namespace detail {

bool class_list_contains(std::string_view classes, std::string_view name) {
  std::size_t i = 0;
  while (i < classes.size()) {
    while (i < classes.size() && is_space(classes[i])) ++i;
    const std::size_t start = i;
    while (i < classes.size() && !is_space(classes[i])) ++i;
    if (i > start && classes.substr(start, i - start) == name) return true;
  }
  return false;
}

bool attribute_matches(const SimpleSelector& s, std::string_view value) {
  const std::string_view want = s.value;
  using M = SimpleSelector::Match;
  switch (s.match) {
    case M::Exists: return true;
    case M::Equals: return value == want;
    case M::Includes: return !want.empty() && class_list_contains(value, want);
    case M::DashMatch:
      return value == want || (value.size() > want.size() && value.substr(0, want.size()) == want &&
                               value[want.size()] == '-');
    case M::Prefix: return !want.empty() && value.substr(0, want.size()) == want;
    case M::Suffix: return !want.empty() && value.size() >= want.size() && value.substr(value.size() - want.size()) == want;
    case M::Substring: return !want.empty() && value.find(want) != std::string_view::npos;
  }
  return false;
}

}  // namespace detail

void sort_cascade(std::vector<Cascaded>& declarations) {
  std::stable_sort(declarations.begin(), declarations.end(), [](const Cascaded& a, const Cascaded& b) {
    return std::tie(a.origin, a.specificity, a.order) < std::tie(b.origin, b.specificity, b.order);
  });
}

}  // namespace vraster::svg::css
