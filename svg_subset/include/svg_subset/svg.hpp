// svg_subset: reads a subset of SVG into a resolved list of draw items, and renders it with vraster.
//
// Data flow: XML text (pugixml) -> the resolved tree (tree.hpp: CSS cascade, inheritance, units, references)
// -> Document (flat draw items in paint order, what the core Renderer can draw) -> render().
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vraster/error.hpp"
#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/renderer.hpp"
#include "vraster/path.hpp"
#include "vraster/raster.hpp"
#include "vraster/stroke.hpp"

namespace vraster::text {
class FontDb;  // vraster_text/font_db.hpp
}

namespace vraster::svg {

/// A problem in an SVG file or in path data, with its 1-based position in the text (line 0 when unknown).
/// what() reads "FILE:LINE:COLUMN: message".
class ParseError : public Error {
 public:
  ParseError(const std::string& file, int line, int column, const std::string& message);
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  int line_, column_;
  std::string message_;
};

/// A problem in path data at a byte offset of the `d` string.
class PathDataError : public Error {
 public:
  PathDataError(std::size_t offset, const std::string& message);
  std::size_t offset() const { return offset_; }
  const std::string& message() const { return message_; }

 private:
  std::size_t offset_;
  std::string message_;
};

/// Parses SVG path data (the whole SVG 1.1 grammar: M m L l H h V v C c S s Q q T t A a Z z, implicit repetition,
/// compact numbers and arc flags such as "a1 1 0 00.5.5" or "1e-3-2") and appends it to `out`.
/// Throws PathDataError naming the first error; SVG says to render up to the error, so `out` keeps the
/// segments before it.
void parse_path_data(std::string_view d, Path& out);

/// Parses a colour: #rgb, #rgba, #rrggbb, #rrggbbaa, rgb(), rgba(), hsl(), hsla(), the CSS named colours,
/// transparent. Returns nothing for "none" (is_none set) or garbage; currentColor is the caller's business.
std::optional<Color> parse_color(std::string_view text, bool& is_none);

/// Parses an SVG transform list ("translate(1 2) rotate(30)"); returns false on a syntax error.
bool parse_transform(std::string_view text, Affine& out);

/// Parses a CSS `transform` value (CSS Transforms 1: `none` or functions separated by spaces, arguments by
/// commas; lengths in px or absolute units, angles in deg, rad, grad or turn, a bare number only for 0);
/// returns false when it is invalid. Percentages (of a reference box) are not supported and make it invalid.
bool parse_css_transform(std::string_view text, Affine& out);

/// One fill or stroke of a shape, fully resolved: user-space path, its transform to device pixels and paint.
/// A shape with both gives two items, fill first (SVG's default paint-order).
struct DrawItem {
  enum class Kind : std::uint8_t { Fill, Stroke };
  Kind kind = Kind::Fill;
  Path path;
  Affine transform;  ///< user space -> device pixels (viewBox and every ancestor transform composed)
  Color color;       ///< opacity and fill-opacity / stroke-opacity already folded into color.a
  FillRule rule = FillRule::NonZero;  ///< fills only
  StrokeStyle stroke;                 ///< strokes only (user-space lengths; width > 0)
  int line = 0, column = 0;           ///< where the element starts in the file (for messages at render time)
  bool is_fill() const { return kind == Kind::Fill; }
  bool is_stroke() const { return kind == Kind::Stroke; }
};

/// A parsed document: its pixel size and the items in paint order.
struct Document {
  int width = 0;   ///< pixels: the intrinsic width rounded up
  int height = 0;  ///< pixels: the intrinsic height rounded up
  double intrinsic_width = 0;   ///< the root's size in CSS px, before rounding
  double intrinsic_height = 0;
  std::vector<DrawItem> items;
  /// "LINE:COLUMN: message" for things ignored; at most 20 of a kind, then one line "... and K more".
  std::vector<std::string> warnings;
  std::string file;  ///< the name given to parse_svg, for messages at render time
};

/// The output size for a requested width and/or height (0 = not given) and zoom (0 = not given), as resvg and
/// rsvg-convert size their output: one side given keeps the aspect ratio of the intrinsic size rounded to whole
/// pixels (at least 1), the other side rounded up; neither given is the document's own size. A zoom scales the
/// intrinsic size (rounded up); a width or height given with it is a maximum, as in rsvg-convert: when the zoomed
/// size exceeds one, the size is what the width and/or height alone give. Throws vraster::Error when the size
/// is out of range.
std::pair<int, int> output_size(const Document& doc, int width, int height, double zoom = 0);

/// Scales the drawing to `width` x `height` pixels (each axis on its own, from the intrinsic size).
void scale_to(Document& doc, int width, int height);

struct Tree;

/// Where <image> may read files from. Relative hrefs resolve against `base_dir` and must stay inside
/// `allowed_dir` (empty: base_dir itself) once `..` and symbolic links are resolved; absolute paths and URLs
/// with a scheme other than data: are never read. An empty base_dir reads no file at all (data: URLs only).
/// The fonts text may use come from `fonts`: a document reads no font file from anywhere else.
struct ParseOptions {
  std::string base_dir;     ///< the document's folder (load_svg fills it in when empty)
  std::string allowed_dir;  ///< a wider folder files may come from (e.g. a test suite's root); empty: base_dir
  /// The fonts text may use. Null: the embedded default font (Noto Sans) alone.
  std::shared_ptr<text::FontDb> fonts;
  double default_font_size = 16;  ///< the root's font-size in px (CSS "medium")
  /// Pixels per inch for the physical units (in, cm, mm, pt, pc): 1in is `dpi` px. CSS (and the default): 96.
  double dpi = 96;
};

/// Flattens a resolved tree (tree.hpp) into draw items for the core Renderer: what it cannot draw yet
/// (gradients, patterns, clip paths, masks, blend modes) is left out with a warning.
Document to_document(const Tree& tree);

/// Parses SVG text: parse_svg_tree() then to_document(). `file` is used only in messages. Throws ParseError only
/// for a document that cannot be used at all (malformed XML, no <svg> root, a size that cannot be resolved or
/// is out of range, a limit exceeded); invalid values are ignored with a warning, as browsers do.
Document parse_svg(std::string_view text, const std::string& file = "<memory>");
Document parse_svg(std::string_view text, const std::string& file, const ParseOptions& options);
/// Reads and parses a file (throws vraster::Error when it cannot be read). Images may come from the file's
/// folder (options.base_dir defaults to it).
Document load_svg(const std::string& path);
Document load_svg(const std::string& path, ParseOptions options);

/// Render settings shared by every item (a rule given here overrides the file's fill-rule).
struct RenderSettings {
  AntiAlias aa = AntiAlias::Analytic;
  double tolerance = kDefaultTolerance;
  std::optional<FillRule> rule_override;
  /// When set, every stroke is drawn as a 1-device-pixel hairline with this algorithm (dashes kept; width, caps
  /// and joins ignored) instead of a geometric stroke.
  std::optional<HairlineMode> hairline;
};

/// Draws every item of `doc` onto `image` (which should be doc.width x doc.height) in order, and flushes `renderer`
/// (with threads its fills are queued): `image` is complete on return. A core limit reached by one item
/// (vraster::Error) is rethrown as a ParseError at that item's element.
template <class T>
void render(const Document& doc, BasicImage<T>& image, const RenderSettings& settings, Renderer& renderer);

}  // namespace vraster::svg
