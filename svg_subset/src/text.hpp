// Private: SVG text -> paths in the resolved tree. document.cpp computes styles (the cascade) and hands each text
// element to build_text() through the TextHost interface; everything about text lives in text.cpp.
#pragma once

#include <pugixml.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "svg_subset/tree.hpp"

namespace vraster::text {
class FontDb;
}

namespace vraster::svg::detail {

enum class TextAnchor : std::uint8_t { Start, Middle, End };
enum class Baseline : std::uint8_t {
  Auto, Alphabetic, Middle, Central, Hanging, Mathematical, TextBeforeEdge, TextAfterEdge, Ideographic
};

/// The text properties of a computed style (part of document.cpp's Style).
struct TextProperties {
  // Inherited.
  std::vector<std::string> font_family;  ///< empty: the default family
  double font_size = 16;                 ///< px
  int font_weight = 400;
  std::uint8_t font_style = 0;           ///< text::FontSlant
  double font_stretch = 100;             ///< percent
  bool small_caps = false;
  bool kerning = true;
  std::string feature_settings;          ///< HarfBuzz syntax, from font-feature-settings
  std::vector<std::pair<std::uint32_t, double>> variation_settings;  ///< font-variation-settings (tag, value)
  double letter_spacing = 0, word_spacing = 0;  ///< px, or percent when the flag below is set
  bool letter_spacing_percent = false, word_spacing_percent = false;  ///< of the viewport (like SVG lengths)
  TextAnchor anchor = TextAnchor::Start;
  bool rtl = false;                      ///< direction
  bool vertical = false;                 ///< writing-mode tb / vertical-*
  bool speed = false;                    ///< text-rendering: optimizeSpeed (glyphs drawn aliased)
  Baseline dominant_baseline = Baseline::Auto;
  std::uint8_t ancestor_decoration = 0;  ///< text-decoration of the ancestors (drawn as if set on <text>)
  // Not inherited.
  Baseline alignment_baseline = Baseline::Auto;
  enum class Shift : std::uint8_t { None, Sub, Super, Length };
  Shift shift = Shift::None;
  double shift_length = 0;               ///< px, up positive (baseline-shift lengths and percentages)
  std::uint8_t decoration = 0;           ///< kUnderline | kOverline | kLineThrough set on this element

  static constexpr std::uint8_t kUnderline = 1, kOverline = 2, kLineThrough = 4;

  /// Resets the properties that are not inherited (a child's starting point).
  void reset_non_inherited() {
    ancestor_decoration |= decoration;
    alignment_baseline = Baseline::Auto;
    shift = Shift::None;
    shift_length = 0;
    decoration = 0;
  }
};

/// Characters of text one document may lay out (all its text elements together): each becomes a glyph outline
/// in the tree, about a kilobyte with its share of the drawing, so this bounds memory and time.
inline constexpr std::size_t kMaxTextCharacters = std::size_t{1} << 18;

/// Whether `name` is a text property (or the `font` shorthand) handled by apply_text_property.
bool is_text_property(std::string_view name);
/// Whether `name` is a text property that may also be given as a presentation attribute.
bool is_text_attribute(std::string_view name);
/// Applies one declaration; false when the value is invalid (the caller warns). `parent` is for relative values,
/// `dpi` for physical units (ParseOptions::dpi).
bool apply_text_property(std::string_view name, std::string_view value, TextProperties& s,
                         const TextProperties& parent, double dpi);
/// `inherit` for a text property.
void inherit_text_property(std::string_view name, TextProperties& s, const TextProperties& parent);

/// What text.cpp needs of an element's computed style.
struct SpanStyle {
  TextProperties text;
  std::optional<Fill> fill;
  std::optional<Stroke> stroke;
  bool stroke_first = false;
  bool crisp_edges = false;
};

/// The services of document.cpp that text needs.
class TextHost {
 public:
  virtual ~TextHost() = default;
  /// Computes the style of `node` (a child of the element last entered), counts it against the element limits
  /// and makes it the current element; nothing (and nothing entered) when it is not displayed.
  virtual std::optional<SpanStyle> enter(pugi::xml_node node) = 0;
  virtual void leave() = 0;
  virtual void warn(pugi::xml_node node, const std::string& message) = 0;
  /// The element an href / xlink:href refers to (null when missing, with a warning).
  virtual pugi::xml_node href_target(pugi::xml_node node) = 0;
  /// The geometry of a shape element in the user space of the element that refers to it (its transform
  /// applied); empty when it is not a shape.
  virtual Path shape_of(pugi::xml_node node) = 0;
  /// Parses a length (percentages against the viewport on `axis`: 0 x, 1 y, 2 other); false when invalid.
  virtual bool length(std::string_view value, int axis, double& out) = 0;
  virtual std::pair<int, int> position(pugi::xml_node node) = 0;  ///< line and column
  /// Counts one character against the document's text budget (kMaxTextCharacters); false once it is spent.
  virtual bool take_character() = 0;
};

/// A font database holding only the embedded default font (for documents read without ParseOptions::fonts).
std::shared_ptr<text::FontDb> default_font_db();

/// Lays out a <text> element (style `style`) and appends its paths to `out` (the element's own group). Fonts come
/// from `fonts` only.
void build_text(pugi::xml_node text, const SpanStyle& style, TextHost& host, text::FontDb* fonts, Group& out);

}  // namespace vraster::svg::detail
