// svg_subset: SVG transform lists ("translate(10 20) rotate(30 5 5) scale(2)").
#include <cmath>
#include <span>
#include <string_view>
#include <utility>

#include "scan.hpp"
#include "svg_subset/svg.hpp"

namespace vraster::svg {
namespace {

/// The matrix of one transform function, or false when the name or the argument count is wrong.
bool make_transform(std::string_view name, const double* v, int n, Affine& m) {
  if (name == "matrix" && n == 6) {
    m = Affine{v[0], v[1], v[2], v[3], v[4], v[5]};
  } else if (name == "translate" && (n == 1 || n == 2)) {
    m = Affine::translate(v[0], n == 2 ? v[1] : 0.0);
  } else if (name == "scale" && (n == 1 || n == 2)) {
    m = Affine::scale(v[0], n == 2 ? v[1] : v[0]);
  } else if (name == "rotate" && (n == 1 || n == 3)) {
    m = n == 3 ? Affine::rotate(v[0], v[1], v[2]) : Affine::rotate(v[0]);
  } else if (name == "skewX" && n == 1) {
    m = Affine::skew_x(v[0]);
  } else if (name == "skewY" && n == 1) {
    m = Affine::skew_y(v[0]);
  } else {
    return false;
  }
  return true;
}

bool is_name_char(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

}  // namespace

bool parse_transform(std::string_view text, Affine& out) {
  using detail::skip_wsp;
  Affine result;
  std::size_t pos = 0;
  skip_wsp(text, pos);
  while (pos < text.size()) {
    const std::size_t name_start = pos;
    while (pos < text.size() && is_name_char(text[pos])) ++pos;
    const std::string_view name = text.substr(name_start, pos - name_start);
    skip_wsp(text, pos);
    if (name.empty() || pos >= text.size() || text[pos] != '(') return false;
    ++pos;

    // Arguments: numbers separated by comma-wsp, no comma before ')'.
    double v[6];
    int n = 0;
    skip_wsp(text, pos);
    while (pos < text.size() && text[pos] != ')') {
      if (n == 6) return false;
      if (detail::scan_number(text, pos, v[n]) != detail::NumberScan::Ok) return false;
      ++n;
      if (detail::skip_comma_wsp(text, pos) && (pos >= text.size() || text[pos] == ')')) return false;
    }
    if (pos >= text.size()) return false;  // no ')'
    ++pos;

    Affine m;
    if (!make_transform(name, v, n, m)) return false;
    result = result * m;  // "A B" applies B first, then A

    // Transforms are separated by optional comma-wsp; a comma must be followed by another transform.
    if (detail::skip_comma_wsp(text, pos) && pos >= text.size()) return false;
  }
  if (!result.is_finite()) return false;
  out = result;
  return true;
}

namespace {

/// One argument of a CSS transform function: a number, a length (px or an absolute unit; a bare number only when
/// it is 0) or an angle (deg, rad, grad, turn; a bare 0), in px or degrees.
enum class CssArgument { Number, Length, Angle };

bool css_argument(std::string_view text, std::size_t& pos, CssArgument kind, double& out) {
  if (detail::scan_number(text, pos, out) != detail::NumberScan::Ok) return false;
  std::size_t end = pos;
  while (end < text.size() && is_name_char(text[end])) ++end;
  const std::string_view unit = text.substr(pos, end - pos);
  pos = end;
  if (kind == CssArgument::Number) return unit.empty();
  if (unit.empty()) return out == 0;
  static constexpr std::pair<std::string_view, double> kLengths[] = {
      {"px", 1}, {"pt", 96.0 / 72.0}, {"pc", 16}, {"mm", 96.0 / 25.4}, {"cm", 96.0 / 2.54}, {"in", 96}};
  static constexpr std::pair<std::string_view, double> kAngles[] = {
      {"deg", 1}, {"rad", 180 / 3.14159265358979323846}, {"grad", 0.9}, {"turn", 360}};
  for (const auto& [name, factor] : kind == CssArgument::Length ? std::span<const std::pair<std::string_view, double>>(kLengths)
                                                       : std::span<const std::pair<std::string_view, double>>(kAngles)) {
    if (detail::iequals(unit, name)) {
      out *= factor;
      return true;
    }
  }
  return false;
}

}  // namespace

bool parse_css_transform(std::string_view text, Affine& out) {
  using detail::skip_wsp;
  const std::string_view trimmed = detail::trim(text);
  if (trimmed == "none") {
    out = Affine{};
    return true;
  }
  Affine result;
  std::size_t pos = 0;
  while (pos < trimmed.size()) {
    const std::size_t name_start = pos;
    while (pos < trimmed.size() && is_name_char(trimmed[pos])) ++pos;
    const std::string_view name = trimmed.substr(name_start, pos - name_start);
    if (name.empty() || pos >= trimmed.size() || trimmed[pos] != '(') return false;  // no space before '('
    ++pos;
    const bool is_matrix = name == "matrix", is_scale = name.starts_with("scale");
    const bool is_translate = name.starts_with("translate");
    const CssArgument kind = is_matrix || is_scale ? CssArgument::Number
                             : is_translate        ? CssArgument::Length
                                                   : CssArgument::Angle;
    double v[6];
    int n = 0;
    skip_wsp(trimmed, pos);
    while (pos < trimmed.size() && trimmed[pos] != ')') {
      if (n == 6) return false;
      if (n > 0) {  // CSS separates arguments with commas
        if (trimmed[pos] != ',') return false;
        ++pos;
        skip_wsp(trimmed, pos);
      }
      if (!css_argument(trimmed, pos, kind, v[n])) return false;
      ++n;
      skip_wsp(trimmed, pos);
    }
    if (pos >= trimmed.size()) return false;  // no ')'
    ++pos;
    Affine m;
    if (name == "translateX" && n == 1) {
      m = Affine::translate(v[0], 0);
    } else if (name == "translateY" && n == 1) {
      m = Affine::translate(0, v[0]);
    } else if (name == "scaleX" && n == 1) {
      m = Affine::scale(v[0], 1);
    } else if (name == "scaleY" && n == 1) {
      m = Affine::scale(1, v[0]);
    } else if (name == "skew" && (n == 1 || n == 2)) {
      constexpr double kRadians = 3.14159265358979323846 / 180;
      m = Affine{1, std::tan((n == 2 ? v[1] : 0) * kRadians), std::tan(v[0] * kRadians), 1, 0, 0};
    } else if (name == "rotate" ? n != 1 : !make_transform(name, v, n, m)) {
      return false;
    } else if (name == "rotate") {
      m = Affine::rotate(v[0]);
    }
    result = result * m;
    skip_wsp(trimmed, pos);
  }
  if (pos == 0 || !result.is_finite()) return false;
  out = result;
  return true;
}

}  // namespace vraster::svg
