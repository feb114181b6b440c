// vraster_text: fonts loaded through FreeType (TrueType, OpenType CFF, collections), their glyph outlines as
// vraster::Path, and the list of fonts tried in turn for characters the first one lacks.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/path.hpp"

namespace vraster::text {

/// Largest accepted font size in pixels (per em). Bigger sizes, zero, negative or non-finite sizes throw
/// vraster::Error: a glyph at 4096 px is already larger than most images; nothing sensible lies beyond.
inline constexpr double kMaxFontSize = 4096.0;

/// Throws vraster::Error naming the problem unless 0 < size <= kMaxFontSize.
void check_font_size(double size);

/// FreeType hinting of glyph outlines. Unhinted outlines are the font's own curves scaled in doubles.
enum class Hinting : std::uint8_t {
  None,   ///< FT_LOAD_NO_HINTING: exact scaled outlines (default)
  Light,  ///< FreeType's light auto-hinting (FT_LOAD_TARGET_LIGHT): vertical snapping only, same advances
};

/// Vertical metrics of a font at one size, in pixels. y grows downwards, so the ascender is negative.
struct FontMetrics {
  double ascender = 0;    ///< baseline to the top of the em box (negative: above the baseline)
  double descender = 0;   ///< baseline to the bottom (positive: below)
  double line_gap = 0;    ///< extra space between lines
  double line_height() const { return descender - ascender + line_gap; }
};

/// Positions for text decorations and baselines at one size, in pixels, y down (negative: above the baseline).
/// Each comes from the font's tables when it has them (post: underline; OS/2: strikeout, sub- and superscript,
/// x-height, cap height), otherwise from a usual proportion of the em. The tables' positions are taken as the
/// lines' centres, as browsers draw them.
struct DecorationMetrics {
  double underline_position = 0;   ///< centre of the underline (positive: below the baseline)
  double underline_thickness = 0;
  double strikeout_position = 0;   ///< centre of the line-through (negative)
  double strikeout_thickness = 0;
  double subscript_offset = 0;     ///< how far a subscript's baseline drops (positive: down)
  double superscript_offset = 0;   ///< how far a superscript's baseline rises (negative: up)
  double x_height = 0;             ///< top of a lowercase x (negative)
  double cap_height = 0;           ///< top of a capital (negative)
};

/// One axis value of a variable font ("wght" 700).
struct FontVariation {
  std::uint32_t tag = 0;  ///< four ASCII characters, big-endian ('w' << 24 | 'g' << 16 | 'h' << 8 | 't')
  double value = 0;
  static std::uint32_t make_tag(std::string_view four) {
    std::uint32_t t = 0;
    for (std::size_t i = 0; i < 4; ++i) t = t << 8 | static_cast<unsigned char>(i < four.size() ? four[i] : ' ');
    return t;
  }
};

/// A glyph's unhinted outline in font units (see Font::outline_units) and the box of all its points, control
/// points included (its Path::control_bounds(), computed once).
struct GlyphOutline {
  Path path;
  Rect control_box;
};

/// A colour bitmap glyph (a CBDT/CBLC or sbix strike image, as FreeType's FT_LOAD_COLOR gives it). Drawn as an
/// image: `size / ppem` user units per image pixel at font size `size`, its top-left corner at (left, top)
/// image pixels from the pen position (y down).
struct ColorBitmap {
  std::shared_ptr<const Image> image;  ///< premultiplied RGBA8
  double ppem = 0;                     ///< pixels per em of the strike it comes from
  double left = 0, top = 0;            ///< the image's top-left corner relative to the pen position, in its pixels
};

/// One font face. Loading reads the whole file into memory (FreeType and HarfBuzz share those bytes).
///
/// A Font keeps a FreeType face and caches; it is not safe to use one Font from two threads at once. Load one per
/// thread (the bytes of the embedded default font are shared, not copied).
class Font {
 public:
  /// Loads face `face_index` of a font file (.ttf, .otf, .ttc/.otc collections). Throws vraster::Error naming the
  /// file when it is missing, unreadable, not a font, or has no face with that index.
  static std::shared_ptr<Font> load_file(const std::string& path, int face_index = 0);
  /// Loads a font from bytes in memory (copied). `name` is used in error messages.
  static std::shared_ptr<Font> load_memory(std::vector<std::uint8_t> bytes, int face_index = 0,
                                           const std::string& name = "<memory>");
  /// The default font compiled into the library: Noto Sans Regular (SIL Open Font License 1.1, text/fonts/).
  static std::shared_ptr<Font> load_default();
  /// The bytes of the embedded default font (no copy).
  static std::span<const std::uint8_t> default_font_data();

  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  /// A number unique to this Font object within the process (cache keys use it).
  std::uint64_t id() const;
  /// The file name (or the name given for memory fonts).
  const std::string& name() const;
  /// The family and style names the font declares.
  std::string family_name() const;
  std::string style_name() const;
  int units_per_em() const;
  int glyph_count() const;
  int face_count() const;  ///< faces in the file (collections hold more than one)
  bool has_outlines() const;

  /// Whether the font has colour bitmap strikes (CBDT/CBLC or sbix: FT_HAS_COLOR with fixed sizes).
  bool has_color_bitmaps() const;
  /// The colour bitmap of a glyph from the font's largest strike (the best quality when the image is scaled to a
  /// font size; COLR fonts have none, their outlines are drawn), cached per glyph; null when the glyph has none
  /// or its image cannot be decoded. Images above 4096 pixels a side are refused (null).
  const ColorBitmap* color_bitmap(std::uint32_t glyph) const;

  /// The glyph for a Unicode code point, 0 (.notdef) when the font has none.
  std::uint32_t glyph_index(char32_t codepoint) const;
  bool has_glyph(char32_t codepoint) const { return glyph_index(codepoint) != 0; }
  /// Whether the font has variation axes (an OpenType variable font).
  bool is_variable() const;
  /// Sets a variable font's design coordinates: the axes named take those values (clamped to the axis's range),
  /// the others their defaults; axes the font lacks are ignored. Outlines, advances and shaping follow. Clears the
  /// font's outline cache and gives it a new id(). Returns false (and changes nothing) for a font without axes.
  bool set_variations(std::span<const FontVariation> values);
  /// Whether the font's GSUB table has a feature with this tag ("smcp", "liga", ...).
  bool has_substitution_feature(std::string_view tag) const;

  FontMetrics metrics(double size) const;
  DecorationMetrics decoration_metrics(double size) const;
  /// Horizontal advance of a glyph at `size` pixels (unhinted).
  double advance(std::uint32_t glyph, double size) const;

  /// The unhinted outline of a glyph in font units, y pointing down (the font's y negated), origin at the pen
  /// position on the baseline. Cached per glyph. Glyphs without outlines (spaces, bitmap-only glyphs) are empty.
  const Path& outline_units(std::uint32_t glyph) const { return glyph_outline(glyph).path; }
  /// outline_units() with its control box, both cached per glyph (renderers size glyph masks from the box).
  const GlyphOutline& glyph_outline(std::uint32_t glyph) const;
  /// The outline at `size` pixels per em, y down, origin at the pen position. Hinting::None scales outline_units(); Hinting::Light loads FreeType's light-hinted outline at
  /// that size (26.6 fixed point). Throws vraster::Error for a bad size.
  Path outline(std::uint32_t glyph, double size, Hinting hinting = Hinting::None) const;

  /// Internals shared with the shaper and the renderer (FreeType and HarfBuzz objects).
  struct Impl;
  Impl& impl() const { return *impl_; }

 private:
  explicit Font(std::unique_ptr<Impl> impl);
  static std::shared_ptr<Font> open(std::unique_ptr<Impl> impl, int face_index);
  std::unique_ptr<Impl> impl_;
};

/// The fonts tried in order for each character: the first one that has a glyph for it is used (marks and
/// joiners stay with the font of the character before them). Characters no font has get the first font's .notdef.
struct FontList {
  std::vector<std::shared_ptr<Font>> fonts;

  FontList() = default;
  explicit FontList(std::shared_ptr<Font> primary) { fonts.push_back(std::move(primary)); }
  FontList& add(std::shared_ptr<Font> fallback) {
    fonts.push_back(std::move(fallback));
    return *this;
  }
  /// The embedded default font alone.
  static FontList default_list() { return FontList(Font::load_default()); }
  bool empty() const { return fonts.empty(); }
};

}  // namespace vraster::text
