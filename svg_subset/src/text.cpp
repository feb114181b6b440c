// SVG text -> glyph outlines as paths in the resolved tree.
//
//   1. collect:   walk <text> and its tspan / textPath / tref / a children: characters after white-space handling
//                 (SVG 1.1 xml:space), each with the element it belongs to; x y dx dy rotate lists per character
//   2. chunks:    a new text chunk at every absolute x or y and at every textPath
//   3. shape:     each chunk split into runs of one font style, shaped by HarfBuzz (fallback fonts, bidi)
//   4. position:  pen positions with dx / dy, letter- and word-spacing, baseline shifts; text-anchor per chunk;
//                 along the path for textPath
//   5. emit:      one PathNode per run of glyphs of one element (its fill and stroke), decorations as rectangles
//                 (underline and overline below the glyphs, line-through above), paint_box = the text's box
#include <algorithm>
#include <array>
#include <cmath>
#include <cwctype>
#include <map>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>

#include "scan.hpp"
#include "text.hpp"
#include "vraster/error.hpp"
#include "vraster_text/font_db.hpp"
#include "vraster_text/layout.hpp"

namespace vraster::svg::detail {
namespace {

constexpr std::size_t kMaxChars = kMaxTextCharacters;  // per text element (and list values per attribute)
constexpr double kMaxShapeSize = text::kMaxFontSize;
constexpr double kVerticalReach = 1e7;  // half the length of the line a vertical chunk is laid out on
constexpr double kShapeSize = 1000;  // px per em runs are shaped at (positions are then scaled per glyph)

struct Element {
  SpanStyle style;
  int parent = -1;
  std::uint32_t begin = 0, end = 0;  // characters [begin, end)
  int path = -1;                     // index into paths when this is (or is inside) a textPath
  bool dropped = false;              // inside a textPath without a path: not drawn, takes no space
  std::optional<double> text_length;  // textLength
  bool stretch_glyphs = false;        // lengthAdjust="spacingAndGlyphs"
};

struct Char {
  char32_t c = 0;
  int element = 0;
  std::optional<double> x, y, rotate;
  double dx = 0, dy = 0;
};

struct Lists {
  int element = 0;
  std::vector<double> x, y, dx, dy, rotate;
};

/// A textPath's geometry: its segments as cubics (lines and quadratics raised exactly), measured by Gauss-Legendre
/// quadrature, so positions and tangents along it are those of the curve itself (a polyline's chords would turn
/// glyphs by up to half a chord's bend). Moves start a new piece without counting their jump; closes are lines.
struct TextPath {
  static constexpr int kSteps = 16;  // quadrature intervals per segment (lengths tabulated at their ends)
  struct Segment {
    Point p[4];
    double start = 0;                     // distance from the path's start
    std::array<double, kSteps + 1> table;  // table[i]: length from t = 0 to t = i / kSteps
    double length() const { return table[kSteps]; }
  };
  std::vector<Segment> segments;
  double start_offset = 0;
  bool closed_loop = false;  // one subpath, closed: text wraps around it

  double total() const { return segments.empty() ? 0 : segments.back().start + segments.back().length(); }
  Point end_point() const { return segments.empty() ? Point{} : segments.back().p[3]; }

  static Point eval(const Segment& s, double t) {
    const double u = 1 - t;
    return s.p[0] * (u * u * u) + s.p[1] * (3 * u * u * t) + s.p[2] * (3 * u * t * t) + s.p[3] * (t * t * t);
  }
  static Point derivative(const Segment& s, double t) {
    const double u = 1 - t;
    return (s.p[1] - s.p[0]) * (3 * u * u) + (s.p[2] - s.p[1]) * (6 * u * t) + (s.p[3] - s.p[2]) * (3 * t * t);
  }
  static double speed(const Segment& s, double t) {
    const Point d = derivative(s, t);
    return std::hypot(d.x, d.y);
  }
  /// Length of the segment between parameters a and b (8-point Gauss-Legendre).
  static double length_between(const Segment& s, double a, double b) {
    static constexpr double kX[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr double kW[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const double mid = (a + b) / 2, half = (b - a) / 2;
    double sum = 0;
    for (int i = 0; i < 4; ++i) sum += kW[i] * (speed(s, mid - half * kX[i]) + speed(s, mid + half * kX[i]));
    return sum * half;
  }

  /// Appends a cubic segment (zero-length ones are left out: they have no direction).
  void add(Point p0, Point p1, Point p2, Point p3) {
    Segment s{{p0, p1, p2, p3}, total(), {}};
    s.table[0] = 0;
    for (int i = 0; i < kSteps; ++i)
      s.table[i + 1] = s.table[i] + length_between(s, double(i) / kSteps, double(i + 1) / kSteps);
    if (s.length() > 0) segments.push_back(s);
  }
  void add_line(Point a, Point b) { add(a, a + (b - a) * (1.0 / 3), a + (b - a) * (2.0 / 3), b); }

  /// The same path run backwards (side="right").
  void reverse() {
    std::vector<Segment> old = std::move(segments);
    segments.clear();
    for (auto it = old.rbegin(); it != old.rend(); ++it) add(it->p[3], it->p[2], it->p[1], it->p[0]);
  }

  /// Point and tangent angle (radians) at distance d (0 <= d <= total()).
  std::pair<Point, double> at(double d) const {
    auto it = std::upper_bound(segments.begin(), segments.end(), d,
                               [](double v, const Segment& s) { return v < s.start; });
    const Segment& s = it == segments.begin() ? segments.front() : *std::prev(it);
    const double target = std::clamp(d - s.start, 0.0, s.length());
    const int i = static_cast<int>(std::upper_bound(s.table.begin(), s.table.end() - 1, target) - s.table.begin()) - 1;
    // The parameter whose length from the table entry is `target`: Newton's method kept inside the interval.
    double lo = double(i) / kSteps, hi = double(i + 1) / kSteps;
    const double base = s.table[static_cast<std::size_t>(i)];
    const double span = s.table[static_cast<std::size_t>(i) + 1] - base;
    double t = span > 0 ? lo + (hi - lo) * (target - base) / span : lo;
    for (int k = 0; k < 50; ++k) {
      const double f = base + length_between(s, double(i) / kSteps, t) - target;
      if (std::abs(f) < 1e-10) break;
      (f > 0 ? hi : lo) = t;
      const double v = speed(s, t);
      const double next = v > 0 ? t - f / v : lo;
      t = next > lo && next < hi ? next : (lo + hi) / 2;
    }
    Point tangent = derivative(s, t);
    if (!(std::hypot(tangent.x, tangent.y) > 1e-9 * s.length())) {  // a cusp or a control point on an end
      tangent = eval(s, std::min(t + 1e-4, 1.0)) - eval(s, std::max(t - 1e-4, 0.0));
    }
    return {eval(s, t), std::atan2(tangent.y, tangent.x)};
  }
};

/// A glyph placed in the text's user space.
struct Placed {
  const text::Font* font = nullptr;
  std::uint32_t glyph = 0;
  double size = 0;
  double x = 0, y = 0;          // pen position (origin on the baseline)
  double advance = 0;
  double rotate = 0;            // degrees, about the pen position of the glyph's cluster
  double ox = 0, oy = 0;        // the glyph's offset from that pen position (marks, ligature parts)
  double stretch = 1;           // horizontal scale (lengthAdjust="spacingAndGlyphs")
  int element = 0;
  std::uint32_t ch = 0;         // first character of its cluster
  int chunk = 0;
  bool on_path = false;
  Affine path_transform;        // for glyphs on a path: the whole placement
  Affine line_transform;        // for glyphs on a path: the frame their decorations follow (as if sideways)
};

/// x, y, dx, dy (lengths; em and ex relative to the element's font size) or rotate (plain numbers).
std::vector<double> parse_number_list(std::string_view v, TextHost& host, int axis, bool plain_numbers, double em) {
  std::vector<double> out;
  std::size_t pos = 0;
  skip_wsp(v, pos);
  while (pos < v.size() && out.size() < kMaxChars) {
    std::size_t end = pos;
    while (end < v.size() && !is_wsp(v[end]) && v[end] != ',') ++end;
    const std::string_view item = v.substr(pos, end - pos);
    double d = 0;
    if (plain_numbers) {
      std::size_t p = 0;
      if (scan_number(item, p, d) != NumberScan::Ok || p != item.size()) return out;
    } else if (item.size() > 2 && (iequals(item.substr(item.size() - 2), "em") || iequals(item.substr(item.size() - 2), "ex"))) {
      std::size_t p = 0;
      if (scan_number(item, p, d) != NumberScan::Ok || p != item.size() - 2) return out;
      d *= iequals(item.substr(item.size() - 2), "em") ? em : em / 2;
    } else if (!host.length(item, axis, d)) {
      return out;
    }
    if (!std::isfinite(d)) return out;
    out.push_back(d);
    pos = end;
    skip_comma_wsp(v, pos);
  }
  return out;
}

class TextBuilder {
 public:
  TextBuilder(TextHost& host, text::FontDb& fonts) : host_(host), fonts_(fonts) {}

  void build(pugi::xml_node text, const SpanStyle& style, Group& out) {
    elements_.push_back(Element{});
    elements_.back().style = style;
    read_lists(text, 0);
    collect(text, 0, preserve_of(text, false));
    elements_[0].end = static_cast<std::uint32_t>(chars_.size());
    trim_trailing();
    drop_unplaced();
    if (chars_.empty()) return;
    apply_lists();
    layout();
    emit(out);
  }

 private:
  // ---- 1. collect ----

  static bool preserve_of(pugi::xml_node node, bool inherited) {
    const pugi::xml_attribute a = node.attribute("xml:space");
    if (!a) return inherited;
    return std::string_view(a.value()) == "preserve";
  }

  void read_lists(pugi::xml_node node, int element, bool positions = true) {
    if (const auto a = node.attribute("textLength")) {
      double d = 0;
      if (host_.length(trim(a.value()), 0, d) && d >= 0 && d < 1e9) {
        Element& e = elements_[static_cast<std::size_t>(element)];
        e.text_length = d;
        e.stretch_glyphs = std::string_view(node.attribute("lengthAdjust").value()) == "spacingAndGlyphs";
      }
    }
    if (!positions) return;
    Lists l;
    l.element = element;
    const double em = elements_[static_cast<std::size_t>(element)].style.text.font_size;
    if (const auto a = node.attribute("x")) l.x = parse_number_list(a.value(), host_, 0, false, em);
    if (const auto a = node.attribute("y")) l.y = parse_number_list(a.value(), host_, 1, false, em);
    if (const auto a = node.attribute("dx")) l.dx = parse_number_list(a.value(), host_, 0, false, em);
    if (const auto a = node.attribute("dy")) l.dy = parse_number_list(a.value(), host_, 1, false, em);
    if (const auto a = node.attribute("rotate")) l.rotate = parse_number_list(a.value(), host_, 2, true, em);
    if (!l.x.empty() || !l.y.empty() || !l.dx.empty() || !l.dy.empty() || !l.rotate.empty())
      lists_.push_back(std::move(l));
  }

  void add_text(std::string_view utf8, int element, bool preserve) {
    for (char32_t c : text::decode_utf8(utf8)) {
      if (chars_.size() >= kMaxChars || !host_.take_character()) {
        if (!warned_size_)
          host_.warn(text_node_, "too much text (the limit is " + std::to_string(kMaxTextCharacters) +
                                     " characters per document), the rest is cut");
        warned_size_ = true;
        return;
      }
      if (preserve) {
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
      } else {
        if (c == '\n' || c == '\r') continue;
        if (c == '\t') c = ' ';
        if (c == ' ' && last_space_) continue;
      }
      last_space_ = c == ' ';
      last_collapsible_ = !preserve && c == ' ';
      Char ch;
      ch.c = c;
      ch.element = element;
      chars_.push_back(ch);
    }
  }

  /// SVG 1.1 xml:space="default" strips the trailing space of the whole element.
  void trim_trailing() {
    if (!chars_.empty() && last_collapsible_ && chars_.back().c == ' ') {
      chars_.pop_back();
      for (Element& e : elements_) {
        e.begin = std::min<std::uint32_t>(e.begin, static_cast<std::uint32_t>(chars_.size()));
        e.end = std::min<std::uint32_t>(e.end, static_cast<std::uint32_t>(chars_.size()));
      }
    }
  }

  /// Removes the characters of dropped elements, keeping every element's range consistent.
  void drop_unplaced() {
    std::vector<std::uint32_t> new_index(chars_.size() + 1);
    std::uint32_t n = 0;
    for (std::uint32_t i = 0; i < chars_.size(); ++i) {
      new_index[i] = n;
      if (!elements_[static_cast<std::size_t>(chars_[i].element)].dropped) chars_[n++] = chars_[i];
    }
    new_index[chars_.size()] = n;
    chars_.resize(n);
    for (Element& e : elements_) {
      e.begin = new_index[e.begin];
      e.end = new_index[e.end];
    }
    for (std::uint32_t& start : path_starts_) start = new_index[start];
  }

  void collect(pugi::xml_node node, int element, bool preserve) {
    if (!text_node_) text_node_ = node;
    for (const pugi::xml_node child : node.children()) {
      if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
        add_text(child.value(), element, preserve);
        continue;
      }
      if (child.type() != pugi::node_element) continue;
      std::string_view name = child.name();
      if (const std::size_t colon = name.find(':'); colon != std::string_view::npos) name = name.substr(colon + 1);
      const bool known = name == "tspan" || name == "tref" || name == "a" ||
                         (name == "textPath" && elements_[static_cast<std::size_t>(element)].path < 0);
      if (!known) continue;  // title, desc, nested textPath and the like draw nothing
      int path = elements_[static_cast<std::size_t>(element)].path;
      bool dropped = elements_[static_cast<std::size_t>(element)].dropped;
      if (name == "textPath") {
        path = text_path(child);
        dropped = dropped || path < 0;  // no usable path: its text takes part in white-space handling only
      }
      const std::optional<SpanStyle> style = host_.enter(child);
      if (!style) continue;
      const int index = static_cast<int>(elements_.size());
      Element& el = elements_.emplace_back();
      el.style = *style;
      el.parent = element;
      el.begin = static_cast<std::uint32_t>(chars_.size());
      el.path = path;
      el.dropped = dropped;
      read_lists(child, index, name != "textPath");  // a textPath has textLength but no position lists
      const bool child_preserve = preserve_of(child, preserve);
      if (name == "tref") {
        if (const pugi::xml_node target = host_.href_target(child)) {
          for (pugi::xml_node n = target.first_child(); n;) {
            if (n.type() == pugi::node_pcdata || n.type() == pugi::node_cdata) add_text(n.value(), index, child_preserve);
            if (n.first_child()) {
              n = n.first_child();
              continue;
            }
            while (n && n != target && !n.next_sibling()) n = n.parent();
            if (!n || n == target) break;
            n = n.next_sibling();
          }
        }
      } else {
        collect(child, index, child_preserve);
      }
      elements_[static_cast<std::size_t>(index)].end = static_cast<std::uint32_t>(chars_.size());
      host_.leave();
      if (name == "textPath" && !dropped) path_starts_.push_back(elements_[static_cast<std::size_t>(index)].begin);
    }
  }

  /// Reads a textPath's path; -1 when it has none (its content is not drawn).
  int text_path(pugi::xml_node node) {
    Path path;
    const pugi::xml_node target = host_.href_target(node);
    if (target) path = host_.shape_of(target);
    if (path.empty()) return -1;
    TextPath tp;
    // The path's contours one after another (a move starts a new piece; its jump is not counted).
    const auto points = path.points();
    std::size_t k = 0, contours = 0;
    Point current{}, contour_start{};
    for (const Verb v : path.verbs()) {
      contours += v == Verb::Move;
      switch (v) {
        case Verb::Move: current = contour_start = points[k++]; break;
        case Verb::Line: tp.add_line(current, points[k]); current = points[k++]; break;
        case Verb::Quad: {
          const Point c = points[k], p = points[k + 1];
          tp.add(current, current + (c - current) * (2.0 / 3), p + (c - p) * (2.0 / 3), p);
          current = p;
          k += 2;
          break;
        }
        case Verb::Cubic: tp.add(current, points[k], points[k + 1], points[k + 2]); current = points[k + 2]; k += 3; break;
        case Verb::Close: tp.add_line(current, contour_start); current = contour_start; break;
      }
    }
    if (!(tp.total() > 0) || !std::isfinite(tp.total())) return -1;
    tp.closed_loop = contours == 1 && path.verbs().back() == Verb::Close;
    if (const pugi::xml_attribute side = node.attribute("side"); side && std::string_view(side.value()) == "right") tp.reverse();
    if (const pugi::xml_attribute offset = node.attribute("startOffset")) {
      const std::string_view v = trim(offset.value());
      double d = 0;
      if (!v.empty() && v.back() == '%') {
        std::size_t p = 0;
        if (scan_number(v, p, d) == NumberScan::Ok && p + 1 == v.size()) tp.start_offset = d / 100 * tp.total();
      } else if (host_.length(v, 0, d)) {
        // A length counts in the author's units when the path declares its length (pathLength).
        double declared = 0;
        std::size_t p = 0;
        const std::string_view declared_text = trim(target.attribute("pathLength").value());
        const bool has_declared = scan_number(declared_text, p, declared) == NumberScan::Ok && p == declared_text.size();
        tp.start_offset = has_declared && declared > 0 && std::isfinite(declared) ? d * tp.total() / declared : d;
      }
    }
    paths_.push_back(std::move(tp));
    return static_cast<int>(paths_.size()) - 1;
  }

  void apply_lists() {
    for (const Lists& l : lists_) {
      const Element& e = elements_[static_cast<std::size_t>(l.element)];
      for (std::uint32_t i = e.begin; i < e.end; ++i) {
        const std::size_t k = i - e.begin;
        Char& c = chars_[i];
        if (k < l.x.size()) c.x = l.x[k];
        if (k < l.y.size()) c.y = l.y[k];
        if (k < l.dx.size()) c.dx = l.dx[k];
        if (k < l.dy.size()) c.dy = l.dy[k];
        if (!l.rotate.empty()) c.rotate = l.rotate[std::min(k, l.rotate.size() - 1)];
      }
    }
  }

  // ---- 2-4. layout ----

  const Element& element(int i) const { return elements_[static_cast<std::size_t>(i)]; }

  /// The font query of an element.
  text::FontQuery query_of(const TextProperties& t) const {
    text::FontQuery q;
    q.families = t.font_family;
    q.weight = t.font_weight;
    q.slant = static_cast<text::FontSlant>(t.font_style);
    q.stretch = t.font_stretch;
    for (const auto& [tag, value] : t.variation_settings) q.variations.push_back(text::FontVariation{tag, value});
    q.optical_size = t.font_size;
    return q;
  }

  /// What has to be equal for two characters to be shaped together. Not the font size: HarfBuzz positions
  /// scale with it, so a run is shaped once at kShapeSize and each glyph scaled to its own element's size (kerning
  /// and joining work across tspans of different sizes).
  static std::string shaping_key(const TextProperties& t) {
    // Appended piece by piece (GCC 12 warns falsely about "literal" + std::string temporaries).
    std::string key;
    auto field = [&key](const std::string& v) {
      key += v;
      key += '|';
    };
    for (const std::string& f : t.font_family) field(f);
    field(std::to_string(t.font_weight));
    field(std::to_string(t.font_style));
    field(std::to_string(t.font_stretch));
    field(t.feature_settings);
    field(std::string{t.kerning ? 'k' : '-', t.small_caps ? 's' : '-', t.rtl ? 'r' : '-',
                      t.letter_spacing != 0 ? 'l' : '-'});
    for (const auto& [tag, value] : t.variation_settings) {
      field(std::to_string(tag));
      field(std::to_string(value));
    }
    return key;
  }

  /// shaping_key of an element, with its font size when its font is variable (the opsz axis follows the size).
  const std::string& key_of(int e) {
    auto it = key_cache_.find(e);
    if (it != key_cache_.end()) return it->second;
    const TextProperties& t = element(e).style.text;
    std::string key = shaping_key(t);
    const std::shared_ptr<text::Font> f = fonts_.match(query_of(t));
    if (f && f->is_variable()) key += std::to_string(t.font_size);
    return key_cache_[e] = std::move(key);
  }

  /// The size a character is drawn at (synthesised small capitals: lowercase letters smaller).
  double char_size(std::uint32_t i) {
    const Char& c = chars_[i];
    const double size = element(c.element).style.text.font_size;
    return is_small(i) ? size * 0.7 : size;
  }
  bool is_small(std::uint32_t i) { return synthesise_small_caps(chars_[i].element) && is_lower(chars_[i].c); }

  /// Where baseline `b` lies relative to the alphabetic one in element e's font (down positive).
  double baseline_line(int e, Baseline b) {
    const TextProperties& t = element(e).style.text;
    const double size = std::min(t.font_size, kMaxShapeSize);
    if (!(size > 0) || b == Baseline::Auto || b == Baseline::Alphabetic) return 0;
    const std::shared_ptr<text::Font> font = fonts_.match(query_of(t));
    if (!font) return 0;
    const text::FontMetrics fm = font->metrics(size);
    const text::DecorationMetrics dm = font->decoration_metrics(size);
    double line = 0;
    switch (b) {
      case Baseline::Middle: line = dm.x_height / 2; break;
      case Baseline::Central: line = (fm.ascender + fm.descender) / 2; break;
      case Baseline::Hanging: line = fm.ascender * 0.8; break;
      case Baseline::Mathematical: line = fm.ascender / 2; break;
      case Baseline::TextBeforeEdge: line = fm.ascender; break;
      case Baseline::TextAfterEdge:
      case Baseline::Ideographic: line = fm.descender; break;
      default: break;
    }
    return line * t.font_size / size;
  }

  /// An element's baseline-shift, down positive.
  double shift_of(int e) {
    const TextProperties& t = element(e).style.text;
    if (t.shift == TextProperties::Shift::Length) return -t.shift_length;
    if (t.shift == TextProperties::Shift::None) return 0;
    const double size = std::min(t.font_size, kMaxShapeSize);
    const std::shared_ptr<text::Font> font = size > 0 ? fonts_.match(query_of(t)) : nullptr;
    if (!font) return 0;
    const text::DecorationMetrics dm = font->decoration_metrics(size);
    return (t.shift == TextProperties::Shift::Sub ? dm.subscript_offset : dm.superscript_offset) * t.font_size / size;
  }

  /// Where element e's alphabetic baseline lies relative to the text's pen y (down positive): the text's
  /// dominant baseline sits on y; a child puts its baseline of the chosen kind (alignment-baseline, else its
  /// dominant one) on the parent's dominant baseline; baseline shifts add up.
  double baseline_offset(int e) {
    if (const auto it = baseline_cache_.find(e); it != baseline_cache_.end()) return it->second;
    const TextProperties& t = element(e).style.text;
    const Baseline b = t.alignment_baseline != Baseline::Auto ? t.alignment_baseline : t.dominant_baseline;
    const int parent = element(e).parent;
    // baseline-shift applies to tspan, tref and textPath, not to <text> itself (SVG 1.1, 10.9.2).
    double offset = -baseline_line(e, b) + (parent >= 0 ? shift_of(e) : 0);
    // ... placed on the parent's dominant baseline.
    if (parent >= 0) offset += baseline_offset(parent) + baseline_line(parent, element(parent).style.text.dominant_baseline);
    baseline_cache_[e] = offset;
    return offset;
  }

  struct Run {
    std::uint32_t begin = 0, end = 0;
    int element = 0;  // the element of the first character (its font properties are the run's)
  };

  static bool is_lower(char32_t c) {
    return c < 0x10000 && std::iswlower(static_cast<wint_t>(c)) && std::towupper(static_cast<wint_t>(c)) != static_cast<wint_t>(c);
  }

  bool synthesise_small_caps(int e) {
    const TextProperties& t = element(e).style.text;
    if (!t.small_caps) return false;
    const auto it = smcp_cache_.find(e);
    if (it != smcp_cache_.end()) return it->second;
    const std::shared_ptr<text::Font> f = fonts_.match(query_of(t));
    return smcp_cache_[e] = !(f && f->has_substitution_feature("smcp"));
  }

  void layout() {
    // Chunks: boundaries at absolute positions and textPath starts.
    std::sort(path_starts_.begin(), path_starts_.end());
    std::vector<std::uint32_t> starts{0};
    for (std::uint32_t i = 1; i < chars_.size(); ++i) {
      const bool path_start = std::binary_search(path_starts_.begin(), path_starts_.end(), i);
      const bool path_change = element(chars_[i].element).path != element(chars_[i - 1].element).path;
      if (chars_[i].x || chars_[i].y || path_start || path_change) starts.push_back(i);
    }
    starts.push_back(static_cast<std::uint32_t>(chars_.size()));
    Point pen{0, 0};
    for (std::size_t c = 0; c + 1 < starts.size(); ++c) layout_chunk(starts[c], starts[c + 1], static_cast<int>(c), pen);
  }

  void layout_chunk(std::uint32_t begin, std::uint32_t end, int chunk, Point& pen) {
    const Char& first = chars_[begin];
    const int path = element(first.element).path;
    const int previous_path = begin == 0 ? -1 : element(chars_[begin - 1].element).path;
    // On a path the pen is a distance along it (x) and a shift across it (y), from 0 at the path's start; text
    // after a textPath goes on from the end point of its path (SVG 2, 11.8.3 "after path").
    if (path >= 0 && previous_path != path) pen = Point{0, 0};
    if (path < 0 && previous_path >= 0) pen = paths_[static_cast<std::size_t>(previous_path)].end_point();
    if (first.x) pen.x = *first.x;
    if (first.y && path < 0) pen.y = *first.y;  // on a path, absolute y means nothing (SVG 1.1, 10.13.2)
    // Runs of one shaping style.
    std::vector<Run> runs;
    for (std::uint32_t i = begin; i < end; ++i) {
      const int e = chars_[i].element;
      const std::string key = key_of(e);
      if (runs.empty() || key != last_key_) runs.push_back(Run{i, i, e});
      runs.back().end = i + 1;
      last_key_ = key;
    }
    last_key_.clear();
    const TextProperties& chunk_style = element(first.element).style.text;
    if (chunk_style.rtl) std::reverse(runs.begin(), runs.end());
    // Vertical writing modes: the chunk is laid out as on a path going down from its start, glyphs turned
    // sideways (upright CJK is not done yet), centred on the line (the central baseline).
    vertical_ = path < 0 && element(0).style.text.vertical;  // writing-mode applies to <text> only
    const Point origin = pen;
    if (vertical_) pen = Point{0, 0};
    const std::size_t chunk_first_glyph = placed_.size();
    const double start_x = pen.x;
    for (const Run& run : runs) shape_and_place(run, begin, end, chunk, pen);
    // textLength: innermost elements first (they come later in elements_).
    // An element that spans several chunks keeps its natural length (as resvg does).
    // Elements are in document order, so their first characters never decrease: those starting in this chunk
    // are one stretch of elements_.
    const auto from = std::lower_bound(elements_.begin(), elements_.end(), begin,
                                       [](const Element& el, std::uint32_t v) { return el.begin < v; });
    const auto to = std::lower_bound(from, elements_.end(), end,
                                     [](const Element& el, std::uint32_t v) { return el.begin < v; });
    index_glyphs(chunk_first_glyph);
    for (auto it = to; it != from;) {
      --it;
      if (it->text_length && it->end <= end && it->end > it->begin)
        fit_length(static_cast<int>(it - elements_.begin()), pen);
    }
    // text-anchor (start is the right end in right-to-left text).
    // The chunk's width: its advance without the letter-spacing after its last character.
    double width = pen.x - start_x;
    if (end > begin) {
      const TextProperties& last = element(chars_[end - 1].element).style.text;
      if (!is_cursive(chars_[end - 1].c)) width -= spacing(last.letter_spacing, last.letter_spacing_percent);
    }
    TextAnchor anchor = chunk_style.anchor;
    if (chunk_style.rtl && anchor != TextAnchor::Middle) anchor = anchor == TextAnchor::Start ? TextAnchor::End : TextAnchor::Start;
    const double shift = anchor == TextAnchor::Middle ? -width / 2 : anchor == TextAnchor::End ? -width : 0;
    for (std::size_t g = chunk_first_glyph; g < placed_.size(); ++g) placed_[g].x += shift;
    pen.x += shift;
    if (vertical_) {
      TextPath down;
      down.add_line(Point{origin.x, origin.y - kVerticalReach}, Point{origin.x, origin.y + kVerticalReach});
      down.start_offset = kVerticalReach;
      for (std::size_t g = chunk_first_glyph; g < placed_.size(); ++g)
        placed_[g].y -= baseline_line(placed_[g].element, Baseline::Central);
      place_on_path(down, chunk_first_glyph);
      // Ideographs, kana and hangul stand upright (Unicode Vertical_Orientation U): centred on the line, the
      // middle of their em box at the middle of their advance.
      for (std::size_t g = chunk_first_glyph; g < placed_.size(); ++g) {
        Placed& p = placed_[g];
        if (!is_upright(chars_[p.ch].c)) continue;
        const double advance = p.advance * p.stretch;
        const double central = baseline_line(p.element, Baseline::Central);
        const double across = -(p.y + central);  // dx and baseline shifts, across the line
        const double mid = origin.y + p.x + advance / 2;
        p.path_transform = Affine::translate(origin.x - advance / 2 + across, mid - central);
      }
      pen = Point{origin.x, origin.y + pen.x};
    } else if (path >= 0) {
      const TextPath& tp = paths_[static_cast<std::size_t>(path)];
      place_on_path(tp, chunk_first_glyph);
    }
  }

  /// textLength on element e: its glyphs in this chunk spaced (or stretched) to span exactly that length; the
  /// glyphs after them move along.
  /// Sorts placed_[first..] by character (by_char_), so the glyphs of an element are found by its character range.
  void index_glyphs(std::size_t first) {
    by_char_.clear();
    for (std::size_t g = first; g < placed_.size(); ++g) by_char_.push_back(g);
    std::stable_sort(by_char_.begin(), by_char_.end(),
                     [&](std::size_t a, std::size_t b) { return placed_[a].ch < placed_[b].ch; });
  }

  /// The glyphs (indices into placed_, in placed_ order) of element e's characters, among those index_glyphs
  /// sorted.
  std::vector<std::size_t> glyphs_of(int e) const {
    const Element& el = element(e);
    const auto lo = std::lower_bound(by_char_.begin(), by_char_.end(), el.begin,
                                     [&](std::size_t g, std::uint32_t v) { return placed_[g].ch < v; });
    const auto hi = std::lower_bound(lo, by_char_.end(), el.end,
                                     [&](std::size_t g, std::uint32_t v) { return placed_[g].ch < v; });
    std::vector<std::size_t> out(lo, hi);
    std::sort(out.begin(), out.end());
    return out;
  }

  void fit_length(int e, Point& pen) {
    const std::vector<std::size_t> mine = glyphs_of(e);
    if (mine.empty()) return;
    const std::size_t begin = mine.front(), end = mine.back() + 1;  // glyphs of one chunk, in a row
    const double x0 = placed_[begin].x;
    const double width = placed_[end - 1].x + placed_[end - 1].advance * placed_[end - 1].stretch - x0;
    const double target = *element(e).text_length;
    if (!(width > 0)) return;
    const double diff = target - width;
    double shift = diff;  // how far the glyphs after the element move
    if (element(e).stretch_glyphs) {
      const double k = target / width;
      for (std::size_t g = begin; g < end; ++g) {
        placed_[g].x = x0 + (placed_[g].x - x0) * k;
        placed_[g].stretch *= k;
      }
    } else {
      // Extra space between clusters: the last glyph ends at the target length.
      std::size_t clusters = 0;
      for (std::size_t g = begin; g < end; ++g) clusters += g == begin || placed_[g].ch != placed_[g - 1].ch;
      const double step = clusters > 1 ? diff / static_cast<double>(clusters - 1) : 0;
      std::size_t k = 0;
      for (std::size_t g = begin; g < end; ++g) {
        if (g != begin && placed_[g].ch != placed_[g - 1].ch) ++k;
        placed_[g].x += step * static_cast<double>(k);
      }
      if (clusters <= 1) return;
      // What follows moves by one more step: the last character gets its share of space after it too (what
      // resvg's references show).
      shift += step;
    }
    for (std::size_t g = end; g < placed_.size(); ++g) placed_[g].x += shift;
    pen.x += shift;
  }

  /// Shapes a run and places its glyphs. The run is shaped with up to kContext characters of the chunk on each
  /// side (then only its own glyphs are kept), so kerning and joining work across a change of font style, as
  /// they do in resvg (which shapes the whole chunk once per style).
  void shape_and_place(const Run& run, std::uint32_t chunk_begin, std::uint32_t chunk_end, int chunk, Point& pen) {
    constexpr std::uint32_t kContext = 8;
    const TextProperties& t = element(run.element).style.text;
    const std::uint32_t from = std::max(chunk_begin, run.begin > kContext ? run.begin - kContext : 0);
    const std::uint32_t to = std::min(chunk_end, run.end + kContext);
    std::u32string text;
    for (std::uint32_t i = from; i < to; ++i) {
      char32_t c = chars_[i].c;
      if (is_small(i)) c = static_cast<char32_t>(std::towupper(static_cast<wint_t>(c)));
      text.push_back(c);
    }
    text::FontList fonts =
        fonts_.fonts_for(query_of(t), std::u32string_view(text).substr(run.begin - from, run.end - run.begin));
    if (fonts.empty()) {
      if (!warned_fonts_) host_.warn(text_node_, "no font available for text, not drawn");
      warned_fonts_ = true;
      return;
    }
    text::TextStyle style;
    style.size = kShapeSize;
    style.direction = t.rtl ? text::Direction::RightToLeft : text::Direction::LeftToRight;
    std::string features = t.feature_settings;
    auto add = [&](const char* f) { features += features.empty() ? f : std::string(",") + f; };
    if (!t.kerning) add("kern=0");
    if (t.small_caps && !synthesise_small_caps(run.element)) add("smcp");
    if (t.letter_spacing != 0) add("liga=0,clig=0");
    style.features = features;
    std::vector<text::ShapedGlyph> glyphs;
    try {
      glyphs = text::shape_text(text, fonts, style);
    } catch (const Error& e) {
      host_.warn(text_node_, std::string("text not shaped: ") + e.what());
      return;
    }
    // The run's own glyphs; clusters become character indices.
    std::erase_if(glyphs, [&](const text::ShapedGlyph& sg) {
      return from + sg.cluster < run.begin || from + sg.cluster >= run.end;
    });
    for (text::ShapedGlyph& sg : glyphs) sg.cluster += from;
    for (std::size_t g = 0; g < glyphs.size(); ++g) {
      const text::ShapedGlyph& sg = glyphs[g];
      const std::uint32_t ci = sg.cluster;
      const bool cluster_start = g == 0 || glyphs[g - 1].cluster != sg.cluster;
      const bool cluster_end = g + 1 == glyphs.size() || glyphs[g + 1].cluster != sg.cluster;
      const Char& ch = chars_[ci];
      const double size = char_size(ci);
      const double ratio = size > 0 ? size / kShapeSize : 0;
      if (cluster_start && vertical_) {  // dy runs along the line, dx across it
        pen.x += ch.dy;
        pen.y -= ch.dx;
      } else if (cluster_start) {
        pen.x += ch.dx;
        pen.y += ch.dy;
      }
      Placed p;
      p.font = fonts.fonts[sg.font].get();
      p.glyph = sg.glyph;
      p.size = size;
      p.x = pen.x + sg.x_offset * ratio;
      p.y = pen.y - sg.y_offset * ratio + baseline_offset(ch.element);  // HarfBuzz offsets point up
      p.advance = sg.x_advance * ratio;
      if (cluster_start) cluster_pen_ = pen;
      p.ox = p.x - cluster_pen_.x;
      p.oy = p.y - cluster_pen_.y - baseline_offset(ch.element);
      p.rotate = ch.rotate.value_or(0);
      p.element = ch.element;
      p.ch = ci;
      p.chunk = chunk;
      if (size > 0) placed_.push_back(p);
      pen.x += sg.x_advance * ratio;
      pen.y -= sg.y_advance * ratio;
      if (cluster_end) {
        const TextProperties& ct = element(ch.element).style.text;
        if (!is_cursive(ch.c)) pen.x += spacing(ct.letter_spacing, ct.letter_spacing_percent);
        if (ch.c == ' ') pen.x += spacing(ct.word_spacing, ct.word_spacing_percent);
      }
      keep_fonts_.push_back(fonts.fonts[sg.font]);
    }
    if (keep_fonts_.size() > 4096) dedupe_fonts();
  }

  /// A letter- or word-spacing in px (percentages of the viewport's diagonal measure, as SVG lengths).
  double spacing(double value, bool percent) {
    if (!percent || value == 0) return value;
    double unit = 0;
    return host_.length("1%", 2, unit) ? value * unit : 0;
  }

  /// Characters set upright in vertical text: CJK ideographs, kana, hangul, fullwidth forms and CJK symbols.
  static bool is_upright(char32_t c) {
    return (c >= 0x1100 && c <= 0x11FF) || (c >= 0x2E80 && c <= 0x2FDF) || (c >= 0x3000 && c <= 0x30FF) ||
           (c >= 0x3100 && c <= 0x31FF) || (c >= 0x3400 && c <= 0x4DBF) || (c >= 0x4E00 && c <= 0x9FFF) ||
           (c >= 0xA000 && c <= 0xA4CF) || (c >= 0xAC00 && c <= 0xD7AF) || (c >= 0xF900 && c <= 0xFAFF) ||
           (c >= 0xFF00 && c <= 0xFF60) || (c >= 0xFFE0 && c <= 0xFFE6) || (c >= 0x20000 && c <= 0x3FFFF);
  }

  /// Scripts whose letters join: letter-spacing would break them apart, so it is not applied (CSS Text 3,
  /// "cursive tracking").
  static bool is_cursive(char32_t c) {
    return (c >= 0x0600 && c <= 0x08FF) || (c >= 0xFB50 && c <= 0xFDFF) || (c >= 0xFE70 && c <= 0xFEFF) ||
           (c >= 0x0700 && c <= 0x074F) || (c >= 0x1800 && c <= 0x18AF);
  }

  void dedupe_fonts() {
    std::sort(keep_fonts_.begin(), keep_fonts_.end());
    keep_fonts_.erase(std::unique(keep_fonts_.begin(), keep_fonts_.end()), keep_fonts_.end());
  }

  /// Glyphs of a textPath chunk: each placed with its advance's midpoint on the path, rotated to the tangent;
  /// glyphs whose midpoint falls off the path are dropped. On a single closed subpath the text wraps around
  /// it, up to one turn in the direction text-anchor and direction leave room for (SVG 2, 11.8.3).
  void place_on_path(const TextPath& tp, std::size_t first) {
    const double length = tp.total();
    std::size_t keep = first;
    for (std::size_t g = first; g < placed_.size(); ++g) {
      Placed p = placed_[g];
      const double advance = p.advance * p.stretch;
      double mid = tp.start_offset + p.x + advance / 2;
      if (tp.closed_loop) {
        const TextProperties& t = element(p.element).style.text;
        const double from_start = mid - tp.start_offset;
        const bool forward = (t.anchor == TextAnchor::Start) != t.rtl;  // (start, ltr) or (end, rtl)
        const double lo = t.anchor == TextAnchor::Middle ? -length / 2 : forward ? 0 : -length;
        if (!(from_start >= lo && from_start <= lo + length)) continue;
        mid = std::fmod(mid, length);
        if (mid < 0) mid += length;
      } else if (!(mid >= 0 && mid <= length)) {
        continue;
      }
      const auto [point, angle] = tp.at(mid);
      p.on_path = true;
      p.path_transform = Affine::translate(point.x, point.y) * Affine::rotate(angle * 180 / std::numbers::pi) *
                         Affine::translate(-advance / 2, p.y) * Affine::rotate(p.rotate);
      p.line_transform = p.path_transform;
      placed_[keep++] = p;
    }
    placed_.resize(keep);
  }

  // ---- 5. emit ----

  /// Where a glyph's pen space (origin on the baseline, x along the advance, in px) lands in user space.
  static Affine placement(const Placed& p) {
    if (p.on_path) return p.path_transform;
    if (p.rotate == 0) return Affine::translate(p.x, p.y);
    return Affine::translate(p.x - p.ox, p.y - p.oy) * Affine::rotate(p.rotate) * Affine::translate(p.ox, p.oy);
  }

  Affine glyph_transform(const Placed& p) const {
    const double s = p.size / p.font->units_per_em();
    return placement(p) * Affine::scale(s * p.stretch, s);
  }

  /// A glyph's full glyph cell: its advance wide, from the font's ascender to its descender (SVG 2, 8.10: the
  /// bounding box of text is the union of these, not of the outlines).
  Path glyph_cell(const Placed& p) const {
    Path cell;
    const double advance = p.advance * p.stretch;
    if (!(advance > 0)) return cell;
    const text::FontMetrics fm = p.font->metrics(std::min(p.size, kMaxShapeSize));
    const double k = p.size / std::min(p.size, kMaxShapeSize);
    cell.add_rect(Rect{0, fm.ascender * k, advance, fm.descender * k});
    return cell.transformed(placement(p));
  }

  PathNode node_for(int e, Path path) {
    const SpanStyle& s = element(e).style;
    PathNode n;
    n.path = std::move(path);
    n.fill = s.fill;
    n.stroke = s.stroke;
    n.stroke_first = s.stroke_first;
    n.crisp_edges = s.crisp_edges || element(0).style.text.speed;  // text-rendering applies to <text> only
    std::tie(n.line, n.column) = host_.position(text_node_);
    return n;
  }

  /// Rectangles of one decoration of element `e` (underline, overline or line-through), one per stretch of its
  /// glyphs on one baseline of one chunk.
  Path decoration(int e, std::uint8_t kind) {
    Path out;
    const TextProperties& t = element(e).style.text;
    const double size = std::min(t.font_size, kMaxShapeSize);
    if (!(size > 0)) return out;
    const std::shared_ptr<text::Font> font = fonts_.match(query_of(t));
    if (!font) return out;
    const double scale = t.font_size / size;
    const text::DecorationMetrics dm = font->decoration_metrics(size);
    const text::FontMetrics fm = font->metrics(size);
    double centre = 0, thickness = dm.underline_thickness * scale;
    if (kind == TextProperties::kUnderline) centre = dm.underline_position * scale;
    if (kind == TextProperties::kOverline) centre = fm.ascender * scale;
    if (kind == TextProperties::kLineThrough) {
      centre = dm.strikeout_position * scale;
      thickness = dm.strikeout_thickness * scale;
    }
    std::optional<Rect> current;
    int current_chunk = -1;
    double current_y = 0;
    auto flush = [&] {
      if (current && current->width() > 0) out.add_rect(*current);
      current.reset();
    };
    std::size_t previous = placed_.size();
    for (const std::size_t g : glyphs_of(e)) {
      const Placed& p = placed_[g];
      if (g != previous + 1) flush();  // another element's glyphs came between
      previous = g;
      if (p.on_path) {  // along a path: one rectangle per glyph, turned with it
        Path r;
        r.add_rect(Rect{0, centre - thickness / 2 - p.y, p.advance, centre + thickness / 2 - p.y});
        out.add_path(r.transformed(p.line_transform * Affine::rotate(-p.rotate)));
        continue;
      }
      if (p.rotate != 0) {  // a rotated glyph: its own piece of line, turned with it
        flush();
        Path r;
        r.add_rect(Rect{0, centre - thickness / 2, p.advance * p.stretch, centre + thickness / 2});
        out.add_path(r.transformed(Affine::translate(p.x, p.y) * Affine::rotate(p.rotate)));
        continue;
      }
      const double base = p.y;
      if (!current || p.chunk != current_chunk || base != current_y) {
        flush();
        current = Rect{p.x, base + centre - thickness / 2, p.x, base + centre + thickness / 2};
        current_chunk = p.chunk;
        current_y = base;
      }
      current->x0 = std::min({current->x0, p.x, p.x + p.advance * p.stretch});
      current->x1 = std::max({current->x1, p.x, p.x + p.advance * p.stretch});
    }
    flush();
    return out;
  }

  /// A colour bitmap glyph (CBDT, sbix) as an image in a group that places it like the glyph's outline, scaled
  /// from its strike to the glyph's size. It takes the place of the glyph's fill: drawn when the element has a
  /// fill, with its fill-opacity.
  std::optional<Node> bitmap_node(const Placed& p, const text::ColorBitmap& bitmap) const {
    const SpanStyle& s = element(p.element).style;
    if (!s.fill || s.fill->paint.kind == Paint::Kind::None || !(bitmap.ppem > 0)) return std::nullopt;
    ImageNode image;
    image.image = bitmap.image;
    image.view = Rect{bitmap.left, bitmap.top, bitmap.left + bitmap.image->width, bitmap.top + bitmap.image->height};
    image.dest = image.clip = image.view;
    std::tie(image.line, image.column) = host_.position(text_node_);
    Group g;
    const double k = p.size / bitmap.ppem;
    g.transform = placement(p) * Affine::scale(k * p.stretch, k);
    g.opacity = s.fill->paint.opacity;
    g.children.push_back(Node{std::move(image)});
    return Node{std::move(g)};
  }

  void emit(Group& out) {
    // Glyph outlines, one path per stretch of glyphs of one element; colour bitmap glyphs as images between them.
    std::vector<Node> glyph_nodes;
    Path current;
    int current_element = -1;
    Rect box;
    bool have_box = false;
    auto include = [&](const Path& p) {
      const auto verbs = p.verbs();
      if (std::all_of(verbs.begin(), verbs.end(), [](Verb v) { return v == Verb::Move; })) return;
      const Rect b = p.bounds();
      if (!have_box) box = b;
      box.include({b.x0, b.y0});
      box.include({b.x1, b.y1});
      have_box = true;
    };
    auto flush = [&] {
      if (current_element >= 0 && !current.empty()) {
        glyph_nodes.push_back(Node{node_for(current_element, std::move(current))});
      }
      current = Path();
    };
    for (const Placed& p : placed_) {
      if (p.element != current_element) {
        flush();
        current_element = p.element;
      }
      include(glyph_cell(p));
      if (const text::ColorBitmap* bitmap = p.font->color_bitmap(p.glyph)) {
        flush();  // in text order between the outlines before and after it
        if (std::optional<Node> image = bitmap_node(p, *bitmap)) glyph_nodes.push_back(std::move(*image));
        continue;
      }
      const Path& outline = p.font->outline_units(p.glyph);
      if (!outline.empty()) current.add_path(outline.transformed(glyph_transform(p)));
    }
    flush();
    // Decorations: from each element that declares one, with that element's paint.
    std::vector<Node> below, above;
    index_glyphs(0);
    for (std::size_t e = 0; e < elements_.size(); ++e) {
      // Decorations of elements around <text> are drawn as the text's own (with its paint).
      const TextProperties& t = elements_[e].style.text;
      const std::uint8_t d = e == 0 ? t.decoration | t.ancestor_decoration : t.decoration;
      for (const std::uint8_t kind : {TextProperties::kUnderline, TextProperties::kOverline, TextProperties::kLineThrough}) {
        if (!(d & kind)) continue;
        Path rects = decoration(static_cast<int>(e), kind);
        if (rects.empty()) continue;
        include(rects);
        (kind == TextProperties::kLineThrough ? above : below).push_back(Node{node_for(static_cast<int>(e), std::move(rects))});
      }
    }
    auto append = [&](std::vector<Node>& nodes) {
      for (Node& n : nodes) {
        // Unpainted glyphs (fill and stroke none, visibility hidden) stay as paths without paint: they draw
        // nothing but count in the bounding box of the groups around the text, as any hidden shape does.
        if (PathNode* path = std::get_if<PathNode>(&n.value); path && have_box) path->paint_box = box;
        out.children.push_back(std::move(n));
      }
    };
    append(below);
    append(glyph_nodes);
    append(above);
  }

  TextHost& host_;
  text::FontDb& fonts_;
  pugi::xml_node text_node_;
  std::vector<Element> elements_;
  std::vector<Char> chars_;
  std::vector<Lists> lists_;
  std::vector<TextPath> paths_;
  std::vector<std::uint32_t> path_starts_;
  std::vector<Placed> placed_;
  std::vector<std::size_t> by_char_;  // glyph indices sorted by character (index_glyphs)
  std::vector<std::shared_ptr<text::Font>> keep_fonts_;  // the fonts placed_ points to stay alive
  std::map<int, double> baseline_cache_;
  std::map<int, bool> smcp_cache_;
  std::map<int, std::string> key_cache_;
  bool vertical_ = false;  // the chunk being laid out is vertical
  Point cluster_pen_;      // pen position at the start of the cluster being placed
  std::string last_key_;
  bool last_space_ = true;  // strips leading white space (xml:space default)
  bool last_collapsible_ = false;
  bool warned_size_ = false, warned_fonts_ = false;
};

}  // namespace

std::shared_ptr<text::FontDb> default_font_db() {
  auto db = std::make_shared<text::FontDb>();
  db->add_embedded_default();
  return db;
}

void build_text(pugi::xml_node text, const SpanStyle& style, TextHost& host, text::FontDb* fonts, Group& out) {
  if (!fonts) return;
  TextBuilder builder(host, *fonts);
  try {
    builder.build(text, style, out);
  } catch (const Error& e) {
    // A position or size out of range (a path refuses non-finite coordinates): the element draws nothing.
    out.children.clear();
    host.warn(text, std::string("text not drawn: ") + e.what());
  }
}

}  // namespace vraster::svg::detail
