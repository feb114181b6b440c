// svg_subset: XML well-formedness checks beyond pugixml's (see xml_check.hpp).
//
// The scan walks markup the way an XML tokenizer does: comments, CDATA sections, processing instructions and
// the DOCTYPE are skipped whole; start tags are read with their quoted attribute values; element depth is
// counted so that the end of the root element is known. The cost is one pass over the text.
#include "xml_check.hpp"

#include <charconv>
#include <cstdint>
#include <system_error>
#include <unordered_map>

#include "vraster/error.hpp"

namespace vraster::svg::detail {
namespace {

bool is_xml_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// XML's Char production.
bool is_xml_char(std::uint32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) || (c >= 0xE000 && c <= 0xFFFD) ||
         (c >= 0x10000 && c <= 0x10FFFF);
}

class Scanner {
 public:
  explicit Scanner(std::string_view text) : s_(text) {}

  std::optional<XmlProblem> run() {
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") i_ = 3;  // a byte order mark
    while (i_ < s_.size() && !problem_) {
      if (s_[i_] == '<') {
        markup();
      } else if (s_[i_] == '&') {
        if (depth_ == 0) report(i_, "text outside the root element");
        else reference();
      } else {
        if (depth_ == 0 && !is_xml_space(s_[i_])) {
          report(i_, roots_ > 0 ? "text after the end of the root element" : "text before the root element");
        }
        ++i_;
      }
    }
    return problem_;
  }

 private:
  void report(std::size_t at, std::string message) {
    if (!problem_) problem_ = XmlProblem{at, std::move(message)};
  }

  bool starts(std::string_view prefix) const { return s_.substr(i_, prefix.size()) == prefix; }

  /// Moves past the next `end` (or to the end of the text).
  void skip_past(std::string_view end) {
    const std::size_t k = s_.find(end, i_);
    i_ = k == std::string_view::npos ? s_.size() : k + end.size();
  }

  void markup() {
    if (starts("<!--")) return skip_past("-->");
    if (starts("<![CDATA[")) return skip_past("]]>");
    if (starts("<?")) return skip_past("?>");
    if (starts("<!")) return doctype();
    if (starts("</")) {
      skip_past(">");
      if (depth_ > 0) --depth_;
      return;
    }
    start_tag();
  }

  /// <!DOCTYPE ...>, with an internal subset in brackets whose declarations may hold '>' in quotes.
  void doctype() {
    has_doctype_ = true;
    int brackets = 0;
    char quote = 0;
    for (++i_; i_ < s_.size(); ++i_) {
      const char c = s_[i_];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '[') {
        ++brackets;
      } else if (c == ']') {
        --brackets;
      } else if (c == '>' && brackets <= 0) {
        ++i_;
        return;
      }
    }
  }

  void start_tag() {
    const std::size_t at = i_;
    if (depth_ == 0 && roots_ > 0) {
      report(at, "a second root element after the end of the first (XML allows one)");
      return;
    }
    char quote = 0;
    for (++i_; i_ < s_.size(); ++i_) {
      const char c = s_[i_];
      if (quote) {
        if (c == quote) {
          quote = 0;
        } else if (c == '<') {
          report(i_, "'<' inside an attribute value (write &lt;)");
          return;
        } else if (c == '&') {
          reference();
          --i_;  // reference() moved past the reference; the loop's ++i_ must not skip a character
        }
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        const bool empty = s_[i_ - 1] == '/';
        ++i_;
        if (depth_ == 0) ++roots_;
        if (!empty) ++depth_;
        return;
      }
    }
  }

  /// An entity or character reference at s_[i_] == '&'; moves past it.
  void reference() {
    const std::size_t at = i_;
    std::size_t end = at + 1;
    while (end < s_.size() && end - at < 64 && s_[end] != ';' && s_[end] != '&' && s_[end] != '<' &&
           !is_xml_space(s_[end]) && s_[end] != '"' && s_[end] != '\'')
      ++end;
    if (end >= s_.size() || s_[end] != ';' || end == at + 1) {
      report(at, "'&' that does not start an entity reference (write &amp;)");
      i_ = at + 1;
      return;
    }
    const std::string_view name = s_.substr(at + 1, end - at - 1);
    i_ = end + 1;
    if (name == "lt" || name == "gt" || name == "amp" || name == "apos" || name == "quot") return;
    if (name[0] == '#') {
      const bool hex = name.size() > 1 && name[1] == 'x';
      const std::string_view digits = name.substr(hex ? 2 : 1);
      std::uint32_t code = 0;
      const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
      if (digits.empty() || r.ec != std::errc() || r.ptr != digits.data() + digits.size() || !is_xml_char(code)) {
        report(at, "character reference " + quoted(s_.substr(at, end - at + 1)) +
                       " is not a character XML allows");
      }
      return;
    }
    report(at, "undefined entity " + quoted(s_.substr(at, end - at + 1)) +
                   (has_doctype_ ? " (not declared in the DOCTYPE's internal subset; external DTDs are not read)"
                                 : " (XML predefines only &lt; &gt; &amp; &apos; &quot;)"));
  }

  std::string_view s_;
  std::size_t i_ = 0;
  int depth_ = 0;
  int roots_ = 0;
  bool has_doctype_ = false;
  std::optional<XmlProblem> problem_;
};

/// Reads the entity declarations of the internal subset, then copies the text with their references replaced.
class EntityExpander {
 public:
  explicit EntityExpander(std::string_view text) : s_(text) {}

  EntityExpansion run() {
    const std::size_t after_doctype = read_doctype();
    if (problem_ || entities_.empty()) return {{}, problem_};
    out_.reserve(s_.size());
    out_.append(s_.substr(0, after_doctype));
    bool replaced = false;
    copy_expanding(s_.substr(after_doctype), after_doctype, 0, replaced);
    if (problem_ || !replaced) return {{}, problem_};
    return {std::move(out_), std::nullopt};
  }

 private:
  struct Entity {
    std::string_view name;
    std::string_view value;
    bool external = false;
    bool expanding = false;  // on the stack of values being expanded (a reference to it closes a loop)
  };

  void report(std::size_t at, std::string message) {
    if (!problem_) problem_ = XmlProblem{at, std::move(message)};
  }

  /// Moves i past a quoted literal starting at s_[i]; false when it does not end.
  bool skip_literal(std::size_t& i) const {
    const std::size_t end = s_.find(s_[i], i + 1);
    if (end == std::string_view::npos) return false;
    i = end + 1;
    return true;
  }

  static bool is_name_char(char c) {
    return c != ';' && c != '&' && c != '<' && c != '>' && c != '"' && c != '\'' && c != '%' && c != '[' &&
           c != ']' && !is_xml_space(c);
  }

  /// Finds the DOCTYPE in the prolog and reads its internal subset; returns the offset just past it (0 when
  /// there is none).
  std::size_t read_doctype() {
    std::size_t i = s_.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
    for (;;) {  // the prolog: white space, the XML declaration, comments, processing instructions
      while (i < s_.size() && is_xml_space(s_[i])) ++i;
      const std::string_view rest = s_.substr(i);
      std::size_t end = std::string_view::npos;
      if (rest.starts_with("<?")) end = s_.find("?>", i), end = end == std::string_view::npos ? end : end + 2;
      else if (rest.starts_with("<!--")) end = s_.find("-->", i), end = end == std::string_view::npos ? end : end + 3;
      else break;
      if (end == std::string_view::npos) return 0;
      i = end;
    }
    if (!s_.substr(i).starts_with("<!DOCTYPE")) return 0;
    for (i += 9; i < s_.size() && s_[i] != '[' && s_[i] != '>';) {  // name and external id
      if (s_[i] == '"' || s_[i] == '\'') {
        if (!skip_literal(i)) return 0;
      } else {
        ++i;
      }
    }
    if (i >= s_.size()) return 0;
    if (s_[i] == '[') read_internal_subset(++i);
    while (i < s_.size() && s_[i] != '>') ++i;
    return i < s_.size() ? i + 1 : 0;
  }

  /// Declarations up to the closing ']'; i ends on it.
  void read_internal_subset(std::size_t& i) {
    while (i < s_.size() && s_[i] != ']' && !problem_) {
      const std::string_view rest = s_.substr(i);
      if (rest.starts_with("<!--")) {
        const std::size_t end = s_.find("-->", i);
        i = end == std::string_view::npos ? s_.size() : end + 3;
      } else if (rest.starts_with("<!ENTITY")) {
        entity_declaration(i);
      } else if (rest.starts_with("<")) {  // <!ELEMENT, <!ATTLIST, <!NOTATION, <?pi?>: skipped to '>'
        while (i < s_.size() && s_[i] != '>') {
          if ((s_[i] == '"' || s_[i] == '\'') && !skip_literal(i)) i = s_.size();
          else ++i;
        }
        ++i;
      } else {
        ++i;  // white space, parameter entity references
      }
    }
  }

  /// <!ENTITY name "value"> or <!ENTITY name SYSTEM "uri"> (kept as external); parameter entities are skipped.
  void entity_declaration(std::size_t& i) {
    const std::size_t at = i;
    i += 8;
    while (i < s_.size() && is_xml_space(s_[i])) ++i;
    const bool parameter = i < s_.size() && s_[i] == '%';
    const std::size_t name_start = i;
    while (i < s_.size() && is_name_char(s_[i])) ++i;
    const std::string_view name = s_.substr(name_start, i - name_start);
    while (i < s_.size() && is_xml_space(s_[i])) ++i;
    Entity e{name, {}, true, false};
    if (i < s_.size() && (s_[i] == '"' || s_[i] == '\'')) {
      const std::size_t value_start = i + 1;
      if (!skip_literal(i)) return report(at, "entity declaration without the end of its value");
      e.value = s_.substr(value_start, i - 1 - value_start);
      e.external = false;
    }
    while (i < s_.size() && s_[i] != '>') {  // the rest: SYSTEM / PUBLIC literals, NDATA
      if ((s_[i] == '"' || s_[i] == '\'') && !skip_literal(i)) i = s_.size();
      else ++i;
    }
    ++i;
    if (parameter || name.empty()) return;
    if (entities_.size() == kMaxEntities) {
      return report(at, "too many entity declarations (the limit is " + std::to_string(kMaxEntities) + ")");
    }
    entities_.emplace(name, e);  // XML: the first declaration of a name binds (emplace keeps it)
  }

  Entity* find(std::string_view name) {
    const auto it = entities_.find(name);
    return it == entities_.end() ? nullptr : &it->second;
  }

  /// Appends `part` to out_, references to declared entities replaced. `at` is the offset in the document that
  /// errors are reported at: the part's own offset at the top level, the outermost reference's inside values.
  void copy_expanding(std::string_view part, std::size_t at, int depth, bool& replaced) {
    std::size_t i = 0;
    while (i < part.size() && !problem_) {
      const std::size_t next = part.find_first_of("<&", i);
      if (next == std::string_view::npos) {
        out_.append(part.substr(i));
        break;
      }
      out_.append(part.substr(i, next - i));
      i = next;
      const std::string_view rest = part.substr(i);
      if (part[i] == '<') {
        std::string_view end_mark;
        if (rest.starts_with("<!--")) end_mark = "-->";
        else if (rest.starts_with("<![CDATA[")) end_mark = "]]>";
        else if (rest.starts_with("<?")) end_mark = "?>";
        const std::size_t end = end_mark.empty() ? i + 1 : part.find(end_mark, i);
        const std::size_t stop = end == std::string_view::npos ? part.size() : end + end_mark.size();
        out_.append(part.substr(i, stop - i));
        i = stop;
        continue;
      }
      std::size_t end = i + 1;
      while (end < part.size() && end - i < 64 && is_name_char(part[end])) ++end;
      Entity* e = end < part.size() && part[end] == ';' ? find(part.substr(i + 1, end - i - 1)) : nullptr;
      if (!e) {  // a predefined or character reference, or an undefined one (find_xml_problem reports it)
        out_.push_back('&');
        ++i;
        continue;
      }
      const std::size_t where = depth == 0 ? at + i : at;
      const std::string ref = "'&" + std::string(e->name) + ";'";
      if (e->external) return report(where, "entity " + ref + " is external; external entities are never loaded");
      if (e->expanding) return report(where, "entity " + ref + " refers to itself");
      if (depth == 0) outermost_ = e->name;
      if (depth + 1 > kMaxEntityNesting) {
        return report(where, "entity '&" + std::string(outermost_) + ";' nests entities too deeply (the limit is " +
                                 std::to_string(kMaxEntityNesting) + " levels; " + ref + " is one too many)");
      }
      e->expanding = true;
      copy_expanding(e->value, where, depth + 1, replaced);
      e->expanding = false;
      replaced = true;
      if (!problem_ && out_.size() > s_.size() + kMaxEntityGrowth) {
        return report(where, "expanding entity '&" + std::string(outermost_) + ";' makes the document more than " +
                                 std::to_string(kMaxEntityGrowth >> 20) + " MiB larger (the limit)");
      }
      i = end + 1;
    }
  }

  std::string_view s_;
  std::unordered_map<std::string_view, Entity> entities_;
  std::string out_;
  std::string_view outermost_;  // the entity referred to in the document whose expansion is under way
  std::optional<XmlProblem> problem_;
};

}  // namespace

std::optional<XmlProblem> find_xml_problem(std::string_view text) { return Scanner(text).run(); }

EntityExpansion expand_internal_entities(std::string_view text) { return EntityExpander(text).run(); }

}  // namespace vraster::svg::detail
