// svg_subset: SVG transform lists ("translate(10 20) rotate(30 5 5) scale(2)").
#include <string_view>

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

}  // namespace vraster::svg
