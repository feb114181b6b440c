// svg_subset: SVG text -> Document.
//
// pugixml parses a private copy of the text in place, so every name and attribute value it hands back points into
// that copy: pointer - buffer start is the byte offset in the original text, which gives exact line:column
// positions for every message. The element walk carries the inherited properties and the current transform
// down the tree and emits a fill and/or a stroke DrawItem per shape, in document (= paint) order, fill first.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <pugixml.hpp>
#include <string>
#include <utility>
#include <vector>

#include "scan.hpp"
#include "xml_check.hpp"
#include "svg_subset/svg.hpp"

namespace vraster::svg {

ParseError::ParseError(const std::string& file, int line, int column, const std::string& message)
    : Error(line > 0 ? file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message
                     : file + ": " + message),
      line_(line),
      column_(column),
      message_(message) {}

PathDataError::PathDataError(std::size_t offset, const std::string& message)
    : Error("path data, offset " + std::to_string(offset) + ": " + message), offset_(offset), message_(message) {}

namespace {

using detail::iequals;
using detail::NumberScan;
using detail::scan_number;
using detail::trim;

constexpr int kMaxDepth = 256;
constexpr std::size_t kMaxElements = 1'000'000;
constexpr std::size_t kMaxWarningsPerKind = 20;

/// Maps byte offsets of the source text to 1-based line and column (column counts bytes).
class LineIndex {
 public:
  explicit LineIndex(std::string_view text) {
    starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') starts_.push_back(i + 1);
    }
  }
  std::pair<int, int> position(std::size_t offset) const {
    const auto next = std::upper_bound(starts_.begin(), starts_.end(), offset);  // never begin(): starts_[0] == 0
    const auto line = static_cast<std::size_t>(next - starts_.begin());
    return {static_cast<int>(line), static_cast<int>(offset - starts_[line - 1] + 1)};
  }

 private:
  std::vector<std::size_t> starts_;
};

enum class PaintKind : std::uint8_t { None, Solid, CurrentColor };

struct Paint {
  PaintKind kind = PaintKind::Solid;
  Color color{0, 0, 0, 1};
};

/// The properties in effect on an element.
struct Style {
  // Inherited.
  Paint fill;
  float fill_opacity = 1;
  FillRule fill_rule = FillRule::NonZero;
  Paint stroke{PaintKind::None, {}};
  float stroke_opacity = 1;
  StrokeStyle stroke_style;  // SVG defaults: width 1, butt, miter, miter limit 4, no dashes
  Color current_color{0, 0, 0, 1};  // the `color` property, used by currentColor
  bool visible = true;
  // Not inherited in SVG; the product down the tree approximates group opacity.
  float opacity = 1;
};

enum class Property {
  Unknown,
  Fill,
  FillOpacity,
  FillRule,
  Stroke,
  StrokeOpacity,
  StrokeWidth,
  StrokeLinecap,
  StrokeLinejoin,
  StrokeMiterlimit,
  StrokeDasharray,
  StrokeDashoffset,
  Opacity,
  Color,
  Display,
  Visibility,
  Unsupported
};

Property property_of(std::string_view name, bool css) {
  // Presentation attributes are case-sensitive XML names; CSS property names are not.
  auto is = [&](std::string_view p) { return css ? iequals(name, p) : name == p; };
  if (is("fill")) return Property::Fill;
  if (is("fill-opacity")) return Property::FillOpacity;
  if (is("fill-rule")) return Property::FillRule;
  if (is("stroke")) return Property::Stroke;
  if (is("stroke-opacity")) return Property::StrokeOpacity;
  if (is("stroke-width")) return Property::StrokeWidth;
  if (is("stroke-linecap")) return Property::StrokeLinecap;
  if (is("stroke-linejoin")) return Property::StrokeLinejoin;
  if (is("stroke-miterlimit")) return Property::StrokeMiterlimit;
  if (is("stroke-dasharray")) return Property::StrokeDasharray;
  if (is("stroke-dashoffset")) return Property::StrokeDashoffset;
  if (is("opacity")) return Property::Opacity;
  if (is("color")) return Property::Color;
  if (is("display")) return Property::Display;
  if (is("visibility")) return Property::Visibility;
  if (is("clip-path") || is("mask") || is("filter")) return Property::Unsupported;
  return Property::Unknown;
}

enum class Axis { X, Y, Other };

struct ViewBox {
  double x, y, width, height;
};

class Builder {
 public:
  Builder(std::string_view text, const std::string& file) : text_(text), file_(file), lines_(text) {}

  Document run() {
    buffer_.assign(text_.begin(), text_.end());
    pugi::xml_document xml;
    const pugi::xml_parse_result result =
        xml.load_buffer_inplace(buffer_.data(), buffer_.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!result) {
      const auto offset = static_cast<std::size_t>(std::max<std::ptrdiff_t>(result.offset, 0));
      fail(std::min(offset, text_.size()), std::string("malformed XML: ") + result.description());
    }
    if (const std::optional<detail::XmlProblem> problem = detail::find_xml_problem(text_))
      fail(problem->offset, "malformed XML: " + problem->message);
    check_unique_attributes(xml);
    const pugi::xml_node root = xml.document_element();
    if (std::string_view(root.name()) != "svg") {
      fail(element_offset(root), "the root element is <" + printable(root.name()) + ">, expected <svg>");
    }
    doc_.file = file_;
    set_up_viewport(root);
    element(root, Style{}, Affine{}, 1);
    finish_warnings();
    return std::move(doc_);
  }

 private:
  /// XML: an attribute name appears at most once in a start tag. Checks every element, drawn or not, walking
  /// the tree without recursion; names are sorted when an element has many, so the cost stays n log n.
  void check_unique_attributes(const pugi::xml_document& xml) const {
    std::vector<pugi::xml_attribute> attrs;
    pugi::xml_node node = xml.first_child();
    while (node) {
      if (node.type() == pugi::node_element) {
        attrs.assign(node.attributes_begin(), node.attributes_end());
        const auto by_name = [](pugi::xml_attribute a, pugi::xml_attribute b) {
          return std::strcmp(a.name(), b.name()) < 0;
        };
        std::stable_sort(attrs.begin(), attrs.end(), by_name);
        for (std::size_t i = 1; i < attrs.size(); ++i) {
          if (std::strcmp(attrs[i - 1].name(), attrs[i].name()) == 0) {
            fail(offset_of(attrs[i].name()),
                 "malformed XML: duplicate attribute " + quoted(attrs[i].name()) + " on <" + printable(node.name()) + ">");
          }
        }
      }
      if (node.first_child()) {
        node = node.first_child();
        continue;
      }
      while (node && !node.next_sibling()) node = node.parent();
      if (node) node = node.next_sibling();
    }
  }

  // ---- positions and messages ----

  [[noreturn]] void fail(std::size_t offset, const std::string& message) const {
    const auto [line, column] = lines_.position(offset);
    throw ParseError(file_, line, column, message);
  }

  /// Records a warning of a kind (a short plural noun phrase, "unsupported elements"). Only the first
  /// kMaxWarningsPerKind of a kind are kept; the rest are counted and summarised at the end (finish_warnings).
  void warn(std::string_view kind, std::size_t offset, const std::string& message) {
    auto it = std::find_if(warning_counts_.begin(), warning_counts_.end(),
                           [&](const WarningCount& c) { return c.kind == kind; });
    if (it == warning_counts_.end()) it = warning_counts_.insert(warning_counts_.end(), WarningCount{kind, 0, 0});
    if (++it->count > kMaxWarningsPerKind) {
      if (it->count == kMaxWarningsPerKind + 1) it->first_dropped = offset;
      return;
    }
    const auto [line, column] = lines_.position(offset);
    doc_.warnings.push_back(std::to_string(line) + ":" + std::to_string(column) + ": " + message);
  }

  /// Appends one line per kind of warning that was cut short: "... and K more (kind), the first at L:C".
  void finish_warnings() {
    for (const WarningCount& c : warning_counts_) {
      if (c.count <= kMaxWarningsPerKind) continue;
      const auto [line, column] = lines_.position(c.first_dropped);
      doc_.warnings.push_back(std::to_string(line) + ":" + std::to_string(column) + ": ... and " +
                              std::to_string(c.count - kMaxWarningsPerKind) + " more warnings about " +
                              std::string(c.kind) + " (not shown)");
    }
  }

  bool in_buffer(const char* p) const { return p >= buffer_.data() && p <= buffer_.data() + buffer_.size(); }
  std::size_t offset_of(const char* p) const { return in_buffer(p) ? static_cast<std::size_t>(p - buffer_.data()) : 0; }

  /// Offset of '<' of an element.
  std::size_t element_offset(pugi::xml_node node) const {
    const std::size_t name = offset_of(node.name());
    return name > 0 ? name - 1 : 0;
  }

  /// Maps decoded byte offsets of one attribute value to source offsets. pugixml decodes values in place
  /// (entities, CR LF -> one space), which can only shorten them, so the value starts where it did; past the
  /// first entity the source has to be walked to map decoded bytes back to source bytes. The walk resumes
  /// where the last call stopped, so increasing offsets (the declarations of a style attribute) cost one pass.
  class ValueOffsets {
   public:
    ValueOffsets(const Builder& b, pugi::xml_attribute attr) : text_(b.text_) {
      start_ = b.in_buffer(attr.value()) ? b.offset_of(attr.value()) : b.offset_of(attr.name());
      known_ = b.in_buffer(attr.value());
      raw_ = start_;
    }
    std::size_t at(std::size_t decoded) {
      if (!known_) return start_;
      if (decoded < done_) {
        raw_ = start_;
        done_ = 0;
      }
      while (done_ < decoded && raw_ < text_.size()) {
        const char c = text_[raw_];
        if (c == '&') {
          const std::size_t semicolon = text_.substr(raw_, 13).find(';');
          if (semicolon != std::string_view::npos) {
            done_ += entity_length(text_.substr(raw_, semicolon + 1));
            raw_ += semicolon + 1;
            continue;
          }
        } else if (c == '\r' && raw_ + 1 < text_.size() && text_[raw_ + 1] == '\n') {
          ++raw_;
        }
        ++raw_;
        ++done_;
      }
      return raw_;
    }

   private:
    std::string_view text_;
    std::size_t start_ = 0, raw_ = 0, done_ = 0;
    bool known_ = false;
  };

  /// Source offset of byte `decoded` of an attribute's value.
  std::size_t value_offset(pugi::xml_attribute attr, std::size_t decoded = 0) const {
    return ValueOffsets(*this, attr).at(decoded);
  }

  /// How many bytes pugixml decodes an entity reference ("&amp;", "&#x4e00;") into.
  static std::size_t entity_length(std::string_view ref) {
    if (ref == "&lt;" || ref == "&gt;" || ref == "&amp;" || ref == "&apos;" || ref == "&quot;") return 1;
    if (ref.size() > 3 && ref[1] == '#') {
      const bool hex = ref[2] == 'x';
      std::uint32_t code = 0;
      const std::string_view digits = ref.substr(hex ? 3 : 2, ref.size() - (hex ? 4 : 3));
      const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
      if (r.ec == std::errc() && r.ptr == digits.data() + digits.size()) {
        return code < 0x80 ? 1 : code < 0x800 ? 2 : code < 0x10000 ? 3 : 4;
      }
    }
    return ref.size();  // unknown entities are kept as written
  }

  // ---- values ----

  bool parse_length(std::string_view v, Axis axis, double& out) const {
    std::size_t pos = 0;
    double number = 0;
    if (scan_number(v, pos, number) != NumberScan::Ok) return false;
    const std::string_view unit = v.substr(pos);
    // CSS absolute units at 96 px per inch; em and ex at the default 16px font.
    static constexpr std::pair<std::string_view, double> kUnits[] = {
        {"", 1},    {"px", 1}, {"pt", 96.0 / 72.0}, {"pc", 16}, {"mm", 96.0 / 25.4}, {"cm", 96.0 / 2.54}, {"in", 96},
        {"em", 16}, {"ex", 8}};
    double scale = 0;
    for (const auto& [name, factor] : kUnits) {
      if (iequals(unit, name)) scale = factor;
    }
    if (unit == "%") {
      const double w = percent_width_, h = percent_height_;
      const double reference = axis == Axis::X ? w : axis == Axis::Y ? h : std::sqrt((w * w + h * h) / 2);
      scale = reference / 100;
    } else if (scale == 0) {
      return false;
    }
    out = number * scale;
    return std::isfinite(out);
  }

  /// A length attribute, or nothing when absent; throws when malformed.
  std::optional<double> length_attribute(pugi::xml_node node, const char* name, Axis axis) const {
    const pugi::xml_attribute attr = node.attribute(name);
    if (!attr) return std::nullopt;
    const std::string_view raw = attr.value();
    const std::string_view v = trim(raw);
    double out = 0;
    if (!parse_length(v, axis, out)) {
      fail(value_offset(attr, static_cast<std::size_t>(v.data() - raw.data())),
           std::string("invalid length for ") + name + ": " + quoted(v));
    }
    return out;
  }

  float parse_opacity(std::string_view v, std::size_t offset, std::string_view property) const {
    std::size_t pos = 0;
    double value = 0;
    if (scan_number(v, pos, value) == NumberScan::Ok) {
      if (pos < v.size() && v[pos] == '%') {
        value /= 100;
        ++pos;
      }
      if (pos == v.size()) return static_cast<float>(std::clamp(value, 0.0, 1.0));
    }
    fail(offset, "invalid " + std::string(property) + " " + quoted(v) + " (expected a number from 0 to 1)");
  }

  Paint parse_paint(std::string_view v, std::size_t offset, std::string_view property) {
    if (iequals(v, "currentColor")) return Paint{PaintKind::CurrentColor, {}};
    if (detail::istarts_with(v, "url(")) {
      // Gradients and patterns: SVG allows a fallback colour after the reference, which is what we can draw.
      const std::size_t close = v.find(')');
      if (close == std::string_view::npos) fail(offset, "invalid " + std::string(property) + ": unterminated url(");
      const std::string_view fallback = trim(v.substr(close + 1));
      if (fallback.empty()) {
        warn("paint servers", offset, "paint servers (" + printable(v.substr(0, close + 1)) + ") are not supported yet; " +
                         std::string(property) + " treated as none");
        return Paint{PaintKind::None, {}};
      }
      warn("paint servers", offset, "paint servers are not supported yet; using the fallback colour " + quoted(fallback));
      return parse_paint(fallback, offset + static_cast<std::size_t>(fallback.data() - v.data()), property);
    }
    bool none = false;
    const std::optional<Color> color = parse_color(v, none);
    if (none) return Paint{PaintKind::None, {}};
    if (!color) fail(offset, "invalid colour for " + std::string(property) + ": " + quoted(v));
    return Paint{PaintKind::Solid, *color};
  }

  /// A length property value (units and percentages as for attributes; percentages of the normalized diagonal).
  double length_property(std::string_view v, std::size_t offset, std::string_view property) const {
    double out = 0;
    if (!parse_length(v, Axis::Other, out)) fail(offset, "invalid length for " + std::string(property) + ": " + quoted(v));
    return out;
  }

  /// stroke-dasharray: "none" or lengths separated by commas and/or whitespace. SVG: a negative value makes the
  /// list invalid, which draws a solid stroke (warning). Odd counts and all-zero lists are the stroker's business.
  std::vector<double> parse_dash_array(std::string_view v, std::size_t offset) {
    if (v == "none") return {};
    std::vector<double> dashes;
    std::size_t pos = 0;
    if (v.empty()) fail(offset, "invalid stroke-dasharray '' (expected none or a list of lengths)");
    while (pos < v.size()) {
      const std::size_t start = pos;
      while (pos < v.size() && !detail::is_wsp(v[pos]) && v[pos] != ',') ++pos;
      double length = 0;
      if (pos == start || !parse_length(v.substr(start, pos - start), Axis::Other, length)) {
        fail(offset + start, "invalid stroke-dasharray " + quoted(v) + " (expected none or a list of lengths)");
      }
      dashes.push_back(length);
      if (detail::skip_comma_wsp(v, pos) && pos == v.size())
        fail(offset + pos, "invalid stroke-dasharray " + quoted(v) + ": expected a length after ','");
    }
    if (std::any_of(dashes.begin(), dashes.end(), [](double d) { return d < 0; })) {
      warn("dash patterns", offset, "negative value in stroke-dasharray " + quoted(v) + ", the stroke is drawn solid");
      return {};
    }
    return dashes;
  }

  // ---- properties ----

  /// Applies one declaration to `style`. Returns false for display:none.
  bool apply(Property property, std::string_view name, std::string_view v, std::size_t offset, Style& style,
             float& own_opacity) {
    if (v == "inherit") return true;  // the inherited value is already in `style`
    switch (property) {
      case Property::Fill:
        style.fill = parse_paint(v, offset, "fill");
        break;
      case Property::FillOpacity:
        style.fill_opacity = parse_opacity(v, offset, "fill-opacity");
        break;
      case Property::FillRule:
        if (v == "nonzero")
          style.fill_rule = FillRule::NonZero;
        else if (v == "evenodd")
          style.fill_rule = FillRule::EvenOdd;
        else
          fail(offset, "invalid fill-rule " + quoted(v) + " (expected nonzero or evenodd)");
        break;
      case Property::Stroke:
        style.stroke = parse_paint(v, offset, "stroke");
        break;
      case Property::StrokeOpacity:
        style.stroke_opacity = parse_opacity(v, offset, "stroke-opacity");
        break;
      case Property::StrokeWidth: {
        const double width = length_property(v, offset, "stroke-width");
        if (width < 0)
          warn("stroke widths", offset, "negative stroke-width " + quoted(v) + ", ignored");
        else
          style.stroke_style.width = width;
        break;
      }
      case Property::StrokeLinecap:
        if (!parse_line_cap(v, style.stroke_style.cap))
          fail(offset, "invalid stroke-linecap " + quoted(v) + " (expected butt, round or square)");
        break;
      case Property::StrokeLinejoin:
        if (v == "miter-clip" || v == "arcs") {
          warn("line joins", offset, "stroke-linejoin " + quoted(v) + " is not supported yet, using miter");
          style.stroke_style.join = LineJoin::Miter;
        } else if (!parse_line_join(v, style.stroke_style.join)) {
          fail(offset, "invalid stroke-linejoin " + quoted(v) + " (expected miter, round or bevel)");
        }
        break;
      case Property::StrokeMiterlimit: {
        std::size_t pos = 0;
        double limit = 0;
        if (scan_number(v, pos, limit) != NumberScan::Ok || pos != v.size())
          fail(offset, "invalid stroke-miterlimit " + quoted(v) + " (expected a number)");
        if (limit < 1)
          warn("miter limits", offset, "stroke-miterlimit " + quoted(v) + " is below 1, ignored");
        else
          style.stroke_style.miter_limit = limit;
        break;
      }
      case Property::StrokeDasharray:
        style.stroke_style.dashes = parse_dash_array(v, offset);
        break;
      case Property::StrokeDashoffset:
        style.stroke_style.dash_offset = length_property(v, offset, "stroke-dashoffset");
        break;
      case Property::Opacity:
        own_opacity = parse_opacity(v, offset, "opacity");
        break;
      case Property::Color: {
        if (iequals(v, "currentColor")) break;  // same as inherit
        bool none = false;
        const std::optional<Color> color = parse_color(v, none);
        if (!color) fail(offset, "invalid colour for color: " + quoted(v));
        style.current_color = *color;
        break;
      }
      case Property::Display:
        if (v == "none") return false;
        break;
      case Property::Visibility:
        if (v == "visible")
          style.visible = true;
        else if (v == "hidden" || v == "collapse")
          style.visible = false;
        else
          warn("visibility", offset, "unknown visibility " + quoted(v) + ", ignored");
        break;
      case Property::Unsupported:
        if (v != "none" && std::find(warned_once_.begin(), warned_once_.end(), name) == warned_once_.end()) {
          warned_once_.emplace_back(name);
          warn("unsupported properties", offset, printable(name) + " is not supported yet, ignored (reported once)");
        }
        break;
      case Property::Unknown:
        break;
    }
    return true;
  }

  /// Applies the presentation attributes, then the style attribute (which wins). Returns false for display:none.
  bool apply_properties(pugi::xml_node node, Style& style, float& own_opacity) {
    bool displayed = true;
    for (const pugi::xml_attribute attr : node.attributes()) {
      const std::string_view name = attr.name();
      const Property property = property_of(name, false);
      if (property == Property::Unknown) continue;
      const std::string_view raw = attr.value();
      const std::string_view v = trim(raw);
      displayed &= apply(property, name, v, value_offset(attr, static_cast<std::size_t>(v.data() - raw.data())), style,
                         own_opacity);
    }
    const pugi::xml_attribute style_attr = node.attribute("style");
    if (!style_attr) return displayed;
    // "name: value; name: value" (CSS comments and escapes are not supported).
    const std::string_view css = style_attr.value();
    ValueOffsets offsets(*this, style_attr);
    std::size_t pos = 0;
    while (pos < css.size()) {
      std::size_t end = css.find(';', pos);
      if (end == std::string_view::npos) end = css.size();
      const std::string_view declaration = css.substr(pos, end - pos);
      const std::size_t colon = declaration.find(':');
      if (colon == std::string_view::npos) {
        if (!trim(declaration).empty()) {
          warn("style declarations", offsets.at(pos), "malformed style declaration " + quoted(trim(declaration)) + ", ignored");
        }
      } else {
        const std::string_view name = trim(declaration.substr(0, colon));
        std::string_view v = trim(declaration.substr(colon + 1));
        if (v.size() >= 10 && iequals(v.substr(v.size() - 10), "!important")) v = trim(v.substr(0, v.size() - 10));
        const Property property = property_of(name, true);
        if (property != Property::Unknown) {
          displayed &=
              apply(property, name, v, offsets.at(static_cast<std::size_t>(v.data() - css.data())), style, own_opacity);
        }
      }
      pos = end + 1;
    }
    return displayed;
  }

  // ---- the root viewport ----

  ViewBox parse_view_box(pugi::xml_attribute attr) const {
    const std::string_view s = attr.value();
    std::size_t pos = 0;
    double v[4];
    detail::skip_wsp(s, pos);
    for (int i = 0; i < 4; ++i) {
      if (i > 0) detail::skip_comma_wsp(s, pos);
      if (scan_number(s, pos, v[i]) != NumberScan::Ok) {
        fail(value_offset(attr, pos),
             "invalid viewBox " + quoted(s) + " (expected four numbers: min-x min-y width height)");
      }
    }
    detail::skip_wsp(s, pos);
    if (pos != s.size())
      fail(value_offset(attr, pos), "invalid viewBox " + quoted(s) + ": unexpected text after four numbers");
    if (!(v[2] > 0 && v[3] > 0)) fail(value_offset(attr), "viewBox width and height must be positive, got " + quoted(s));
    return ViewBox{v[0], v[1], v[2], v[3]};
  }

  /// A size of the root element; nothing when absent, "auto", or a percentage (there is no enclosing viewport).
  std::optional<double> root_size(pugi::xml_node root, const char* name) {
    const pugi::xml_attribute attr = root.attribute(name);
    if (!attr) return std::nullopt;
    const std::string_view raw = attr.value();
    const std::string_view v = trim(raw);
    const std::size_t offset = value_offset(attr, static_cast<std::size_t>(v.data() - raw.data()));
    if (v == "auto") return std::nullopt;
    if (!v.empty() && v.back() == '%') {
      warn("root sizes", offset, std::string(name) + " " + quoted(v) +
                       " is relative to an enclosing viewport, which a file does not have; using the viewBox size");
      return std::nullopt;
    }
    double value = 0;
    if (!parse_length(v, Axis::Other, value)) fail(offset, std::string("invalid ") + name + " " + quoted(v));
    if (!(value > 0)) fail(offset, std::string(name) + " must be positive, got " + quoted(v));
    return value;
  }

  /// The viewBox -> viewport transform for a preserveAspectRatio value (SVG 1.1 section 7.8).
  Affine view_box_transform(const ViewBox& vb, double width, double height, pugi::xml_attribute aspect) {
    double align_x = 0.5, align_y = 0.5;  // xMidYMid
    bool none = false, slice = false;
    if (aspect) {
      bool valid = true;
      std::string_view s = trim(aspect.value());
      auto next_word = [&s] {
        s = trim(s);
        std::size_t end = 0;
        while (end < s.size() && !detail::is_wsp(s[end])) ++end;
        const std::string_view word = s.substr(0, end);
        s.remove_prefix(end);
        return word;
      };
      std::string_view word = next_word();
      if (word == "defer") word = next_word();
      if (word == "none") {
        none = true;
      } else if (word.size() == 8 && word[0] == 'x' && word[4] == 'Y') {
        auto align = [&valid](std::string_view part) {
          if (part == "Min") return 0.0;
          if (part == "Mid") return 0.5;
          if (part == "Max") return 1.0;
          valid = false;
          return 0.5;
        };
        align_x = align(word.substr(1, 3));
        align_y = align(word.substr(5, 3));
      } else {
        valid = false;
      }
      const std::string_view mode = next_word();
      if (mode == "slice")
        slice = true;
      else if (!mode.empty() && mode != "meet")
        valid = false;
      if (!trim(s).empty()) valid = false;
      if (!valid) {
        warn("preserveAspectRatio", value_offset(aspect), "invalid preserveAspectRatio " + quoted(aspect.value()) + ", using xMidYMid meet");
        align_x = align_y = 0.5;
        none = slice = false;
      }
    }
    const double sx = width / vb.width, sy = height / vb.height;
    if (none) return Affine{sx, 0, 0, sy, -vb.x * sx, -vb.y * sy};
    const double s = slice ? std::max(sx, sy) : std::min(sx, sy);
    const double tx = -vb.x * s + align_x * (width - vb.width * s);
    const double ty = -vb.y * s + align_y * (height - vb.height * s);
    return Affine{s, 0, 0, s, tx, ty};
  }

  void set_up_viewport(pugi::xml_node root) {
    std::optional<ViewBox> vb;
    if (const pugi::xml_attribute attr = root.attribute("viewBox")) vb = parse_view_box(attr);
    std::optional<double> width = root_size(root, "width");
    std::optional<double> height = root_size(root, "height");
    if (!width || !height) {
      if (!vb) {
        const char* missing = !width && !height ? "width and height" : !width ? "a width" : "a height";
        fail(element_offset(root), std::string("the root <svg> needs ") + missing + " (or a viewBox)");
      }
      // One size given: the other follows the viewBox's aspect ratio, as browsers do.
      if (width && !height) {
        height = *width * vb->height / vb->width;
      } else if (height && !width) {
        width = *height * vb->width / vb->height;
      } else {
        width = vb->width;
        height = vb->height;
      }
    }
    // Fractional sizes round up so the drawing is not cut off.
    const double pixels_w = std::ceil(*width - 1e-9), pixels_h = std::ceil(*height - 1e-9);
    try {
      check_image_size(pixels_w, pixels_h);
    } catch (const Error& e) {
      std::size_t offset = element_offset(root);
      if (pixels_w > kMaxImageSide && root.attribute("width"))
        offset = value_offset(root.attribute("width"));
      else if (pixels_h > kMaxImageSide && root.attribute("height"))
        offset = value_offset(root.attribute("height"));
      fail(offset, e.what());
    }
    doc_.intrinsic_width = *width;
    doc_.intrinsic_height = *height;
    doc_.width = static_cast<int>(pixels_w);
    doc_.height = static_cast<int>(pixels_h);
    percent_width_ = vb ? vb->width : *width;
    percent_height_ = vb ? vb->height : *height;
    if (vb) viewport_ = view_box_transform(*vb, *width, *height, root.attribute("preserveAspectRatio"));
  }

  // ---- elements ----

  /// Runs a Path builder call; a core error (coordinates overflowing) becomes a ParseError at `offset`.
  template <class F>
  void build(std::size_t offset, F&& call) const {
    try {
      call();
    } catch (const ParseError&) {
      throw;
    } catch (const Error& e) {
      fail(offset, e.what());
    }
  }

  /// The path of a basic shape or <path> element, in user space (empty when there is nothing to draw).
  Path shape_path(pugi::xml_node node, std::string_view name) {
    Path path;
    const std::size_t at = element_offset(node);
    auto get = [&](const char* attr, Axis axis) { return length_attribute(node, attr, axis); };
    if (name == "path") {
      const pugi::xml_attribute d = node.attribute("d");
      try {
        parse_path_data(d.value(), path);
      } catch (const PathDataError& e) {
        fail(value_offset(d, e.offset()), "path data: " + e.message());
      }
    } else if (name == "rect") {
      const double x = get("x", Axis::X).value_or(0), y = get("y", Axis::Y).value_or(0);
      const double w = get("width", Axis::X).value_or(0), h = get("height", Axis::Y).value_or(0);
      std::optional<double> rx = get("rx", Axis::X), ry = get("ry", Axis::Y);
      if (w < 0 || h < 0) {
        warn("negative sizes", at, "<rect> with a negative width or height, ignored");
        return path;
      }
      if (rx && *rx < 0) rx.reset();  // negative radii mean "auto"
      if (ry && *ry < 0) ry.reset();
      if (!rx) rx = ry;
      if (!ry) ry = rx;
      if (w == 0 || h == 0) return path;
      const Rect r{x, y, x + w, y + h};
      build(at, [&] {
        if (rx.value_or(0) > 0 && ry.value_or(0) > 0)
          path.add_round_rect(r, *rx, *ry);
        else
          path.add_rect(r);
      });
    } else if (name == "circle" || name == "ellipse") {
      const Point c{get("cx", Axis::X).value_or(0), get("cy", Axis::Y).value_or(0)};
      std::optional<double> rx, ry;
      if (name == "circle") {
        rx = ry = get("r", Axis::Other);
      } else {
        rx = get("rx", Axis::X);
        ry = get("ry", Axis::Y);
        if (!rx) rx = ry;  // SVG 2: a missing radius is "auto", the other one
        if (!ry) ry = rx;
      }
      if (rx.value_or(0) < 0 || ry.value_or(0) < 0) {
        warn("negative sizes", at, "<" + std::string(name) + "> with a negative radius, ignored");
        return path;
      }
      if (rx.value_or(0) > 0 && ry.value_or(0) > 0) build(at, [&] { path.add_ellipse(c, *rx, *ry); });
    } else if (name == "polygon" || name == "polyline") {
      const pugi::xml_attribute attr = node.attribute("points");
      const std::string_view s = attr.value();
      std::vector<Point> points;
      std::vector<double> numbers;
      std::size_t pos = 0;
      detail::skip_wsp(s, pos);
      while (pos < s.size()) {
        const std::size_t start = pos;
        double v = 0;
        if (scan_number(s, pos, v) != NumberScan::Ok) fail(value_offset(attr, start), "points: expected a number");
        numbers.push_back(v);
        if (detail::skip_comma_wsp(s, pos) && pos == s.size())
          fail(value_offset(attr, pos), "points: expected a number after ','");
      }
      if (numbers.size() % 2 != 0) fail(value_offset(attr, pos), "points: odd number of coordinates");
      for (std::size_t i = 0; i + 1 < numbers.size(); i += 2) points.push_back({numbers[i], numbers[i + 1]});
      if (points.size() >= 2) build(at, [&] { path.add_polygon(points, name == "polygon"); });
    } else if (name == "line") {
      const Point p0{get("x1", Axis::X).value_or(0), get("y1", Axis::Y).value_or(0)};
      const Point p1{get("x2", Axis::X).value_or(0), get("y2", Axis::Y).value_or(0)};
      build(at, [&] { path.move_to(p0).line_to(p1); });
    }
    return path;
  }

  /// The colour of a paint with its opacity and the element's opacity folded in; nothing when invisible.
  static std::optional<Color> paint_color(const Paint& paint, float paint_opacity, const Style& style) {
    if (!style.visible || paint.kind == PaintKind::None) return std::nullopt;
    Color color = paint.kind == PaintKind::CurrentColor ? style.current_color : paint.color;
    color.a *= paint_opacity * style.opacity;
    if (!(color.a > 0)) return std::nullopt;
    return color;
  }

  /// Emits the fill (unless `line`: a <line> encloses no area), then the stroke of a shape.
  void add_shape(Path&& path, bool line, const Style& style, const Affine& ctm, std::size_t at) {
    const auto verbs = path.verbs();
    if (std::all_of(verbs.begin(), verbs.end(), [](Verb v) { return v == Verb::Move; })) return;  // nothing drawn
    const auto [source_line, source_column] = lines_.position(at);
    const std::optional<Color> fill = line ? std::nullopt : paint_color(style.fill, style.fill_opacity, style);
    const std::optional<Color> stroke =
        style.stroke_style.width > 0 ? paint_color(style.stroke, style.stroke_opacity, style) : std::nullopt;
    if (fill) {
      DrawItem item;
      item.kind = DrawItem::Kind::Fill;
      if (stroke)
        item.path = path;
      else
        item.path = std::move(path);
      item.transform = ctm;
      item.color = *fill;
      item.rule = style.fill_rule;
      item.line = source_line;
      item.column = source_column;
      doc_.items.push_back(std::move(item));
    }
    if (stroke) {
      DrawItem item;
      item.kind = DrawItem::Kind::Stroke;
      item.path = std::move(path);
      item.transform = ctm;
      item.color = *stroke;
      item.stroke = style.stroke_style;
      item.line = source_line;
      item.column = source_column;
      warn_about_dashes(item, at);
      doc_.items.push_back(std::move(item));
    }
  }

  /// Says why a dashed stroke is drawn solid (the stroker decides the same way, from the same check).
  void warn_about_dashes(const DrawItem& item, std::size_t at) {
    switch (check_dashes(item.path, item.stroke.dashes)) {
      case DashVerdict::Invalid:
        warn("dash patterns", at, "stroke-dasharray sums to zero or overflows, the stroke is drawn solid");
        break;
      case DashVerdict::TooMany:
        warn("dash patterns", at,
             "stroke-dasharray would cut this path into more than " + std::to_string(std::lround(kMaxDashElements)) +
                 " dashes and gaps (the limit), the stroke is drawn solid");
        break;
      case DashVerdict::None:
      case DashVerdict::Dashed:
        break;
    }
  }

  void element(pugi::xml_node node, const Style& parent, const Affine& parent_ctm, int depth) {
    const std::size_t at = element_offset(node);
    if (++element_count_ > kMaxElements)
      fail(at, "too many elements (the limit is " + std::to_string(kMaxElements) + ")");
    if (depth > kMaxDepth)
      fail(at, "elements nested too deeply (the limit is " + std::to_string(kMaxDepth) + " levels)");

    const std::string_view name = node.name();
    const bool root = depth == 1;
    // Elements that are never drawn where they stand (they are only referenced, or hold no graphics).
    static constexpr std::string_view kSilent[] = {"defs",     "title",          "desc",           "metadata",
                                                   "symbol",   "linearGradient", "radialGradient", "pattern",
                                                   "clipPath", "mask",           "marker",         "filter"};
    if (!root && std::find(std::begin(kSilent), std::end(kSilent), name) != std::end(kSilent)) return;
    const bool container = root || name == "g" || name == "a";
    const bool shape = name == "path" || name == "rect" || name == "circle" || name == "ellipse" || name == "line" ||
                       name == "polyline" || name == "polygon";
    if (!container && !shape) {
      warn("unsupported elements", at, "element <" + printable(name) + "> is not supported yet, ignored");
      return;
    }

    Style style = parent;
    float own_opacity = 1;
    if (!apply_properties(node, style, own_opacity)) return;  // display: none hides the whole subtree
    style.opacity = parent.opacity * own_opacity;

    Affine own;
    if (const pugi::xml_attribute t = node.attribute("transform")) {
      if (!parse_transform(t.value(), own)) fail(value_offset(t), "invalid transform " + quoted(t.value()));
    }
    // The root's transform applies in the viewport, outside its viewBox mapping (SVG 2).
    const Affine ctm = root ? own * viewport_ : parent_ctm * own;
    if (!ctm.is_finite()) fail(at, "transform out of range");

    if (container) {
      if (own_opacity < 1 && node.first_child()) {
        warn("group opacity", at, "group opacity is approximated: opacity on <" + std::string(name) +
                     "> is multiplied into each child's alpha (overlapping children differ from a browser)");
      }
      for (const pugi::xml_node child : node.children()) {
        if (child.type() == pugi::node_element) element(child, style, ctm, depth + 1);
      }
      return;
    }
    add_shape(shape_path(node, name), name == "line", style, ctm, at);
  }

  std::string_view text_;
  const std::string& file_;
  LineIndex lines_;
  std::string buffer_;  // the private copy pugixml parses in place
  Document doc_;
  Affine viewport_;
  double percent_width_ = 0, percent_height_ = 0;  // what percentages of lengths refer to
  std::size_t element_count_ = 0;
  std::vector<std::string> warned_once_;
  struct WarningCount {
    std::string_view kind;  // always a string literal
    std::size_t count;
    std::size_t first_dropped;
  };
  std::vector<WarningCount> warning_counts_;
};

}  // namespace

Document parse_svg(std::string_view text, const std::string& file) { return Builder(text, file).run(); }

Document load_svg(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw Error("cannot read " + path + ": " + std::strerror(errno));
  std::string text;
  char chunk[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(chunk, 1, sizeof chunk, file.get())) > 0) text.append(chunk, n);
  if (std::ferror(file.get())) throw Error("cannot read " + path + ": " + std::strerror(errno));
  return parse_svg(text, path);
}

}  // namespace vraster::svg
