// svg_subset: SVG text -> Document.
//
// pugixml parses a private copy of the text in place, so every name and attribute value it hands back points into
// that copy: pointer - buffer start is the byte offset in the original text, which gives exact line:column
// positions for every message. The element walk carries the inherited properties and the current transform
// down the tree and emits a fill and/or a stroke DrawItem per shape, in document (= paint) order, fill first.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <pugixml.hpp>
#include <string>
#include <utility>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <variant>
#include <vector>

#include "image_element.hpp"
#include "markers.hpp"
#include "scan.hpp"
#include "xml_check.hpp"
#include "css.hpp"
#include "text.hpp"
#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"
#include "vraster/files.hpp"
#include "vraster/image_io.hpp"

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
/// A paint as declared: the resolution of url() and currentColor waits for the element that uses it.
struct DeclaredPaint {
  enum class Kind : std::uint8_t { None, Color, CurrentColor, Url, ContextFill, ContextStroke };
  Kind kind = Kind::Color;
  Color color{0, 0, 0, 1};
  std::string url;                     ///< the id referred to (without '#')
  std::optional<DeclaredPaint::Kind> fallback_kind;  ///< after url(): none, a colour or currentColor
  std::size_t offset = 0;
};

/// The properties in effect on an element (inherited ones come from the parent; the others are reset).
struct Style {
  // Inherited.
  DeclaredPaint fill;
  float fill_opacity = 1;
  FillRule fill_rule = FillRule::NonZero;
  DeclaredPaint stroke{DeclaredPaint::Kind::None, {}, {}, {}, 0};
  float stroke_opacity = 1;
  StrokeStyle stroke_style;  // SVG defaults: width 1, butt, miter, miter limit 4, no dashes
  Color current_color{0, 0, 0, 1};  // the `color` property, used by currentColor
  bool visible = true;
  FillRule clip_rule = FillRule::NonZero;
  bool stroke_first = false;
  bool crisp_edges = false;
  bool smooth_images = true;  // image-rendering
  std::string marker_start, marker_mid, marker_end;  // ids from url(#id)
  std::uint8_t markers_position = 2;  // paint-order: where markers come among the three paints (0, 1 or 2)
  // Not inherited.
  float opacity = 1;
  bool displayed = true;
  std::string clip_path, mask;  // ids from url(#id)
  std::string blend_mode = "normal";
  bool isolate = false;
  Color stop_color{0, 0, 0, 1};
  float stop_opacity = 1;
  bool overflow_visible = true;  // the initial value; the UA style sheet hides it on viewports (computed())
  bool mask_luminance = true;  // mask-type
  std::optional<Affine> css_transform;  // `transform` from CSS (style sheets, style attribute): beats the attribute
  std::optional<Color> background;       // background-color (CSS only; drawn for the root element)
  detail::TextProperties text;  // font, spacing, anchor, baselines, decorations (text.hpp)
  // Custom properties (--name), inherited: shared with the parent until an element declares its own.
  std::shared_ptr<const css::CustomProperties> custom;

  /// The style a child starts from: inherited properties kept, the others at their initial values.
  Style inherited() const {
    Style s = *this;
    s.opacity = 1;
    s.displayed = true;
    s.clip_path.clear();
    s.mask.clear();
    s.blend_mode = "normal";
    s.isolate = false;
    s.stop_color = Color{0, 0, 0, 1};
    s.stop_opacity = 1;
    s.overflow_visible = true;
    s.mask_luminance = true;
    s.css_transform.reset();
    s.background.reset();
    s.text.reset_non_inherited();
    return s;
  }
};

/// The presentation attributes and CSS properties we know. Everything else is ignored silently (SVG has many
/// properties that do not change what is drawn here; unknown names are not errors in CSS either).
constexpr std::string_view kProperties[] = {
    "fill",           "fill-opacity",     "fill-rule",         "stroke",         "stroke-opacity",
    "stroke-width",   "stroke-linecap",   "stroke-linejoin",   "stroke-miterlimit", "stroke-dasharray",
    "stroke-dashoffset", "opacity",       "color",             "display",        "visibility",
    "clip-path",      "clip-rule",        "mask",              "filter",         "mix-blend-mode",
    "isolation",      "stop-color",       "stop-opacity",      "paint-order",    "shape-rendering",
    "overflow",       "marker-start",     "marker-mid",        "marker-end",     "marker",
    "image-rendering", "transform",        "mask-type",         "background-color"};

bool is_property(std::string_view name) {
  return std::find(std::begin(kProperties), std::end(kProperties), name) != std::end(kProperties) ||
         detail::is_text_property(name);
}

enum class Axis { X, Y, Other };

struct ViewBox {
  double x, y, width, height;
};

/// Adapter for css::matches_path on pugixml nodes.
struct XmlAdapter {
  static std::string_view name(pugi::xml_node n) {
    const std::string_view full = n.name();
    const std::size_t colon = full.find(':');
    return colon == std::string_view::npos ? full : full.substr(colon + 1);
  }
  static bool attribute(pugi::xml_node n, std::string_view name, std::string_view& value) {
    for (const pugi::xml_attribute a : n.attributes()) {
      if (name == a.name()) {
        value = a.value();
        return true;
      }
    }
    return false;
  }
  static pugi::xml_node previous_element(pugi::xml_node n) {
    for (pugi::xml_node p = n.previous_sibling(); p; p = p.previous_sibling()) {
      if (p.type() == pugi::node_element) return p;
    }
    return {};
  }
  static pugi::xml_node next_element(pugi::xml_node n) {
    for (pugi::xml_node p = n.next_sibling(); p; p = p.next_sibling()) {
      if (p.type() == pugi::node_element) return p;
    }
    return {};
  }
  static bool is_root(pugi::xml_node n) { return n.parent().type() != pugi::node_element; }
  static bool is_null(pugi::xml_node n) { return !n; }
};

constexpr std::string_view kSvgNamespace = "http://www.w3.org/2000/svg";
constexpr std::size_t kMaxUseInstances = 100'000;  // made inside other uses' instances
constexpr int kMaxReferenceDepth = 64;
// Markers inside markers (each a different marker: one cannot contain itself) nest at most this deep.
constexpr std::size_t kMaxMarkerNesting = 8;
/// SVG images inside SVG images: at most this many levels below the document (data: URLs can nest).
constexpr int kMaxImageNesting = 4;
/// Decoded image pixels one document may hold, its SVG images included (512 MiB of RGBA8: two images of the
/// largest size).
constexpr std::int64_t kMaxDocumentImagePixels = std::int64_t{1} << 27;

/// Clip-path content is drawn as coverage: what counts is that it paints, opaquely (the colour is unused).
Paint opaque_black() {
  Paint p;
  p.kind = Paint::Kind::Color;
  p.color = Color{0, 0, 0, 1};
  return p;
}

class Builder {
 public:
  /// `image_depth` is 0 for a document, n for an SVG image n levels down; `pixels_left` is the decoded-pixel
  /// budget the document shares with the SVG images inside it.
  Builder(std::string_view text, const std::string& file, const ParseOptions& options, int image_depth,
          std::int64_t& pixels_left)
      : text_(text), file_(file), lines_(text), options_(options), image_depth_(image_depth), pixels_left_(pixels_left) {}

  Tree run() {
    // Entities declared in the DOCTYPE are expanded first; positions are then those of the expanded text
    // (the same as the file's up to the first reference).
    detail::EntityExpansion expansion = detail::expand_internal_entities(text_);
    if (expansion.problem) fail(expansion.problem->offset, "malformed XML: " + expansion.problem->message);
    if (!expansion.text.empty()) {
      expanded_text_ = std::move(expansion.text);
      text_ = expanded_text_;
      lines_ = LineIndex(text_);
    }
    buffer_.assign(text_.begin(), text_.end());
    font_size_ = options_.default_font_size;
    const pugi::xml_parse_result result =
        xml_.load_buffer_inplace(buffer_.data(), buffer_.size(), pugi::parse_default | pugi::parse_ws_pcdata,
                                 pugi::encoding_utf8);  // white-space-only text counts in <text>
    if (!result) {
      const auto offset = static_cast<std::size_t>(std::max<std::ptrdiff_t>(result.offset, 0));
      fail(std::min(offset, text_.size()), std::string("malformed XML: ") + result.description());
    }
    if (const std::optional<detail::XmlProblem> problem = detail::find_xml_problem(text_))
      fail(problem->offset, "malformed XML: " + problem->message);
    check_unique_attributes(xml_);
    const pugi::xml_node root = xml_.document_element();
    index_document(root);
    if (local_name(root) != "svg") {
      fail(element_offset(root), "the root element is <" + printable(root.name()) + ">, expected <svg>");
    }
    tree_.file = file_;
    count_element(element_offset(root), 1);
    set_up_viewport(root);
    Style style = computed(root, initial_style());
    tree_.root.id = root.attribute("id").value();
    tree_.root.transform = root_transform(root, style);
    tree_.background = style.background;
    if (style.displayed) {
      children(root, style, tree_.root.children, 1);
      apply_group_effects(style, tree_.root, element_offset(root));
    }
    finish_warnings();
    return std::move(tree_);
  }

 private:
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
    tree_.warnings.push_back(std::to_string(line) + ":" + std::to_string(column) + ": " + message);
  }

  /// Appends one line per kind of warning that was cut short: "... and K more (kind), the first at L:C".
  void finish_warnings() {
    for (const WarningCount& c : warning_counts_) {
      if (c.count <= kMaxWarningsPerKind) continue;
      const auto [line, column] = lines_.position(c.first_dropped);
      tree_.warnings.push_back(std::to_string(line) + ":" + std::to_string(column) + ": ... and " +
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


  // ---- the document index: ids, style sheets, namespace prefixes ----

  /// One pass over every element: the id map (first one wins, as getElementById), the <style> sheets in
  /// document order, and the prefixes bound to the SVG namespace (xmlns:svg="...").
  void index_document(pugi::xml_node root) {
    std::vector<pugi::xml_node> styles;
    pugi::xml_node node = root;
    while (node) {
      if (node.type() == pugi::node_element) {
        for (const pugi::xml_attribute a : node.attributes()) {
          const std::string_view name = a.name();
          if (name.substr(0, 6) == "xmlns:" && a.value() == kSvgNamespace) svg_prefixes_.emplace_back(name.substr(6));
          if (node != root && (name == "xmlns" || name.substr(0, 6) == "xmlns:")) scoped_namespaces_ = true;
        }
        if (const pugi::xml_attribute id = node.attribute("id")) ids_.emplace(std::string_view(id.value()), node);
        if (std::string_view(node.name()) == "style" || std::string_view(node.name()).ends_with(":style"))
          styles.push_back(node);
      }
      if (node.first_child()) {
        node = node.first_child();
        continue;
      }
      while (node && node != root && !node.next_sibling()) node = node.parent();
      if (!node || node == root) break;
      node = node.next_sibling();
    }
    for (const pugi::xml_node style : styles) {
      if (local_name(style) != "style") continue;
      const std::string_view type = trim(style.attribute("type").value());
      if (!type.empty() && !iequals(type, "text/css")) continue;
      for (const pugi::xml_node child : style.children()) {
        if (child.type() != pugi::node_pcdata && child.type() != pugi::node_cdata) continue;
        const std::string_view css = child.value();
        const std::size_t base = offset_of(child.value());
        for (const std::size_t bad : sheet_.add(css, base)) {
          warn("style rules", bad, "style rule with an unsupported selector, ignored");
        }
      }
    }
  }

  /// The element's local name when it is in the SVG namespace (no prefix, or a prefix bound to it); empty for
  /// elements of other namespaces (Inkscape's sodipodi:, inkscape:, RDF), which are skipped silently.
  std::string_view local_name(pugi::xml_node node) const {
    const std::string_view full = node.name();
    const std::size_t colon = full.find(':');
    const std::string_view prefix = colon == std::string_view::npos ? std::string_view{} : full.substr(0, colon);
    if (!in_svg_namespace(node, prefix)) return {};
    return colon == std::string_view::npos ? full : full.substr(colon + 1);
  }

  /// Whether an element whose name has `prefix` (empty: none) is in the SVG namespace. When only the root
  /// declares namespaces (nearly every file), a prefix is SVG when it is bound to it and no prefix always is
  /// (documents without xmlns are accepted). Otherwise the nearest declaration of the prefix among the element
  /// and its ancestors decides (XML Namespaces 1.0, 6.1-6.2), cached per element.
  bool in_svg_namespace(pugi::xml_node node, std::string_view prefix) const {
    if (!scoped_namespaces_)
      return prefix.empty() || std::find(svg_prefixes_.begin(), svg_prefixes_.end(), prefix) != svg_prefixes_.end();
    const auto cached = svg_namespace_cache_.find(node.internal_object());
    if (cached != svg_namespace_cache_.end()) return cached->second;
    const std::string declaration = prefix.empty() ? "xmlns" : "xmlns:" + std::string(prefix);
    bool svg = prefix.empty();  // no declaration: no prefix is SVG, an unbound prefix is not
    for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) {
      if (const pugi::xml_attribute a = n.attribute(declaration.c_str())) {
        svg = std::string_view(a.value()) == kSvgNamespace;
        break;
      }
      const auto parent_cached = svg_namespace_cache_.find(n.parent().internal_object());
      if (prefix.empty() && parent_cached != svg_namespace_cache_.end() &&
          std::string_view(n.parent().name()).find(':') == std::string_view::npos) {
        svg = parent_cached->second;  // an unprefixed parent's answer is this element's
        break;
      }
    }
    svg_namespace_cache_.emplace(node.internal_object(), svg);
    return svg;
  }

  /// The element an href (or xlink:href) points to in this document, or a null node (warns when it is not a
  /// same-document reference or the id does not exist).
  pugi::xml_node href_target(pugi::xml_node node, bool warn_missing = true) {
    pugi::xml_attribute attr = node.attribute("href");
    if (!attr) attr = node.attribute("xlink:href");
    if (!attr) return {};
    const std::string_view v = trim(attr.value());
    if (v.empty() || v[0] != '#') {
      if (warn_missing) warn("references", value_offset(attr), "only same-document references (#id) are supported: " + quoted(v));
      return {};
    }
    const pugi::xml_node target = by_id(v.substr(1));
    if (!target && warn_missing) warn("references", value_offset(attr), "no element with id " + quoted(v.substr(1)));
    return target;
  }

  pugi::xml_node by_id(std::string_view id) const {
    const auto it = ids_.find(id);
    return it == ids_.end() ? pugi::xml_node{} : it->second;
  }

  // ---- values (an invalid value is reported and treated as not given: nothing is returned) ----

  bool parse_length(std::string_view v, Axis axis, double& out) const {
    std::size_t pos = 0;
    double number = 0;
    if (scan_number(v, pos, number) != NumberScan::Ok) return false;
    const std::string_view unit = v.substr(pos);
    // CSS absolute units at the document's dpi (ParseOptions::dpi); em is the font size of the element the length
    // is on, ex half of it (the x-height of a font is not known here; half an em is CSS's fallback).
    double scale = detail::absolute_unit_scale(unit, options_.dpi);
    if (iequals(unit, "em")) scale = font_size_;
    if (iequals(unit, "ex")) scale = font_size_ / 2;
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

  /// A length attribute, or nothing when absent or invalid (with a warning).
  std::optional<double> length_attribute(pugi::xml_node node, const char* name, Axis axis) {
    const pugi::xml_attribute attr = node.attribute(name);
    if (!attr) return std::nullopt;
    const std::string_view raw = attr.value();
    const std::string_view v = trim(raw);
    double out = 0;
    if (!parse_length(v, axis, out)) {
      warn("invalid values", value_offset(attr, static_cast<std::size_t>(v.data() - raw.data())),
           std::string("invalid length for ") + name + ": " + quoted(v) + ", ignored");
      return std::nullopt;
    }
    return out;
  }

  /// A number or a percentage (a fraction), as gradient and stop attributes take them.
  static std::optional<double> number_or_percent(std::string_view v) {
    std::size_t pos = 0;
    double value = 0;
    if (scan_number(trim(v), pos, value) != NumberScan::Ok) return std::nullopt;
    const std::string_view t = trim(v);
    if (pos < t.size() && t[pos] == '%') {
      value /= 100;
      ++pos;
    }
    if (pos != t.size() || !std::isfinite(value)) return std::nullopt;
    return value;
  }

  static std::optional<float> parse_opacity(std::string_view v) {
    const std::optional<double> value = number_or_percent(v);
    if (!value) return std::nullopt;
    return static_cast<float>(std::clamp(*value, 0.0, 1.0));
  }

  static std::optional<DeclaredPaint> parse_paint(std::string_view v, std::size_t offset) {
    DeclaredPaint paint;
    paint.offset = offset;
    if (iequals(v, "currentColor")) {
      paint.kind = DeclaredPaint::Kind::CurrentColor;
      return paint;
    }
    if (v == "context-fill" || v == "context-stroke") {
      paint.kind = v == "context-fill" ? DeclaredPaint::Kind::ContextFill : DeclaredPaint::Kind::ContextStroke;
      return paint;
    }
    if (detail::istarts_with(v, "url(")) {
      const std::size_t close = v.find(')');
      if (close == std::string_view::npos) return std::nullopt;
      std::string_view ref = trim(v.substr(4, close - 4));
      if (ref.size() >= 2 && (ref.front() == '"' || ref.front() == '\'') && ref.back() == ref.front())
        ref = ref.substr(1, ref.size() - 2);
      paint.kind = DeclaredPaint::Kind::Url;
      paint.url = std::string(!ref.empty() && ref[0] == '#' ? ref.substr(1) : ref);
      const std::string_view fallback = trim(v.substr(close + 1));
      if (!fallback.empty()) {
        const std::optional<DeclaredPaint> f = parse_paint(fallback, offset);
        if (!f || f->kind == DeclaredPaint::Kind::Url) return std::nullopt;
        paint.fallback_kind = f->kind;
        paint.color = f->color;
      }
      return paint;
    }
    bool none = false;
    const std::optional<Color> color = parse_color(v, none);
    if (none) {
      paint.kind = DeclaredPaint::Kind::None;
      return paint;
    }
    if (!color) return std::nullopt;
    paint.color = *color;
    return paint;
  }

  /// stroke-dasharray: "none" or lengths separated by commas and/or whitespace; nothing when malformed.
  /// SVG: a negative value makes the list invalid (drawn solid, with a warning).
  std::optional<std::vector<double>> parse_dash_array(std::string_view v, std::size_t offset) {
    if (v == "none") return std::vector<double>{};
    std::vector<double> dashes;
    std::size_t pos = 0;
    if (v.empty()) return std::nullopt;
    while (pos < v.size()) {
      const std::size_t start = pos;
      while (pos < v.size() && !detail::is_wsp(v[pos]) && v[pos] != ',') ++pos;
      double length = 0;
      if (pos == start || !parse_length(v.substr(start, pos - start), Axis::Other, length)) return std::nullopt;
      dashes.push_back(length);
      if (detail::skip_comma_wsp(v, pos) && pos == v.size()) return std::nullopt;
    }
    if (std::any_of(dashes.begin(), dashes.end(), [](double d) { return d < 0; })) {
      warn("dash patterns", offset, "negative value in stroke-dasharray " + quoted(v) + ", the stroke is drawn solid");
      return std::vector<double>{};
    }
    return dashes;
  }

  /// url(#id) of clip-path, mask, marker: the id, "" for none; nothing when malformed.
  static std::optional<std::string> parse_url_reference(std::string_view v) {
    if (v == "none") return std::string();
    if (!detail::istarts_with(v, "url(") || v.back() != ')') return std::nullopt;
    std::string_view ref = trim(v.substr(4, v.size() - 5));
    if (ref.size() >= 2 && (ref.front() == '"' || ref.front() == '\'') && ref.back() == ref.front())
      ref = ref.substr(1, ref.size() - 2);
    if (ref.empty() || ref[0] != '#') return std::nullopt;
    return std::string(ref.substr(1));
  }

  // ---- the cascade ----

  /// The computed style of `node` whose parent's computed style is `parent`: presentation attributes, then the
  /// style sheets' rules, then the style attribute, in cascade order (css::sort_cascade), each applied over the
  /// inherited values.
  Style computed(pugi::xml_node node, const Style& parent) {
    Style style = parent.inherited();
    // The UA style sheet (SVG 2, appendix "User agent style sheet"): elements that establish a viewport, and
    // patterns, clip their content unless told otherwise.
    const std::string_view element_name = local_name(node);
    if (element_name == "symbol" || element_name == "image" || element_name == "marker" || element_name == "pattern" ||
        (element_name == "svg" && node != xml_.document_element()))
      style.overflow_visible = false;
    std::vector<css::Declaration> own;  // presentation attributes and the style attribute
    std::vector<std::pair<css::Origin, std::size_t>> own_origin;
    for (const pugi::xml_attribute attr : node.attributes()) {
      const std::string_view name = attr.name();
      // The transform attribute has SVG's grammar (own_transform reads it; a CSS transform beats it); the
      // `marker` shorthand (SVG 2, 11.6.2) and background-color are CSS only.
      if (!is_property(name) || name == "transform" || name == "marker" || name == "background-color") continue;
      if (detail::is_text_property(name) && !detail::is_text_attribute(name)) continue;
      const std::string_view raw = attr.value();
      const std::string_view v = trim(raw);
      own.push_back(css::Declaration{std::string(name), std::string(v), false,
                                     value_offset(attr, static_cast<std::size_t>(v.data() - raw.data()))});
      own_origin.emplace_back(css::Origin::PresentationAttribute, own.size());
    }
    if (const pugi::xml_attribute style_attr = node.attribute("style")) {
      std::vector<std::size_t> bad;
      std::vector<css::Declaration> declarations = css::parse_declarations(style_attr.value(), 0, &bad);
      ValueOffsets offsets(*this, style_attr);
      for (const std::size_t b : bad) warn("style declarations", offsets.at(b), "malformed style declaration, ignored");
      offsets = ValueOffsets(*this, style_attr);
      for (css::Declaration& d : declarations) {
        d.offset = offsets.at(d.offset);
        const css::Origin origin = d.important ? css::Origin::StyleImportant : css::Origin::StyleAttribute;
        own.push_back(std::move(d));
        own_origin.emplace_back(origin, own.size());
      }
    }
    std::vector<css::Cascaded> cascade;
    for (std::size_t i = 0; i < own.size(); ++i) {
      cascade.push_back(css::Cascaded{&own[i], own_origin[i].first, 0, own_origin[i].second});
    }
    if (!sheet_.rules.empty()) {
      path_.clear();
      for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) path_.push_back(n);
      std::reverse(path_.begin(), path_.end());
      for (const css::Rule& rule : sheet_.rules) {
        if (!css::matches_path<XmlAdapter>(rule.selector, path_)) continue;
        for (const css::Declaration& d : rule.declarations) {
          cascade.push_back(css::Cascaded{&d, d.important ? css::Origin::SheetImportant : css::Origin::Sheet,
                                          rule.selector.specificity, rule.order});
        }
      }
    }
    css::sort_cascade(cascade);
    // The font size first: em and ex in the other properties (stroke-width="2em") refer to it.
    const auto is_font_size = [](const css::Cascaded& c) {
      return c.declaration->name == "font-size" || c.declaration->name == "font";
    };
    std::stable_partition(cascade.begin(), cascade.end(), is_font_size);
    // Custom properties first, in cascade order (the last one wins): var() in the others refers to them.
    const auto is_custom = [](const std::string& name) { return name.size() > 2 && name.compare(0, 2, "--") == 0; };
    std::shared_ptr<css::CustomProperties> own_custom;
    for (const css::Cascaded& c : cascade) {
      const css::Declaration& d = *c.declaration;
      if (!is_custom(d.name)) continue;
      if (!own_custom)
        own_custom = std::make_shared<css::CustomProperties>(style.custom ? *style.custom : css::CustomProperties{});
      if (d.value == "initial" || d.value.empty())
        own_custom->erase(d.name);
      else if (d.value != "inherit")
        (*own_custom)[d.name] = d.value;
    }
    if (own_custom) style.custom = std::move(own_custom);
    static const css::CustomProperties kNoCustom;
    std::string substituted;
    const double saved_font_size = font_size_;
    font_size_ = parent.text.font_size;  // em in font-size itself is the parent's (text_properties.cpp)
    for (const css::Cascaded& c : cascade) {
      const css::Declaration& d = *c.declaration;
      if (is_custom(d.name)) continue;
      if (!is_font_size(c) && font_size_ != style.text.font_size) font_size_ = style.text.font_size;
      std::string_view value = d.value;
      if (css::has_var(value)) {
        // A reference with no value makes the declaration invalid at computed-value time: the property is then
        // `unset` (CSS Custom Properties 1, 3.1), not the value of a declaration it won over.
        if (!css::substitute_vars(value, style.custom ? *style.custom : kNoCustom, substituted)) {
          warn("invalid values", d.offset, "var() in " + printable(d.name) + " " + quoted(value) +
                                               " refers to no custom property and has no fallback: unset");
          value = "unset";
        } else {
          value = trim(substituted);
        }
      }
      apply(d.name, value, d.offset, style, parent);
    }
    font_size_ = saved_font_size;
    return style;
  }

  void invalid(std::string_view name, std::string_view v, std::size_t offset) {
    warn("invalid values", offset, "invalid " + printable(name) + " " + quoted(v) + ", ignored");
  }

  /// Applies one declaration. An invalid value is reported and changes nothing (CSS drops it).
  void apply(std::string_view name, std::string_view v, std::size_t offset, Style& s, const Style& parent) {
    if (v == "inherit") {
      inherit(name, s, parent);
      return;
    }
    if (v == "unset") {  // inherited properties take the parent's value, the others their initial one
      inherit(name, s, parent.inherited());
      return;
    }
    if (v == "initial") return;  // close enough: most SVG properties start at their initial values
    auto bad = [&] { invalid(name, v, offset); };
    if (name == "fill" || name == "stroke") {
      const std::optional<DeclaredPaint> paint = parse_paint(v, offset);
      if (!paint) return bad();
      (name == "fill" ? s.fill : s.stroke) = *paint;
    } else if (name == "fill-opacity" || name == "stroke-opacity" || name == "opacity" || name == "stop-opacity") {
      const std::optional<float> o = parse_opacity(v);
      if (!o) return bad();
      (name == "fill-opacity" ? s.fill_opacity : name == "stroke-opacity" ? s.stroke_opacity
                                                 : name == "opacity"      ? s.opacity
                                                                          : s.stop_opacity) = *o;
    } else if (name == "fill-rule" || name == "clip-rule") {
      FillRule& rule = name == "fill-rule" ? s.fill_rule : s.clip_rule;
      if (v == "nonzero")
        rule = FillRule::NonZero;
      else if (v == "evenodd")
        rule = FillRule::EvenOdd;
      else
        bad();
    } else if (name == "stroke-width") {
      double width = 0;
      if (!parse_length(v, Axis::Other, width) || width < 0) return bad();
      s.stroke_style.width = width;
    } else if (name == "stroke-linecap") {
      if (!parse_line_cap(v, s.stroke_style.cap)) bad();
    } else if (name == "stroke-linejoin") {
      if (v == "arcs") {
        warn("line joins", offset, "stroke-linejoin " + quoted(v) + " is not supported yet, using miter");
        s.stroke_style.join = LineJoin::Miter;
      } else if (!parse_line_join(v, s.stroke_style.join)) {
        bad();
      }
    } else if (name == "stroke-miterlimit") {
      std::size_t pos = 0;
      double limit = 0;
      if (scan_number(v, pos, limit) != NumberScan::Ok || pos != v.size() || limit < 1) return bad();
      s.stroke_style.miter_limit = limit;
    } else if (name == "stroke-dasharray") {
      const auto dashes = parse_dash_array(v, offset);
      if (!dashes) return bad();
      s.stroke_style.dashes = *dashes;
    } else if (name == "stroke-dashoffset") {
      double d = 0;
      if (!parse_length(v, Axis::Other, d)) return bad();
      s.stroke_style.dash_offset = d;
    } else if (name == "color") {
      if (iequals(v, "currentColor")) return;  // same as inherit
      bool none = false;
      const std::optional<Color> color = parse_color(v, none);
      if (!color) return bad();
      s.current_color = *color;
    } else if (name == "stop-color") {
      if (iequals(v, "currentColor")) {
        s.stop_color = s.current_color;
        return;
      }
      bool none = false;
      const std::optional<Color> color = parse_color(v, none);
      if (!color) return bad();
      s.stop_color = *color;
    } else if (name == "display") {
      s.displayed = v != "none";
    } else if (name == "mask-type") {
      if (v == "luminance" || v == "alpha")
        s.mask_luminance = v == "luminance";
      else
        bad();
    } else if (name == "transform") {
      Affine m;
      if (!parse_css_transform(v, m)) return bad();
      s.css_transform = m;
    } else if (name == "background-color") {
      bool none = false;
      const std::optional<Color> color = iequals(v, "currentColor") ? s.current_color : parse_color(v, none);
      if (!color) return bad();
      s.background = *color;
    } else if (name == "visibility") {
      if (v == "visible")
        s.visible = true;
      else if (v == "hidden" || v == "collapse")
        s.visible = false;
      else
        bad();
    } else if (name == "clip-path" || name == "mask") {
      const std::optional<std::string> id = parse_url_reference(v);
      if (!id) return bad();
      (name == "clip-path" ? s.clip_path : s.mask) = *id;
    } else if (name == "mix-blend-mode") {
      static constexpr std::string_view kModes[] = {
          "normal",     "multiply",   "screen", "overlay",    "darken", "lighten", "color-dodge", "color-burn",
          "hard-light", "soft-light", "difference", "exclusion", "hue", "saturation", "color", "luminosity"};
      if (std::find(std::begin(kModes), std::end(kModes), v) == std::end(kModes)) return bad();
      s.blend_mode = std::string(v);
    } else if (name == "isolation") {
      if (v != "auto" && v != "isolate") return bad();
      s.isolate = v == "isolate";
    } else if (name == "paint-order") {
      const std::optional<std::array<std::string_view, 3>> order = parse_paint_order(v);
      if (!order) return bad();
      const auto at = [&](std::string_view paint) { return std::find(order->begin(), order->end(), paint) - order->begin(); };
      s.stroke_first = at("stroke") < at("fill");
      s.markers_position = static_cast<std::uint8_t>(at("markers"));
    } else if (name == "shape-rendering") {
      s.crisp_edges = v == "crispEdges" || v == "optimizeSpeed";
    } else if (name == "image-rendering") {
      // CSS Images: crisp-edges and pixelated keep pixels sharp; SVG 1.1's optimizeSpeed is read the same way
      // (as resvg does). auto, smooth, high-quality, optimizeQuality: smooth.
      s.smooth_images = !(v == "optimizeSpeed" || v == "crisp-edges" || v == "pixelated");
    } else if (name == "overflow") {
      s.overflow_visible = v == "visible" || v == "auto";
    } else if (detail::is_text_property(name)) {
      if (!detail::apply_text_property(name, v, s.text, parent.text, options_.dpi)) bad();
    } else if (name == "filter") {
      if (v != "none" && !warned_filter_) {
        warned_filter_ = true;
        warn("unsupported properties", offset, "filter is not supported yet, ignored (reported once)");
      }
    } else if (name.substr(0, 6) == "marker") {
      const std::optional<std::string> id = parse_url_reference(v);
      if (!id) return bad();
      if (name == "marker-start" || name == "marker") s.marker_start = *id;
      if (name == "marker-mid" || name == "marker") s.marker_mid = *id;
      if (name == "marker-end" || name == "marker") s.marker_end = *id;
    }
  }

  /// paint-order: "normal", or some of fill, stroke, markers (each at most once) followed by the missing ones
  /// in their normal order. Nothing when malformed.
  static std::optional<std::array<std::string_view, 3>> parse_paint_order(std::string_view v) {
    std::array<std::string_view, 3> order{"fill", "stroke", "markers"};
    if (v == "normal") return order;
    std::vector<std::string_view> given;
    while (!(v = trim(v)).empty()) {
      std::size_t end = 0;
      while (end < v.size() && !detail::is_wsp(v[end])) ++end;
      const std::string_view word = v.substr(0, end);
      v.remove_prefix(end);
      if (std::find(order.begin(), order.end(), word) == order.end()) return std::nullopt;
      if (std::find(given.begin(), given.end(), word) != given.end()) return std::nullopt;
      given.push_back(word);
    }
    if (given.empty()) return std::nullopt;
    for (const std::string_view paint : std::array<std::string_view, 3>{"fill", "stroke", "markers"}) {
      if (std::find(given.begin(), given.end(), paint) == given.end()) given.push_back(paint);
    }
    std::copy(given.begin(), given.end(), order.begin());
    return order;
  }

  /// `inherit`: the parent's value of one property.
  static void inherit(std::string_view name, Style& s, const Style& p) {
    if (name == "fill") s.fill = p.fill;
    else if (name == "stroke") s.stroke = p.stroke;
    else if (name == "fill-opacity") s.fill_opacity = p.fill_opacity;
    else if (name == "stroke-opacity") s.stroke_opacity = p.stroke_opacity;
    else if (name == "opacity") s.opacity = p.opacity;
    else if (name == "stop-opacity") s.stop_opacity = p.stop_opacity;
    else if (name == "stop-color") s.stop_color = p.stop_color;
    else if (name == "fill-rule") s.fill_rule = p.fill_rule;
    else if (name == "clip-rule") s.clip_rule = p.clip_rule;
    else if (name == "stroke-width") s.stroke_style.width = p.stroke_style.width;
    else if (name == "stroke-linecap") s.stroke_style.cap = p.stroke_style.cap;
    else if (name == "stroke-linejoin") s.stroke_style.join = p.stroke_style.join;
    else if (name == "stroke-miterlimit") s.stroke_style.miter_limit = p.stroke_style.miter_limit;
    else if (name == "stroke-dasharray") s.stroke_style.dashes = p.stroke_style.dashes;
    else if (name == "stroke-dashoffset") s.stroke_style.dash_offset = p.stroke_style.dash_offset;
    else if (name == "color") s.current_color = p.current_color;
    else if (name == "visibility") s.visible = p.visible;
    else if (name == "display") s.displayed = p.displayed;
    else if (name == "clip-path") s.clip_path = p.clip_path;
    else if (name == "mask") s.mask = p.mask;
    else if (name == "image-rendering") s.smooth_images = p.smooth_images;
    else if (name == "overflow") s.overflow_visible = p.overflow_visible;
    else if (name == "mask-type") s.mask_luminance = p.mask_luminance;
    else if (name == "transform") s.css_transform = p.css_transform;
    else if (name == "background-color") s.background = p.background;
    else detail::inherit_text_property(name, s.text, p.text);
    if (name == "marker-start" || name == "marker") s.marker_start = p.marker_start;
    if (name == "marker-mid" || name == "marker") s.marker_mid = p.marker_mid;
    if (name == "marker-end" || name == "marker") s.marker_end = p.marker_end;
  }

  // ---- viewports ----

  std::optional<ViewBox> parse_view_box(pugi::xml_attribute attr) {
    const std::string_view s = attr.value();
    std::size_t pos = 0;
    double v[4];
    detail::skip_wsp(s, pos);
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
      if (i > 0) detail::skip_comma_wsp(s, pos);
      ok = scan_number(s, pos, v[i]) == NumberScan::Ok;
    }
    detail::skip_wsp(s, pos);
    if (!ok || pos != s.size() || !(v[2] > 0 && v[3] > 0)) {
      warn("invalid values", value_offset(attr),
           "invalid viewBox " + quoted(s) + " (expected min-x min-y width height, sizes positive), ignored");
      return std::nullopt;
    }
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

  /// A preserveAspectRatio value (xMidYMid meet when absent or invalid, with a warning).
  detail::AspectRatio parse_aspect(pugi::xml_attribute aspect) {
    detail::AspectRatio r;
    if (!aspect) return r;
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
      r.none = true;
    } else if (word.size() == 8 && word[0] == 'x' && word[4] == 'Y') {
      auto align = [&valid](std::string_view part) {
        if (part == "Min") return 0.0;
        if (part == "Mid") return 0.5;
        if (part == "Max") return 1.0;
        valid = false;
        return 0.5;
      };
      r.align_x = align(word.substr(1, 3));
      r.align_y = align(word.substr(5, 3));
    } else {
      valid = false;
    }
    const std::string_view mode = next_word();
    if (mode == "slice")
      r.slice = true;
    else if (!mode.empty() && mode != "meet")
      valid = false;
    if (!trim(s).empty()) valid = false;
    if (!valid) {
      warn("invalid values", value_offset(aspect),
           "invalid preserveAspectRatio " + quoted(aspect.value()) + ", using xMidYMid meet");
      r = detail::AspectRatio{};
    }
    return r;
  }

  /// The viewBox -> viewport transform for a preserveAspectRatio value (SVG 1.1 section 7.8).
  Affine view_box_transform(const ViewBox& vb, double width, double height, pugi::xml_attribute aspect) {
    return rect_transform(Rect{vb.x, vb.y, vb.x + vb.width, vb.y + vb.height},
                          detail::fit_rect(Rect{0, 0, width, height}, vb.width, vb.height, parse_aspect(aspect)));
  }

  /// The transform that maps rectangle `from` onto rectangle `to`.
  static Affine rect_transform(const Rect& from, const Rect& to) {
    const double sx = (to.x1 - to.x0) / (from.x1 - from.x0), sy = (to.y1 - to.y0) / (from.y1 - from.y0);
    return Affine{sx, 0, 0, sy, to.x0 - from.x0 * sx, to.y0 - from.y0 * sy};
  }

  void set_up_viewport(pugi::xml_node root) {
    if (const pugi::xml_attribute attr = root.attribute("viewBox")) root_view_box_ = parse_view_box(attr);
    const std::optional<ViewBox>& vb = root_view_box_;
    std::optional<double> width = root_size(root, "width");
    std::optional<double> height = root_size(root, "height");
    if (!width || !height) {
      if (!vb) {
        // Browsers use 300 x 150 here; resvg and librsvg use 100%% of nothing. Both sides missing is an error.
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
    try {
      check_image_size(std::ceil(*width - 1e-9), std::ceil(*height - 1e-9));
    } catch (const Error& e) {
      std::size_t offset = element_offset(root);
      if (*width > kMaxImageSide && root.attribute("width"))
        offset = value_offset(root.attribute("width"));
      else if (*height > kMaxImageSide && root.attribute("height"))
        offset = value_offset(root.attribute("height"));
      fail(offset, e.what());
    }
    tree_.width = *width;
    tree_.height = *height;
    percent_width_ = vb ? vb->width : *width;
    percent_height_ = vb ? vb->height : *height;
    root_viewport_ = vb ? view_box_transform(*vb, *width, *height, root.attribute("preserveAspectRatio")) : Affine{};
  }

  /// The root group's transform: its own transform applies in the viewport, outside the viewBox mapping.
  Affine root_transform(pugi::xml_node root, const Style& style) { return own_transform(root, &style) * root_viewport_; }

  /// The transform attribute (identity when absent or invalid, with a warning).
  /// The element's transform: a CSS `transform` in `style` (from a style sheet or style attribute) when there is
  /// one, else the transform attribute (SVG 2: the attribute is the property's presentation attribute).
  Affine own_transform(pugi::xml_node node, const Style* style = nullptr) {
    Affine own;
    if (style && style->css_transform) {
      own = *style->css_transform;
    } else if (const pugi::xml_attribute t = node.attribute("transform")) {
      if (!parse_transform(t.value(), own)) {
        warn("invalid values", value_offset(t), "invalid transform " + quoted(t.value()) + ", ignored");
        own = Affine{};
      }
    }
    return around_origin(node, own);
  }

  /// `m` applied around the element's transform-origin (SVG 2 / CSS Transforms: translate(origin) m
  /// translate(-origin)). The origin is one or two of: a length, a percentage of the viewport, left, center,
  /// right, top, bottom (a third, z, value is ignored); an invalid one is ignored with a warning.
  Affine around_origin(pugi::xml_node node, const Affine& m) {
    const pugi::xml_attribute attr = node.attribute("transform-origin");
    if (!attr || m.is_identity()) return m;
    std::vector<std::string_view> parts;
    const std::string_view v = trim(attr.value());
    for (std::size_t i = 0; i < v.size();) {
      while (i < v.size() && v[i] == ' ') ++i;
      const std::size_t start = i;
      while (i < v.size() && v[i] != ' ') ++i;
      if (i > start) parts.push_back(v.substr(start, i - start));
    }
    // A keyword's axis and position as a fraction of the viewport; a length or percentage fits either axis.
    struct Part {
      char axis;  // 'x', 'y' or '?'
      double fraction = 0;
      std::string_view length;
    };
    auto read = [](std::string_view t) {
      if (t == "left") return Part{'x', 0, {}};
      if (t == "right") return Part{'x', 1, {}};
      if (t == "top") return Part{'y', 0, {}};
      if (t == "bottom") return Part{'y', 1, {}};
      if (t == "center") return Part{'c', 0.5, {}};
      return Part{'?', 0, t};
    };
    if (parts.empty() || parts.size() > 3) {
      warn("invalid values", value_offset(attr), "invalid transform-origin " + quoted(v) + ", ignored");
      return m;
    }
    Part x{'c', 0.5, {}}, y{'c', 0.5, {}};
    const Part first = read(parts[0]);
    const Part second = parts.size() > 1 ? read(parts[1]) : Part{'c', 0.5, {}};
    if (first.axis == 'y' || second.axis == 'x') {
      x = second;
      y = first;
    } else {
      x = first;
      y = second;
    }
    double origin[2] = {0, 0};
    const Part* axes[2] = {&x, &y};
    for (int k = 0; k < 2; ++k) {
      const Part& p = *axes[k];
      const Axis axis = k == 0 ? Axis::X : Axis::Y;
      if (p.axis == '?') {
        if (!parse_length(p.length, axis, origin[k])) {
          warn("invalid values", value_offset(attr), "invalid transform-origin " + quoted(v) + ", ignored");
          return m;
        }
      } else if ((k == 0 && p.axis == 'y') || (k == 1 && p.axis == 'x')) {
        warn("invalid values", value_offset(attr), "invalid transform-origin " + quoted(v) + ", ignored");
        return m;
      } else {
        double full = 0;
        parse_length("100%", axis, full);
        origin[k] = p.fraction * full;
      }
    }
    return Affine::translate(origin[0], origin[1]) * m * Affine::translate(-origin[0], -origin[1]);
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
        // SVG: render the path up to the first error.
        warn("path data", value_offset(d, e.offset()), "path data: " + e.message() + ", drawn up to there");
      } catch (const ParseError&) {
        throw;
      } catch (const Error& e) {
        fail(at, e.what());
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
          path.add_round_rect(r, std::min(*rx, w / 2), std::min(*ry, h / 2));
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
        if (rx && *rx < 0) rx.reset();
        if (ry && *ry < 0) ry.reset();
        if (!rx) rx = ry;  // SVG 2: a missing radius is "auto", the other one
        if (!ry) ry = rx;
      }
      if (rx.value_or(0) < 0 || ry.value_or(0) < 0) {
        warn("negative sizes", at, "<" + std::string(name) + "> with a negative radius, ignored");
        return path;
      }
      if (rx.value_or(0) > 0 && ry.value_or(0) > 0) build(at, [&] { path.add_ellipse(c, *rx, *ry); });
    } else if (name == "polygon" || name == "polyline") {
      // SVG: numbers up to the first error; an odd last coordinate is dropped.
      const pugi::xml_attribute attr = node.attribute("points");
      const std::string_view s = attr.value();
      std::vector<Point> points;
      std::vector<double> numbers;
      std::size_t pos = 0;
      detail::skip_wsp(s, pos);
      while (pos < s.size()) {
        const std::size_t start = pos;
        double v = 0;
        if (scan_number(s, pos, v) != NumberScan::Ok) {
          warn("invalid values", value_offset(attr, start), "points: expected a number; the points before are drawn");
          break;
        }
        numbers.push_back(v);
        detail::skip_comma_wsp(s, pos);
      }
      if (numbers.size() % 2 != 0) {
        warn("invalid values", value_offset(attr), "points: odd number of coordinates, the last one is dropped");
        numbers.pop_back();
      }
      for (std::size_t i = 0; i + 1 < numbers.size(); i += 2) points.push_back({numbers[i], numbers[i + 1]});
      if (points.size() >= 2) build(at, [&] { path.add_polygon(points, name == "polygon"); });
    } else if (name == "line") {
      const Point p0{get("x1", Axis::X).value_or(0), get("y1", Axis::Y).value_or(0)};
      const Point p1{get("x2", Axis::X).value_or(0), get("y2", Axis::Y).value_or(0)};
      build(at, [&] { path.move_to(p0).line_to(p1); });
    }
    return path;
  }

  /// Whether conditional processing attributes let the element render (SVG 1.1 section 5.8.2; the user's
  /// language is English, we support no extensions, requiredFeatures is true as SVG 2 says).
  bool conditions_pass(pugi::xml_node node) const {
    if (const pugi::xml_attribute ext = node.attribute("requiredExtensions")) {
      (void)ext;
      return false;  // an empty value is false too
    }
    if (const pugi::xml_attribute lang = node.attribute("systemLanguage")) {
      std::string_view list = lang.value();
      bool any = false;
      while (!list.empty()) {
        const std::size_t comma = list.find(',');
        const std::string_view item = trim(list.substr(0, comma));
        if (iequals(item, "en") || detail::istarts_with(item, "en-")) any = true;
        if (comma == std::string_view::npos) break;
        list.remove_prefix(comma + 1);
      }
      if (!any) return false;
    }
    return true;
  }

  /// Elements that never render where they stand (referenced only, or holding no graphics).
  static bool switch_candidate(std::string_view name) {
    static constexpr std::string_view kNames[] = {"a",    "foreignObject", "g",      "image",   "svg",     "switch",
                                                  "text", "use",           "path",   "rect",    "circle",  "ellipse",
                                                  "line", "polyline",      "polygon"};
    return std::find(std::begin(kNames), std::end(kNames), name) != std::end(kNames);
  }

  static bool never_rendered(std::string_view name) {
    static constexpr std::string_view kNames[] = {
        "defs",   "title", "desc",   "metadata", "symbol", "linearGradient", "radialGradient", "pattern", "clipPath",
        "mask",   "marker", "filter", "style",   "script", "stop",           "font",           "font-face", "cursor",
        "view",   "animate", "set",   "animateMotion", "animateTransform", "animateColor", "mpath"};
    return std::find(std::begin(kNames), std::end(kNames), name) != std::end(kNames);
  }

  void count_element(std::size_t at, int depth) {
    if (++element_count_ > kMaxElements)
      fail(at, "too many elements (the limit is " + std::to_string(kMaxElements) + ", <use> instances included)");
    if (depth > kMaxDepth)
      fail(at, "elements nested too deeply (the limit is " + std::to_string(kMaxDepth) + " levels, <use> included)");
  }

  /// Appends the nodes of the children of `node` (computed style `style`).
  void children(pugi::xml_node node, const Style& style, std::vector<Node>& out, int depth) {
    // Room for every element child at once (most become one node): a group of a million shapes would otherwise
    // grow by doubling, copying its nodes and holding two copies at each step.
    std::size_t elements = 0;
    for (const pugi::xml_node child : node.children()) elements += child.type() == pugi::node_element;
    if (elements > 1 && out.capacity() < out.size() + elements)
      out.reserve(std::max(out.size() + elements, 2 * out.capacity()));  // geometric: calls may share `out`
    for (const pugi::xml_node child : node.children()) {
      if (child.type() == pugi::node_element) element(child, style, out, depth + 1);
    }
  }

  /// The group effects of a computed style: opacity, blend mode, isolation, clip path, mask. `at` is where the
  /// element starts (for warnings about its references).
  void apply_group_effects(const Style& style, Group& g, std::size_t at) {
    g.opacity = style.opacity;
    g.blend_mode = style.blend_mode;
    g.isolate = style.isolate;
    if (!style.clip_path.empty()) g.clip = clip_path(style.clip_path, at);
    if (!style.mask.empty()) g.mask = mask(style.mask, at);
  }

  /// Sets the font size that em and ex lengths refer to for as long as it lives.
  class FontSizeScope {
   public:
    FontSizeScope(Builder& b, double font_size) : b_(b), saved_(std::exchange(b.font_size_, font_size)) {}
    ~FontSizeScope() { b_.font_size_ = saved_; }
    FontSizeScope(const FontSizeScope&) = delete;
    FontSizeScope& operator=(const FontSizeScope&) = delete;

   private:
    Builder& b_;
    double saved_;
  };

  /// Appends what `node` draws to `out`.
  void element(pugi::xml_node node, const Style& parent, std::vector<Node>& out, int depth) {
    const std::size_t at = element_offset(node);
    count_element(at, depth);
    const std::string_view name = local_name(node);
    if (name.empty() || never_rendered(name)) return;  // foreign namespaces are skipped silently
    if (!conditions_pass(node)) return;
    const bool container = name == "g" || name == "a" || name == "switch";
    const bool shape = name == "path" || name == "rect" || name == "circle" || name == "ellipse" || name == "line" ||
                       name == "polyline" || name == "polygon";
    const bool known = container || shape || name == "use" || name == "svg" || name == "image" || name == "text";
    if (!known) {
      warn("unsupported elements", at, "element <" + printable(name) + "> is not supported yet, ignored");
      return;
    }
    // A clipPath's children: shapes, text and uses of shapes only.
    if (in_clip_ && !shape && name != "use" && name != "text") return;
    const Style style = computed(node, parent);
    if (!style.displayed) return;  // display: none hides the whole subtree
    const FontSizeScope font_size(*this, style.text.font_size);  // for em and ex in the attributes

    Group group;
    group.id = node.attribute("id").value();
    group.transform = own_transform(node, &style);
    if (!group.transform.is_finite()) fail(at, "transform out of range");
    apply_group_effects(style, group, at);

    if (container) {
      if (name == "switch") {
        for (const pugi::xml_node child : node.children()) {
          if (child.type() != pugi::node_element || !conditions_pass(child)) continue;
          // Only graphics and container elements are candidates (SVG 2, 5.8.2: what switch may contain);
          // an unknown element or a resource is passed over.
          if (!switch_candidate(local_name(child))) continue;
          element(child, style, group.children, depth + 1);
          break;
        }
      } else {
        children(node, style, group.children, depth);
      }
    } else if (name == "svg") {
      nested_viewport(node, node, style, group, depth, std::nullopt, std::nullopt);
    } else if (name == "use") {
      if (!use_element(node, style, group, depth)) return;
    } else if (name == "text") {
      TextAdapter host(*this, style, depth);
      if (!fonts_) fonts_ = options_.fonts ? options_.fonts : detail::default_font_db();
      detail::build_text(node, span_style(style), host, fonts_.get(), group);
    } else if (name == "image") {
      image_element(node, style, group, at);
    } else {
      Path geometry = shape_path(node, name);
      const bool marked = !style.marker_start.empty() || !style.marker_mid.empty() || !style.marker_end.empty();
      std::optional<Group> markers;
      if (marked) {  // the ellipse's marker path (and its exact bounds) only where markers may be drawn
        markers = (name == "circle" || name == "ellipse") && !geometry.empty()
                      ? markers_of(detail::ellipse_marker_path(geometry.bounds()), style, at)
                      : markers_of(geometry, style, at);
      }
      std::optional<PathNode> path = path_node(node, std::move(geometry), name, style, at);
      if (markers) {
        add_with_markers(std::move(path), std::move(*markers), style.markers_position, group.children);
      } else if (!path) {
        return;
      } else if (group.transform.is_identity() && !group.needs_layer()) {
        out.push_back(Node{std::move(*path)});
        return;
      } else {
        group.children.push_back(Node{std::move(*path)});
      }
    }
    if (!group.children.empty()) out.push_back(Node{std::move(group)});
  }

  /// A shape's PathNode, or nothing when it paints nothing.
  std::optional<PathNode> path_node(pugi::xml_node node, Path path, std::string_view name, const Style& style, std::size_t at) {
    const auto verbs = path.verbs();
    if (std::all_of(verbs.begin(), verbs.end(), [](Verb v) { return v == Verb::Move; })) return std::nullopt;
    PathNode p;
    p.id = node.attribute("id").value();
    std::tie(p.line, p.column) = lines_.position(at);
    if (in_clip_) {  // clip geometry: fill and stroke have no effect, clip-rule is the rule
      if (style.visible) p.fill = Fill{opaque_black(), style.clip_rule};
    } else if (style.visible && name != "line") {
      const Paint paint = resolve_paint(style.fill, style.fill_opacity, style);
      if (paint.kind != Paint::Kind::None) p.fill = Fill{paint, style.fill_rule};
    }
    if (!in_clip_ && style.visible && style.stroke_style.width > 0) {
      const Paint paint = resolve_paint(style.stroke, style.stroke_opacity, style);
      if (paint.kind != Paint::Kind::None) {
        p.stroke = Stroke{paint, style.stroke_style};
        warn_about_dashes(path, style.stroke_style, at);
      }
    }
    // A shape that paints nothing (fill and stroke none, visibility hidden) still counts in the bounding box
    // of the groups around it (SVG 2, 8.10: every rendered element's geometry); in a clip path it is nothing.
    if (!p.fill && !p.stroke && in_clip_) return std::nullopt;
    p.path = std::move(path);
    p.stroke_first = style.stroke_first;
    p.crisp_edges = style.crisp_edges;
    return p;
  }

  // ---- markers ----

  /// A marker element, resolved once: its content and how an instance is placed.
  struct MarkerDef {
    pugi::xml_node node;
    Style style;                            ///< the marker's computed style (from its own ancestors)
    double percent_width = 0, percent_height = 0;  ///< what percentages in the content refer to
    bool usable = false;                    ///< a positive size and a finite viewBox transform
    std::shared_ptr<const Group> content;   ///< built for the first shape; null: the marker draws nothing
    bool uses_context = false;              ///< content uses context-fill / context-stroke: built per shape
    Affine view_box;                        ///< content -> marker viewport (viewBox and preserveAspectRatio)
    Point ref;                              ///< refX, refY mapped into the marker viewport
    double width = 3, height = 3;           ///< markerWidth, markerHeight
    bool stroke_units = true;               ///< markerUnits="strokeWidth"
    enum class Orient { Angle, Auto, AutoStartReverse } orient = Orient::Angle;
    double angle = 0;                       ///< orient as an angle, degrees
    bool clip = true;                       ///< overflow hidden (the default for markers)
    std::shared_ptr<const ClipPath> viewport_clip;  ///< the clip every instance shares (when `clip`)
  };

  /// The markers of a shape as one group of instances (in the shape's user space), or nothing when it has
  /// none. Shapes inside a marker have markers too, except a marker whose content is being built (a marker
  /// reached again through its own content is left out there, as resvg does: no recursion).
  std::optional<Group> markers_of(const Path& path, const Style& style, std::size_t at) {
    if (in_clip_path_ > 0 || !style.visible) return std::nullopt;
    if (style.marker_start.empty() && style.marker_mid.empty() && style.marker_end.empty()) return std::nullopt;
    // Inside a marker, which markers apply depends on the markers being built: the enclosing content cannot be
    // shared with other shapes (it is built per shape, like content with context paints).
    if (!marker_stack_.empty()) context_used_ = true;
    // context-fill and context-stroke in marker content are this shape's paints.
    const Paint fill = style.visible ? resolve_paint(style.fill, style.fill_opacity, style) : Paint{};
    const Paint stroke = style.stroke_style.width > 0 ? resolve_paint(style.stroke, style.stroke_opacity, style) : Paint{};
    std::unordered_map<const MarkerDef*, std::shared_ptr<const Group>> contents;  // per shape, for context paints
    auto content_of = [&](const MarkerDef* def) {
      if (!def->uses_context) return def->content;
      auto& built = contents[def];
      if (!built) built = marker_content(*def, &fill, &stroke, nullptr);
      return built;
    };
    std::optional<Rect> shape_box;  // what context paints in the content refer to (once: paths can be long)
    Group all;
    for (const detail::MarkerVertex& v : detail::marker_vertices(path)) {
      using K = detail::MarkerVertex::Kind;
      const std::string& id = v.kind == K::Start ? style.marker_start : v.kind == K::Mid ? style.marker_mid : style.marker_end;
      if (id.empty()) continue;
      const MarkerDef* def = marker_def(id, at, fill, stroke);
      if (!def || !def->usable) continue;
      const std::shared_ptr<const Group> marker_content = content_of(def);
      if (!marker_content) continue;
      const double scale = def->stroke_units ? style.stroke_style.width : 1;
      if (!(scale > 0)) continue;
      double angle = def->angle;
      if (def->orient != MarkerDef::Orient::Angle) angle = v.angle;
      if (def->orient == MarkerDef::Orient::AutoStartReverse && v.kind == K::Start) angle += 180;
      Group instance;
      instance.transform = Affine::translate(v.at.x, v.at.y) * Affine::rotate(angle) * Affine::scale(scale) *
                           Affine::translate(-def->ref.x, -def->ref.y);
      if (!instance.transform.is_finite()) continue;
      instance.clip = def->viewport_clip;
      Group content = *marker_content;
      content.transform = def->view_box;
      element_count_ += count_nodes(content);
      if (element_count_ > kMaxElements)
        fail(at, "too many elements (the limit is " + std::to_string(kMaxElements) + ", marker instances included)");
      instance.children.push_back(Node{std::move(content)});
      if (def->uses_context) {
        if (!shape_box) shape_box = path.bounds();
        place_context_paints(instance, instance.transform, *shape_box);
      }
      all.children.push_back(Node{std::move(instance)});
    }
    if (all.children.empty()) return std::nullopt;
    return all;
  }

  /// Places the context paints below `g` that no context element has placed yet (the innermost context element
  /// places first) in their context element's space: `to_context` maps `g`'s children's space into it, `box` is
  /// the context element's object bounding box there. A space that cannot be inverted paints nothing.
  static void place_context_paints(Group& g, const Affine& to_context, const Rect& box) {
    auto place = [&](Paint& paint, const Affine& m) {
      if (!paint.from_context) return;
      paint.from_context = false;
      if (!m.invertible()) {
        paint.kind = Paint::Kind::None;
        return;
      }
      paint.context = std::make_shared<const ContextPlacement>(ContextPlacement{m.inverse(), box});
    };
    for (Node& child : g.children) {
      if (Group* sub = std::get_if<Group>(&child.value)) {
        place_context_paints(*sub, to_context * sub->transform, box);
      } else if (PathNode* p = std::get_if<PathNode>(&child.value)) {
        if (p->fill) place(p->fill->paint, to_context);
        if (p->stroke) place(p->stroke->paint, to_context);
      }
    }
  }

  /// The path and its markers in paint order: markers first, between fill and stroke (the path split in two),
  /// or last.
  static void add_with_markers(std::optional<PathNode> path, Group markers, std::uint8_t position, std::vector<Node>& out) {
    if (!path || position == 2) {
      if (path) out.push_back(Node{std::move(*path)});
      out.push_back(Node{std::move(markers)});
      return;
    }
    if (position == 0 || !path->fill || !path->stroke) {
      // Markers before both paints, or in the middle of one paint: before the path unless the paint that
      // comes first is the one it has.
      const bool path_first = position == 1 && ((path->stroke_first && path->stroke) || (!path->stroke_first && path->fill));
      if (path_first) out.push_back(Node{std::move(*path)});
      out.push_back(Node{std::move(markers)});
      if (!path_first) out.push_back(Node{std::move(*path)});
      return;
    }
    PathNode first = *path, second = std::move(*path);
    if (first.stroke_first) {
      first.fill.reset();
      second.stroke.reset();
    } else {
      first.stroke.reset();
      second.fill.reset();
    }
    out.push_back(Node{std::move(first)});
    out.push_back(Node{std::move(markers)});
    out.push_back(Node{std::move(second)});
  }

  /// A marker's placement and its content as built for the first shape that uses it (`fill` and `stroke` are
  /// that shape's paints, for context-fill and context-stroke).
  const MarkerDef* marker_def(const std::string& id, std::size_t at, const Paint& fill, const Paint& stroke) {
    const pugi::xml_node node = by_id(id);
    if (!node || local_name(node) != "marker") {
      warn("references", at, "no marker with id " + quoted(id) + ", ignored");
      return nullptr;
    }
    // A marker whose content is being built is left out inside it (no recursion).
    if (std::find(marker_stack_.begin(), marker_stack_.end(), node) != marker_stack_.end()) return nullptr;
    if (marker_stack_.size() >= kMaxMarkerNesting) return nullptr;
    const auto cached = markers_.find(node.internal_object());
    if (cached != markers_.end()) return &cached->second;
    MarkerDef def;
    def.node = node;
    // markerWidth and markerHeight: 3 by default; zero or negative disables the marker. Percentages here and in
    // refX / refY refer to the viewport the marker is defined in.
    def.width = length_attribute(node, "markerWidth", Axis::X).value_or(3);
    def.height = length_attribute(node, "markerHeight", Axis::Y).value_or(3);
    const Point ref{length_attribute(node, "refX", Axis::X).value_or(0), length_attribute(node, "refY", Axis::Y).value_or(0)};
    def.stroke_units = trim(node.attribute("markerUnits").value()) != "userSpaceOnUse";
    const std::string_view orient = trim(node.attribute("orient").value());
    if (orient == "auto") {
      def.orient = MarkerDef::Orient::Auto;
    } else if (orient == "auto-start-reverse") {
      def.orient = MarkerDef::Orient::AutoStartReverse;
    } else if (!orient.empty()) {
      def.angle = parse_angle(orient).value_or(0);
    }
    std::optional<ViewBox> vb;
    if (const pugi::xml_attribute attr = node.attribute("viewBox")) vb = parse_view_box(attr);
    if (def.width > 0 && def.height > 0) {
      def.view_box = vb ? view_box_transform(*vb, def.width, def.height, node.attribute("preserveAspectRatio")) : Affine{};
      def.usable = def.view_box.is_finite();
      // Content lengths in percentages refer to the marker's viewBox (or its size).
      def.percent_width = vb ? vb->width : def.width;
      def.percent_height = vb ? vb->height : def.height;
      def.ref = def.view_box.apply(ref);
      // Properties inherit from the marker's own ancestors, not from the shape that uses it.
      def.style = style_from_ancestors(node);
      def.clip = !def.style.overflow_visible;
      if (def.clip) def.viewport_clip = rect_clip(Rect{0, 0, def.width, def.height});
      if (def.usable) def.content = marker_content(def, &fill, &stroke, &def.uses_context);
    }
    return &markers_.emplace(node.internal_object(), std::move(def)).first->second;
  }

  /// The content of a marker (null when empty), with context paints from `fill` and `stroke`; `uses_context`
  /// (when given) says whether any was needed.
  std::shared_ptr<const Group> marker_content(const MarkerDef& def, const Paint* fill, const Paint* stroke,
                                              bool* uses_context) {
    const double saved_w = percent_width_, saved_h = percent_height_;
    const Paint* saved_fill = context_fill_;
    const Paint* saved_stroke = context_stroke_;
    const bool saved_used = context_used_;
    percent_width_ = def.percent_width;
    percent_height_ = def.percent_height;
    context_fill_ = fill;
    context_stroke_ = stroke;
    context_used_ = false;
    auto content = std::make_shared<Group>();
    ++in_marker_;
    marker_stack_.push_back(def.node);
    // Marker content is drawn apart from the shape, like a pattern tile: a `use` being instanced around the
    // shape is no loop there (marker_stack_ stops markers from recursing).
    std::vector<pugi::xml_node> outer_uses = std::exchange(use_stack_, {});
    children(def.node, def.style, content->children, 1);
    use_stack_ = std::move(outer_uses);
    marker_stack_.pop_back();
    --in_marker_;
    if (uses_context) *uses_context = context_used_;
    percent_width_ = saved_w;
    percent_height_ = saved_h;
    context_fill_ = saved_fill;
    context_stroke_ = saved_stroke;
    context_used_ = saved_used;
    if (content->children.empty()) return nullptr;
    return content;
  }

  /// The style the root element inherits from: initial values, the default font size.
  Style initial_style() const {
    Style initial;
    initial.text.font_size = options_.default_font_size;
    return initial;
  }

  /// The computed style of `node` cascaded from the root down through its ancestors. Resources (paint servers,
  /// clip paths, masks, markers) take their properties from where they are in the document, not from the
  /// element that refers to them.
  Style style_from_ancestors(pugi::xml_node node) {
    std::vector<pugi::xml_node> chain;
    for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) chain.push_back(n);
    Style style = initial_style();
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) style = computed(*it, style);
    return style;
  }

  /// An angle: a number of degrees, or a number with deg, grad, rad or turn.
  static std::optional<double> parse_angle(std::string_view v) {
    std::size_t pos = 0;
    double number = 0;
    if (scan_number(v, pos, number) != NumberScan::Ok) return std::nullopt;
    const std::string_view unit = v.substr(pos);
    double factor = 0;
    if (unit.empty() || unit == "deg") factor = 1;
    else if (unit == "grad") factor = 0.9;
    else if (unit == "rad") factor = 180 / 3.14159265358979323846;
    else if (unit == "turn") factor = 360;
    if (factor == 0 || !std::isfinite(number * factor)) return std::nullopt;
    return number * factor;
  }

  /// Says why a dashed stroke is drawn solid (the stroker decides the same way, from the same check).
  void warn_about_dashes(const Path& path, const StrokeStyle& stroke, std::size_t at) {
    switch (check_dashes(path, stroke.dashes)) {
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

  /// A nested viewport (<svg> inside the document, or a <symbol> instanced by <use>): x, y, width, height
  /// (from `size_from`, default 100%), viewBox and preserveAspectRatio of `node`, a clip to the viewport
  /// unless overflow is visible, then the children.
  void nested_viewport(pugi::xml_node node, pugi::xml_node size_from, const Style& style, Group& group, int depth,
                       std::optional<double> use_width, std::optional<double> use_height) {
    const double x = local_name(node) == "svg" ? length_attribute(node, "x", Axis::X).value_or(0) : 0;
    const double y = local_name(node) == "svg" ? length_attribute(node, "y", Axis::Y).value_or(0) : 0;
    double width = use_width ? *use_width : length_attribute(size_from, "width", Axis::X).value_or(percent_width_);
    double height = use_height ? *use_height : length_attribute(size_from, "height", Axis::Y).value_or(percent_height_);
    if (!(width > 0) || !(height > 0)) return;  // a zero-sized viewport draws nothing
    std::optional<ViewBox> vb;
    if (const pugi::xml_attribute attr = node.attribute("viewBox")) vb = parse_view_box(attr);
    Group inner;
    inner.transform = Affine::translate(x, y);
    if (vb) inner.transform = inner.transform * view_box_transform(*vb, width, height, node.attribute("preserveAspectRatio"));
    if (!style.overflow_visible) group.clip = rect_clip(Rect{x, y, x + width, y + height});
    const double saved_w = percent_width_, saved_h = percent_height_;
    percent_width_ = vb ? vb->width : width;
    percent_height_ = vb ? vb->height : height;
    children(node, style, inner.children, depth);
    percent_width_ = saved_w;
    percent_height_ = saved_h;
    if (!inner.children.empty()) group.children.push_back(Node{std::move(inner)});
  }

  /// A clip to a rectangle (a viewport's): an anonymous ClipPath holding the rectangle.
  static std::shared_ptr<const ClipPath> rect_clip(const Rect& r) {
    auto clip = std::make_shared<ClipPath>();
    auto content = std::make_shared<Group>();
    PathNode rect;
    rect.path.add_rect(r);
    rect.fill = Fill{opaque_black(), FillRule::NonZero};
    content->children.push_back(Node{std::move(rect)});
    clip->content = std::move(content);
    return clip;
  }

  /// <use>: an instance of the referenced element (or symbol) under a translate(x, y). Returns false when the
  /// reference is missing or loops (the use draws nothing, with a warning, as browsers do).
  bool use_element(pugi::xml_node node, const Style& style, Group& group, int depth) {
    const pugi::xml_node target = href_target(node);
    if (!target) return false;
    const std::size_t at = element_offset(node);
    for (pugi::xml_node n = node; n; n = n.parent()) {
      if (n == target) {
        warn("references", at, "<use> refers to an element that contains it (a reference loop), ignored");
        return false;
      }
    }
    if (std::find(use_stack_.begin(), use_stack_.end(), target) != use_stack_.end()) {
      warn("references", at, "<use> reference loop through " + quoted(target.attribute("id").value()) + ", ignored");
      return false;
    }
    // Only instances made inside another use's instance multiply (each level copies the one below): a flat list of
    // uses is bounded by the file itself (a scatter plot of 200,000 points is a normal document).
    if (!use_stack_.empty() && ++use_instances_ > kMaxUseInstances) {
      fail(at, "too many <use> instances (the limit is " + std::to_string(kMaxUseInstances) +
                   "): nested uses multiply; is this a \"billion laughs\" document?");
    }
    const double x = length_attribute(node, "x", Axis::X).value_or(0);
    const double y = length_attribute(node, "y", Axis::Y).value_or(0);
    group.transform = group.transform * Affine::translate(x, y);
    if (in_clip_ && (local_name(target) == "symbol" || local_name(target) == "svg")) return false;
    use_stack_.push_back(target);
    // SVG 2: inside a use, context-fill and context-stroke are the use element's own paints.
    const Paint context_fill = resolve_paint(style.fill, style.fill_opacity, style);
    const Paint context_stroke = resolve_paint(style.stroke, style.stroke_opacity, style);
    const Paint* saved_fill = context_fill_;
    const Paint* saved_stroke = context_stroke_;
    const bool saved_used = std::exchange(context_used_, false);
    context_fill_ = &context_fill;
    context_stroke_ = &context_stroke;
    if (local_name(target) == "symbol") {
      count_element(element_offset(target), depth + 1);
      const Style symbol_style = computed(target, style);
      if (symbol_style.displayed) {
        Group symbol;
        apply_group_effects(symbol_style, symbol, element_offset(target));
        symbol.transform = own_transform(target, &symbol_style);
        nested_viewport(target, target, symbol_style, symbol, depth + 1, length_attribute(node, "width", Axis::X),
                        length_attribute(node, "height", Axis::Y));
        if (!symbol.children.empty()) group.children.push_back(Node{std::move(symbol)});
      }
    } else if (local_name(target) == "svg") {
      Group inner;
      const Style svg_style = computed(target, style);
      if (svg_style.displayed) {
        apply_group_effects(svg_style, inner, element_offset(target));
        nested_viewport(target, target, svg_style, inner, depth + 1, length_attribute(node, "width", Axis::X),
                        length_attribute(node, "height", Axis::Y));
        if (!inner.children.empty()) group.children.push_back(Node{std::move(inner)});
      }
    } else {
      element(target, style, group.children, depth + 1);
    }
    context_fill_ = saved_fill;
    context_stroke_ = saved_stroke;
    use_stack_.pop_back();
    // The use element's user space is the group's before translate(x, y); its box is its content's there.
    if (context_used_) {
      const Affine content_to_use = Affine::translate(x, y);
      place_context_paints(group, content_to_use, object_bounds(group, content_to_use).value_or(Rect{}));
    }
    context_used_ = saved_used || context_used_;
    return true;
  }

  // ---- <image> ----

  /// What an href gives: decoded pixels, a parsed SVG document, or nothing (`error` says why).
  struct LoadedImage {
    std::shared_ptr<const Image> raster;
    std::shared_ptr<const Tree> svg;
    std::string error;
  };

  /// <image>: a raster image becomes an ImageNode (null pixels when it cannot be had, with a warning); an SVG
  /// document becomes its root group, placed by preserveAspectRatio and clipped to where it shows.
  void image_element(pugi::xml_node node, const Style& style, Group& group, std::size_t at) {
    if (in_clip_path_ > 0) return;  // not clipPath content (SVG: shapes, text and use only)
    pugi::xml_attribute href = node.attribute("href");
    if (!href) href = node.attribute("xlink:href");
    const std::string_view link = trim(href.value());
    const std::size_t href_at = href ? value_offset(href) : at;
    const LoadedImage& loaded = load_image(link, href_at);
    if (!loaded.error.empty()) warn("images", href_at, "<image> " + quoted(link) + ": " + loaded.error + "; not drawn");
    // Intrinsic size: the pixels, or the SVG document's own size.
    double iw = 0, ih = 0;
    if (loaded.raster) {
      iw = loaded.raster->width;
      ih = loaded.raster->height;
    } else if (loaded.svg) {
      iw = loaded.svg->width;
      ih = loaded.svg->height;
    }
    // SVG 2: width and height are auto when absent; auto takes the intrinsic size, or keeps its aspect ratio
    // when the other side is given.
    std::optional<double> w = image_size(node, "width", Axis::X), h = image_size(node, "height", Axis::Y);
    if (!w && !h) {
      w = iw;
      h = ih;
    } else if (!w) {
      w = ih > 0 ? *h * iw / ih : 0;
    } else if (!h) {
      h = iw > 0 ? *w * ih / iw : 0;
    }
    if (!(*w > 0) || !(*h > 0) || !style.visible) return;  // a zero size or hidden: nothing drawn
    const double x = length_attribute(node, "x", Axis::X).value_or(0);
    const double y = length_attribute(node, "y", Axis::Y).value_or(0);
    const Rect view{x, y, x + *w, y + *h};
    const detail::AspectRatio aspect = parse_aspect(node.attribute("preserveAspectRatio"));
    if (loaded.svg) {
      const Tree& doc = *loaded.svg;
      const Rect dest = detail::fit_rect(view, doc.width, doc.height, aspect);
      // The document shows inside its own canvas and inside the viewport, whichever is smaller.
      Group clipped;
      clipped.clip = rect_clip(Rect{std::max(view.x0, dest.x0), std::max(view.y0, dest.y0), std::min(view.x1, dest.x1),
                                    std::min(view.y1, dest.y1)});
      Group content = doc.root;
      content.transform = rect_transform(Rect{0, 0, doc.width, doc.height}, dest) * content.transform;
      if (!content.transform.is_finite()) fail(at, "image transform out of range");
      element_count_ += count_nodes(doc.root);
      if (element_count_ > kMaxElements) fail(at, "too many elements (the limit is " + std::to_string(kMaxElements) +
                                                      ", SVG images and <use> instances included)");
      clipped.children.push_back(Node{std::move(content)});
      group.children.push_back(Node{std::move(clipped)});
      return;
    }
    ImageNode image;
    image.id = node.attribute("id").value();
    // A data: URL can be megabytes: the tree keeps its head only.
    image.href = detail::istarts_with(link, "data:") ? std::string(link.substr(0, link.find(','))) + ",..." : std::string(link);
    image.image = loaded.raster;
    image.view = view;
    image.clip = view;
    image.dest = loaded.raster ? detail::fit_rect(view, iw, ih, aspect) : view;
    image.smooth = style.smooth_images;
    std::tie(image.line, image.column) = lines_.position(at);
    group.children.push_back(Node{std::move(image)});
  }

  /// width or height of an <image>: nothing when absent or auto; negative sizes are reported and read as 0.
  std::optional<double> image_size(pugi::xml_node node, const char* name, Axis axis) {
    if (trim(node.attribute(name).value()) == "auto") return std::nullopt;
    std::optional<double> v = length_attribute(node, name, axis);
    if (v && *v < 0) {
      warn("negative sizes", value_offset(node.attribute(name)), std::string("<image> with a negative ") + name + ", not drawn");
      return 0.0;
    }
    return v;
  }

  /// The image an href names, loaded once per document (a <use> of an <image> shares the pixels).
  const LoadedImage& load_image(std::string_view href, std::size_t at) {
    const std::string key(href);
    const auto cached = images_.find(key);
    if (cached != images_.end()) return cached->second;
    return images_.emplace(key, read_image(key, at)).first->second;
  }

  /// Reads, sniffs and decodes (or parses) what an href names; `at` is where the href is, for the warnings of
  /// an SVG image.
  LoadedImage read_image(const std::string& href, std::size_t at) {
    LoadedImage out;
    if (href.empty()) {
      out.error = "no href";
      return out;
    }
    std::vector<std::uint8_t> bytes;
    std::string mime, name = "<data: URL>";
    if (detail::istarts_with(href, "data:")) {
      std::optional<detail::DataUrl> url = detail::parse_data_url(href, out.error);
      if (!url) return out;
      bytes = std::move(url->bytes);
      mime = std::move(url->mime);
    } else {
      const std::optional<std::string> path = detail::resolve_image_file(href, options_, out.error);
      if (!path) return out;
      try {
        bytes = read_file_limited(*path, kMaxSvgFileBytes, "image file");
      } catch (const Error& e) {
        out.error = e.what();
        return out;
      }
      name = *path;
    }
    const std::span<const std::uint8_t> data(bytes);
    if (sniff_image_format(data) != ImageFormat::Unknown) {
      if (pixels_left_ <= 0) {
        out.error = "the document's decoded images reach the limit of " + std::to_string(kMaxDocumentImagePixels) + " pixels";
        return out;
      }
      try {
        auto image = std::make_shared<Image>(decode_image(data));
        pixels_left_ -= std::int64_t{image->width} * image->height;
        out.raster = std::move(image);
      } catch (const Error& e) {
        out.error = e.what();
      } catch (const std::bad_alloc&) {
        out.error = "out of memory while decoding";
      }
      return out;
    }
    if (!detail::looks_like_svg(data, mime)) {
      out.error = "not an image format vraster reads (PNG, JPEG, GIF, WebP, SVG)";
      return out;
    }
    if (image_depth_ >= kMaxImageNesting) {
      out.error = "SVG images nested more than " + std::to_string(kMaxImageNesting) + " levels deep";
      return out;
    }
    std::string text;
    if (detail::is_gzip(data)) {
      std::optional<std::string> inflated = detail::gunzip(data, kMaxSvgFileBytes, out.error);
      if (!inflated) return out;
      text = std::move(*inflated);
    } else {
      text.assign(bytes.begin(), bytes.end());
    }
    try {
      // Secure mode (SVG 2, "image"): the image reads no external file, whatever its own hrefs say.
      ParseOptions secure;
      secure.dpi = options_.dpi;  // the same physical units as the document around it
      Builder nested(text, name, secure, image_depth_ + 1, pixels_left_);
      auto tree = std::make_shared<Tree>(nested.run());
      if (!tree->warnings.empty())
        warn("images", at, "in the SVG image " + quoted(href) + ": " + tree->warnings.front() +
                              (tree->warnings.size() > 1 ? " (and " + std::to_string(tree->warnings.size() - 1) + " more)" : ""));
      out.svg = std::move(tree);
    } catch (const Error& e) {
      out.error = std::string("the SVG image cannot be used: ") + e.what();
    }
    return out;
  }


  // ---- text (text.cpp lays it out; these are the services it needs) ----

  detail::SpanStyle span_style(const Style& s) {
    detail::SpanStyle out;
    out.text = s.text;
    if (in_clip_) {  // clip geometry, as path_node: filled with the clip-rule, never stroked
      if (s.visible) out.fill = Fill{opaque_black(), s.clip_rule};
    } else if (s.visible) {
      const Paint fill = resolve_paint(s.fill, s.fill_opacity, s);
      if (fill.kind != Paint::Kind::None) out.fill = Fill{fill, s.fill_rule};
      const Paint stroke = s.stroke_style.width > 0 ? resolve_paint(s.stroke, s.stroke_opacity, s) : Paint{};
      if (stroke.kind != Paint::Kind::None) out.stroke = Stroke{stroke, s.stroke_style};
    }
    out.stroke_first = s.stroke_first;
    out.crisp_edges = s.crisp_edges;
    return out;
  }

  class TextAdapter final : public detail::TextHost {
   public:
    TextAdapter(Builder& b, const Style& style, int depth) : b_(b) { stack_.push_back({style, depth}); }
    std::optional<detail::SpanStyle> enter(pugi::xml_node node) override {
      const int depth = stack_.back().second + 1;
      b_.count_element(b_.element_offset(node), depth);
      Style s = b_.computed(node, stack_.back().first);
      if (!s.displayed) return std::nullopt;
      stack_.emplace_back(std::move(s), depth);
      return b_.span_style(stack_.back().first);
    }
    void leave() override { stack_.pop_back(); }
    void warn(pugi::xml_node node, const std::string& message) override {
      b_.warn("text", b_.element_offset(node), message);
    }
    pugi::xml_node href_target(pugi::xml_node node) override { return b_.href_target(node); }
    Path shape_of(pugi::xml_node node) override {
      const std::string_view name = b_.local_name(node);
      if (name != "path" && name != "rect" && name != "circle" && name != "ellipse" && name != "line" &&
          name != "polyline" && name != "polygon")
        return {};
      Path path = b_.shape_path(node, name);
      const Affine m = b_.own_transform(node);
      if (!m.is_finite()) return {};
      path.transform(m);
      return path;
    }
    bool length(std::string_view value, int axis, double& out) override {
      return b_.parse_length(value, axis == 0 ? Axis::X : axis == 1 ? Axis::Y : Axis::Other, out);
    }
    std::pair<int, int> position(pugi::xml_node node) override { return b_.lines_.position(b_.element_offset(node)); }
    bool take_character() override { return ++b_.text_characters_ <= detail::kMaxTextCharacters; }

   private:
    Builder& b_;
    std::vector<std::pair<Style, int>> stack_;
  };

  // ---- paint servers, clip paths, masks ----

  Paint resolve_paint(const DeclaredPaint& d, float opacity, const Style& style) {
    Paint paint;
    paint.opacity = opacity;
    using K = DeclaredPaint::Kind;
    auto simple = [&](K kind, Color color) {
      if (kind == K::Color) {
        paint.kind = Paint::Kind::Color;
        paint.color = color;
      } else if (kind == K::CurrentColor) {
        paint.kind = Paint::Kind::Color;
        paint.color = style.current_color;
      } else if ((kind == K::ContextFill || kind == K::ContextStroke) && context_fill_) {
        context_used_ = true;
        const Paint& context = kind == K::ContextFill ? *context_fill_ : *context_stroke_;
        paint = context;
        paint.opacity = opacity;  // the shape's own fill- or stroke-opacity
        // A server is placed in the context element's space once that element is built (place_context_paints).
        paint.from_context = !context.context &&
                             (context.kind == Paint::Kind::Gradient || context.kind == Paint::Kind::Pattern);
      } else {
        paint.kind = Paint::Kind::None;  // none, and context paints outside markers
      }
    };
    if (d.kind != K::Url) {
      simple(d.kind, d.color);
      return paint;
    }
    const pugi::xml_node target = by_id(d.url);
    const std::string_view kind = target ? local_name(target) : std::string_view{};
    if (d.fallback_kind) {  // kept for shapes the server cannot apply to (draw.cpp)
      const Paint server = paint;
      simple(*d.fallback_kind, d.color);
      const Paint fallback = std::exchange(paint, server);
      paint.fallback = fallback.kind == Paint::Kind::Color ? fallback.color : Color::transparent();
    }
    if (kind == "linearGradient" || kind == "radialGradient") {
      const std::shared_ptr<const Gradient> g = gradient(target);
      if (g && g->stops.size() >= 2) {
        paint.kind = Paint::Kind::Gradient;
        paint.gradient = g;
        return paint;
      }
      if (g && g->stops.size() == 1) {  // one stop: a solid colour
        paint.kind = Paint::Kind::Color;
        paint.color = g->stops[0].color;
        return paint;
      }
      // No stops: the server is not usable, so the fallback applies (else none).
    } else if (kind == "pattern") {
      if (std::shared_ptr<const Pattern> p = pattern(target)) {
        paint.kind = Paint::Kind::Pattern;
        paint.pattern = std::move(p);
        return paint;
      }
    } else if (!target) {
      if (!d.fallback_kind) warn("references", d.offset, "no paint server with id " + quoted(d.url) + ", painted as none");
    }
    // A missing or unusable paint server: the fallback, else none (SVG 2, 13.2: "as if none").
    if (d.fallback_kind) simple(*d.fallback_kind, d.color);
    return paint;
  }

  /// The href chain of a paint server, `node` first; stops at a loop (with a warning) or a non-server.
  std::vector<pugi::xml_node> href_chain(pugi::xml_node node) {
    std::vector<pugi::xml_node> chain{node};
    while (chain.size() < kMaxReferenceDepth) {
      const pugi::xml_node next = href_target(chain.back(), false);
      if (!next) break;
      if (std::find(chain.begin(), chain.end(), next) != chain.end()) {
        warn("references", element_offset(chain.back()), "href loop between paint servers, the chain stops here");
        break;
      }
      const std::string_view kind = local_name(next);
      if (kind != "linearGradient" && kind != "radialGradient" && kind != "pattern") break;
      chain.push_back(next);
    }
    return chain;
  }

  static pugi::xml_attribute chain_attribute(const std::vector<pugi::xml_node>& chain, const char* name) {
    for (const pugi::xml_node n : chain) {
      if (const pugi::xml_attribute a = n.attribute(name)) return a;
    }
    return {};
  }

  /// The element of an href chain an attribute comes from (its transform-origin goes with it).
  static pugi::xml_node chain_owner(const std::vector<pugi::xml_node>& chain, const char* name) {
    for (const pugi::xml_node n : chain) {
      if (n.attribute(name)) return n;
    }
    return {};
  }

  static Units units_of(pugi::xml_attribute a, Units fallback) {
    if (!a) return fallback;
    const std::string_view v = trim(a.value());
    if (v == "userSpaceOnUse") return Units::UserSpaceOnUse;
    if (v == "objectBoundingBox") return Units::ObjectBoundingBox;
    return fallback;
  }

  /// A coordinate of a paint server: for objectBoundingBox a number or a percentage (a fraction); for
  /// userSpaceOnUse a length (percentages of the viewport).
  std::optional<double> server_length(pugi::xml_attribute a, Units units, Axis axis) {
    if (!a) return std::nullopt;
    const std::string_view v = trim(a.value());
    double out = 0;
    if (units == Units::ObjectBoundingBox) {
      if (const std::optional<double> f = number_or_percent(v)) return f;
      if (parse_length(v, axis, out)) return out;
    } else if (parse_length(v, axis, out)) {
      return out;
    }
    warn("invalid values", value_offset(a), "invalid " + printable(a.name()) + " " + quoted(v) + ", ignored");
    return std::nullopt;
  }

  std::shared_ptr<const Gradient> gradient(pugi::xml_node node) {
    const auto cached = gradients_.find(node.internal_object());
    if (cached != gradients_.end()) return cached->second;
    const std::vector<pugi::xml_node> chain = href_chain(node);
    auto g = std::make_shared<Gradient>();
    g->id = node.attribute("id").value();
    g->kind = local_name(node) == "radialGradient" ? Gradient::Kind::Radial : Gradient::Kind::Linear;
    g->units = units_of(chain_attribute(chain, "gradientUnits"), Units::ObjectBoundingBox);
    if (const pugi::xml_attribute t = chain_attribute(chain, "gradientTransform")) {
      if (!parse_transform(t.value(), g->transform)) {
        warn("invalid values", value_offset(t), "invalid gradientTransform " + quoted(t.value()) + ", ignored");
        g->transform = Affine{};
      }
      g->transform = around_origin(chain_owner(chain, "gradientTransform"), g->transform);
    }
    if (const pugi::xml_attribute s = chain_attribute(chain, "spreadMethod")) {
      const std::string_view v = trim(s.value());
      g->spread = v == "reflect" ? Spread::Reflect : v == "repeat" ? Spread::Repeat : Spread::Pad;
    }
    // The geometry (x1.., cx..) comes only from gradients of the same kind; units, transform, spread and stops
    // from any gradient of the chain (SVG 2, 14.2: attributes a gradient of the other kind does not have).
    std::vector<pugi::xml_node> same_kind;
    for (const pugi::xml_node n : chain) {
      if (local_name(n) == local_name(node)) same_kind.push_back(n);
    }
    auto get = [&](const char* name, Axis axis, double fallback) {
      return server_length(chain_attribute(same_kind, name), g->units, axis).value_or(fallback);
    };
    const bool user = g->units == Units::UserSpaceOnUse;
    if (g->kind == Gradient::Kind::Linear) {
      g->x1 = get("x1", Axis::X, 0);
      g->y1 = get("y1", Axis::Y, 0);
      g->x2 = get("x2", Axis::X, user ? percent_width_ : 1);
      g->y2 = get("y2", Axis::Y, 0);
    } else {
      g->cx = get("cx", Axis::X, user ? percent_width_ / 2 : 0.5);
      g->cy = get("cy", Axis::Y, user ? percent_height_ / 2 : 0.5);
      const double half_diagonal = std::sqrt((percent_width_ * percent_width_ + percent_height_ * percent_height_) / 2) / 2;
      g->r = get("r", Axis::Other, user ? half_diagonal : 0.5);
      g->fx = get("fx", Axis::X, g->cx);
      g->fy = get("fy", Axis::Y, g->cy);
      g->fr = get("fr", Axis::Other, 0);
      if (g->r < 0) g->r = 0;
    }
    // Stops: those of the first element in the chain that has any.
    for (const pugi::xml_node n : chain) {
      bool any = false;
      std::optional<Style> gradient_style;  // what the stops inherit (their color for currentColor)
      for (const pugi::xml_node stop : n.children()) {
        if (stop.type() != pugi::node_element || local_name(stop) != "stop") continue;
        any = true;
        if (!gradient_style) gradient_style = style_from_ancestors(n);
        const Style s = computed(stop, *gradient_style);
        double offset = 0;
        if (const pugi::xml_attribute o = stop.attribute("offset")) {
          const std::optional<double> v = number_or_percent(o.value());
          if (!v) warn("invalid values", value_offset(o), "invalid stop offset " + quoted(o.value()) + ", using 0");
          offset = std::clamp(v.value_or(0.0), 0.0, 1.0);
        }
        if (!g->stops.empty()) offset = std::max(offset, g->stops.back().offset);
        g->stops.push_back(GradientStop{offset, s.stop_color.with_alpha(s.stop_opacity)});
      }
      if (any) break;
    }
    gradients_.emplace(node.internal_object(), g);
    return g;
  }

  std::shared_ptr<const Pattern> pattern(pugi::xml_node node) {
    const auto cached = patterns_.find(node.internal_object());
    if (cached != patterns_.end()) return cached->second;
    if (std::find(resolving_.begin(), resolving_.end(), node) != resolving_.end()) {
      warn("references", element_offset(node), "pattern refers to itself through its content, painted as none");
      return nullptr;
    }
    const std::vector<pugi::xml_node> chain = href_chain(node);
    auto p = std::make_shared<Pattern>();
    p->id = node.attribute("id").value();
    p->units = units_of(chain_attribute(chain, "patternUnits"), Units::ObjectBoundingBox);
    p->content_units = units_of(chain_attribute(chain, "patternContentUnits"), Units::UserSpaceOnUse);
    if (const pugi::xml_attribute t = chain_attribute(chain, "patternTransform")) {
      if (!parse_transform(t.value(), p->transform)) p->transform = Affine{};
      p->transform = around_origin(chain_owner(chain, "patternTransform"), p->transform);
    }
    auto get = [&](const char* name, Axis axis) {
      return server_length(chain_attribute(chain, name), p->units, axis).value_or(0);
    };
    const double x = get("x", Axis::X), y = get("y", Axis::Y);
    p->rect = Rect{x, y, x + get("width", Axis::X), y + get("height", Axis::Y)};
    if (const pugi::xml_attribute vb = chain_attribute(chain, "viewBox")) {
      if (const std::optional<ViewBox> v = parse_view_box(vb)) p->view_box = Rect{v->x, v->y, v->x + v->width, v->y + v->height};
    }
    resolving_.push_back(node);
    auto content = std::make_shared<Group>();
    for (const pugi::xml_node n : chain) {
      if (!n.first_child()) continue;
      const Style s = style_from_ancestors(n);
      const bool was_in_clip = std::exchange(in_clip_, false);
      children(n, s, content->children, 1);
      in_clip_ = was_in_clip;
      break;
    }
    resolving_.pop_back();
    p->content = std::move(content);
    patterns_.emplace(node.internal_object(), p);
    return p;
  }

  /// Whether `node` is being resolved already: the reference being followed would close a loop.
  bool in_loop(pugi::xml_node node) {
    return std::find(resolving_.begin(), resolving_.end(), node) != resolving_.end();
  }

  /// The clipPath `id` refers to; `at` is where the referring element starts (for the warning when there is none).
  std::shared_ptr<const ClipPath> clip_path(const std::string& id, std::size_t at) {
    const pugi::xml_node node = by_id(id);
    if (!node || local_name(node) != "clipPath") {
      warn("references", at, "clip-path: no clipPath with id " + quoted(id) + ", ignored");
      return nullptr;
    }
    const auto cached = clips_.find(node.internal_object());
    if (cached != clips_.end()) return cached->second;
    if (in_loop(node)) {
      // The reference that closes the loop is dropped; the rest of the loop applies (as resvg and browsers do).
      warn("references", element_offset(node), "clipPath " + quoted(id) + " refers to itself (a reference loop); "
                                                "the reference that closes the loop is ignored");
      return nullptr;
    }
    resolving_.push_back(node);
    auto clip = std::make_shared<ClipPath>();
    clip->id = id;
    clip->units = units_of(node.attribute("clipPathUnits"), Units::UserSpaceOnUse);
    const Style s = style_from_ancestors(node);
    clip->transform = own_transform(node, &s);
    auto content = std::make_shared<Group>();
    const bool was_in_clip = std::exchange(in_clip_, true);
    ++in_clip_path_;  // a clip path is the shapes' geometry: no markers, no images
    children(node, s, content->children, 1);
    --in_clip_path_;
    in_clip_ = was_in_clip;
    clip->content = std::move(content);
    if (!s.clip_path.empty()) clip->clip = clip_path(s.clip_path, element_offset(node));
    resolving_.pop_back();
    clips_.emplace(node.internal_object(), clip);
    return clip;
  }

  /// The mask `id` refers to; `at` is where the referring element starts (for the warning when there is none).
  std::shared_ptr<const Mask> mask(const std::string& id, std::size_t at) {
    const pugi::xml_node node = by_id(id);
    if (!node || local_name(node) != "mask") {
      warn("references", at, "mask: no mask with id " + quoted(id) + ", ignored");
      return nullptr;
    }
    const auto cached = masks_.find(node.internal_object());
    if (cached != masks_.end()) return cached->second;
    if (in_loop(node)) {
      warn("references", element_offset(node), "mask " + quoted(id) + " refers to itself (a reference loop); "
                                                "the reference that closes the loop is ignored");
      return nullptr;
    }
    resolving_.push_back(node);
    auto m = std::make_shared<Mask>();
    m->id = id;
    m->units = units_of(node.attribute("maskUnits"), Units::ObjectBoundingBox);
    m->content_units = units_of(node.attribute("maskContentUnits"), Units::UserSpaceOnUse);
    const Style s = style_from_ancestors(node);
    const FontSizeScope font_size(*this, s.text.font_size);
    auto get = [&](const char* name, Axis axis, double fallback) {
      return server_length(node.attribute(name), m->units, axis).value_or(fallback);
    };
    const bool bbox = m->units == Units::ObjectBoundingBox;
    const double x = get("x", Axis::X, bbox ? -0.1 : -0.1 * percent_width_);
    const double y = get("y", Axis::Y, bbox ? -0.1 : -0.1 * percent_height_);
    m->rect = Rect{x, y, x + get("width", Axis::X, bbox ? 1.2 : 1.2 * percent_width_),
                   y + get("height", Axis::Y, bbox ? 1.2 : 1.2 * percent_height_)};
    m->luminance = s.mask_luminance;
    auto content = std::make_shared<Group>();
    const bool was_in_clip = std::exchange(in_clip_, false);
    children(node, s, content->children, 1);
    in_clip_ = was_in_clip;
    m->content = std::move(content);
    if (!s.mask.empty()) m->mask = mask(s.mask, element_offset(node));
    resolving_.pop_back();
    masks_.emplace(node.internal_object(), m);
    return m;
  }

  std::string_view text_;
  const std::string& file_;
  LineIndex lines_;
  const ParseOptions& options_;
  int image_depth_ = 0;
  std::int64_t& pixels_left_;
  std::unordered_map<std::string, LoadedImage> images_;
  std::unordered_map<const void*, MarkerDef> markers_;
  int in_marker_ = 0;  // > 0 while a marker's content is built
  std::vector<pugi::xml_node> marker_stack_;  // the markers whose content is being built, outermost first
  int in_clip_path_ = 0;  // > 0 while a clipPath's content is built
  // While a marker's content is built: the paints of the shape it marks (context-fill, context-stroke).
  const Paint* context_fill_ = nullptr;
  const Paint* context_stroke_ = nullptr;
  bool context_used_ = false;
  std::shared_ptr<text::FontDb> fonts_;  // options_.fonts, or the embedded font alone
  std::size_t text_characters_ = 0;      // laid out so far (detail::kMaxTextCharacters)
  std::string expanded_text_;  // the text with DOCTYPE entities expanded, when it has any (text_ points here)
  std::string buffer_;  // the private copy pugixml parses in place
  pugi::xml_document xml_;
  Tree tree_;
  std::optional<ViewBox> root_view_box_;
  Affine root_viewport_;
  double percent_width_ = 0, percent_height_ = 0;  // what percentages of lengths refer to
  double font_size_ = 16;  // what em and ex refer to: the font size of the element whose lengths are read
  std::size_t element_count_ = 0, use_instances_ = 0;
  std::unordered_map<std::string_view, pugi::xml_node> ids_;
  std::vector<std::string> svg_prefixes_;
  bool scoped_namespaces_ = false;  // an element other than the root declares a namespace (in_svg_namespace)
  mutable std::unordered_map<const void*, bool> svg_namespace_cache_;
  css::StyleSheet sheet_;
  std::vector<pugi::xml_node> path_;       // scratch: the ancestors of the element being styled
  std::vector<pugi::xml_node> use_stack_;  // use targets being instanced
  std::vector<pugi::xml_node> resolving_;  // patterns, clip paths and masks being resolved
  std::unordered_map<const void*, std::shared_ptr<const Gradient>> gradients_;
  std::unordered_map<const void*, std::shared_ptr<const Pattern>> patterns_;
  std::unordered_map<const void*, std::shared_ptr<const ClipPath>> clips_;
  std::unordered_map<const void*, std::shared_ptr<const Mask>> masks_;
  bool warned_filter_ = false;
  bool in_clip_ = false;  // building a clipPath's content: geometry only (reset inside masks and patterns)
  struct WarningCount {
    std::string_view kind;  // always a string literal
    std::size_t count;
    std::size_t first_dropped;
  };
  std::vector<WarningCount> warning_counts_;
};

/// Turns the tree into draw items for the core Renderer: transforms composed, group opacity multiplied into
/// each child's alpha (an approximation where children overlap), paints it cannot draw yet left out with one
/// warning each (gradients, patterns, clip paths, masks, blend modes wait for the canvas).
class Flattener {
 public:
  explicit Flattener(Document& doc) : doc_(doc) {}

  void group(const Group& g, const Affine& parent, float opacity) {
    const Affine ctm = parent * g.transform;
    if ((g.clip && !g.clip->content) || (g.mask && !g.mask->content)) return;  // clipped or masked away entirely
    if (g.clip && !is_viewport_clip(*g.clip)) note("clip paths are not applied yet (drawn unclipped)");
    if (g.mask) note("masks are not applied yet (drawn unmasked)");
    if (g.blend_mode != "normal") note("mix-blend-mode is not applied yet (drawn as normal)");
    if (g.opacity < 1 && !single_paint(g)) {
      note("group opacity is approximated: it is multiplied into each child's alpha (overlaps differ)");
    }
    for (const Node& child : g.children) {
      if (const Group* sub = std::get_if<Group>(&child.value)) {
        group(*sub, ctm, opacity * g.opacity);
      } else if (const PathNode* path = std::get_if<PathNode>(&child.value)) {
        this->path(*path, ctm, opacity * g.opacity);
      }
    }
  }

  void finish() {
    for (const std::string& n : notes_) doc_.warnings.push_back("0:0: " + n);
  }

 private:
  /// A nested viewport's clip is a rectangle; drawing without it is only wrong where content overflows.
  static bool is_viewport_clip(const ClipPath& clip) {
    return clip.id.empty() && clip.content && clip.content->children.size() == 1 && !clip.clip;
  }

  /// Whether a group draws exactly one fill or one stroke (then multiplying its opacity in is exact).
  static bool single_paint(const Group& g) {
    if (g.children.size() != 1) return false;
    if (const Group* sub = std::get_if<Group>(&g.children[0].value)) return single_paint(*sub);
    const PathNode* p = std::get_if<PathNode>(&g.children[0].value);
    return p && !(p->fill && p->stroke);
  }

  void note(const std::string& message) {
    if (std::find(notes_.begin(), notes_.end(), message) == notes_.end()) notes_.push_back(message);
  }

  std::optional<Color> color_of(const Paint& paint, float opacity) {
    if (paint.kind == Paint::Kind::Gradient) {
      note("gradients are not drawn yet (the shape's paint is left out)");
      return std::nullopt;
    }
    if (paint.kind == Paint::Kind::Pattern) {
      note("patterns are not drawn yet (the shape's paint is left out)");
      return std::nullopt;
    }
    if (paint.kind != Paint::Kind::Color) return std::nullopt;
    Color c = paint.color;
    c.a *= paint.opacity * opacity;
    if (!(c.a > 0)) return std::nullopt;
    return c;
  }

  void path(const PathNode& p, const Affine& ctm, float opacity) {
    std::optional<Color> fill, stroke;
    if (p.fill) fill = color_of(p.fill->paint, opacity);
    if (p.stroke) stroke = color_of(p.stroke->paint, opacity);
    auto emit_fill = [&] {
      if (!fill) return;
      DrawItem item;
      item.kind = DrawItem::Kind::Fill;
      item.path = p.path;
      item.transform = ctm;
      item.color = *fill;
      item.rule = p.fill->rule;
      item.line = p.line;
      item.column = p.column;
      doc_.items.push_back(std::move(item));
    };
    auto emit_stroke = [&] {
      if (!stroke) return;
      DrawItem item;
      item.kind = DrawItem::Kind::Stroke;
      item.path = p.path;
      item.transform = ctm;
      item.color = *stroke;
      item.stroke = p.stroke->style;
      item.line = p.line;
      item.column = p.column;
      doc_.items.push_back(std::move(item));
    };
    if (p.stroke_first) {
      emit_stroke();
      emit_fill();
    } else {
      emit_fill();
      emit_stroke();
    }
  }

  Document& doc_;
  std::vector<std::string> notes_;
};

}  // namespace

Tree parse_svg_tree(std::string_view text, const std::string& file, const ParseOptions& options) {
  std::int64_t pixels_left = kMaxDocumentImagePixels;
  return Builder(text, file, options, 0, pixels_left).run();
}

Document to_document(const Tree& tree) {
  Document doc;
  doc.file = tree.file;
  doc.intrinsic_width = tree.width;
  doc.intrinsic_height = tree.height;
  // Fractional sizes round up so the drawing is not cut off.
  doc.width = static_cast<int>(std::ceil(tree.width - 1e-9));
  doc.height = static_cast<int>(std::ceil(tree.height - 1e-9));
  doc.warnings = tree.warnings;
  Flattener flattener(doc);
  flattener.group(tree.root, Affine{}, 1);
  flattener.finish();
  return doc;
}

Document parse_svg(std::string_view text, const std::string& file) { return parse_svg(text, file, ParseOptions{}); }

Document parse_svg(std::string_view text, const std::string& file, const ParseOptions& options) {
  return to_document(parse_svg_tree(text, file, options));
}

Document load_svg(const std::string& path) { return load_svg(path, ParseOptions{}); }

Document load_svg(const std::string& path, ParseOptions options) {
  const std::vector<std::uint8_t> bytes = read_file_limited(path, kMaxSvgFileBytes, "SVG file");
  if (options.base_dir.empty()) options.base_dir = detail::folder_of(path);
  return parse_svg(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path, options);
}

}  // namespace vraster::svg
