// svg_subset: XML well-formedness checks beyond pugixml's (see xml_check.hpp).
//
// The scan walks markup the way an XML tokenizer does: comments, CDATA sections, processing instructions and
// the DOCTYPE are skipped whole; start tags are read with their quoted attribute values; element depth is
// counted so that the end of the root element is known. The cost is one pass over the text.
#include "xml_check.hpp"

#include <charconv>
#include <cstdint>
#include <system_error>

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
                   (has_doctype_ ? " (entities declared in a DOCTYPE are not supported)"
                                 : " (XML predefines only &lt; &gt; &amp; &apos; &quot;)"));
  }

  std::string_view s_;
  std::size_t i_ = 0;
  int depth_ = 0;
  int roots_ = 0;
  bool has_doctype_ = false;
  std::optional<XmlProblem> problem_;
};

}  // namespace

std::optional<XmlProblem> find_xml_problem(std::string_view text) { return Scanner(text).run(); }

}  // namespace vraster::svg::detail
