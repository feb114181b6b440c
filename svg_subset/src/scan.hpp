// svg_subset: the small lexical pieces shared by the parsers (whitespace, numbers, case-insensitive compare).
#pragma once

#include <charconv>
#include <cstddef>
#include <string_view>
#include <system_error>
#include <utility>

namespace vraster::svg::detail {

/// SVG 1.1 whitespace (space, tab, CR, LF).
inline bool is_wsp(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline char to_lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

/// True when a number may start at s[pos] (sign, digit or '.').
inline bool at_number_start(std::string_view s, std::size_t pos) {
  if (pos >= s.size()) return false;
  const char c = s[pos];
  return is_digit(c) || c == '.' || c == '-' || c == '+';
}

inline void skip_wsp(std::string_view s, std::size_t& pos) {
  while (pos < s.size() && is_wsp(s[pos])) ++pos;
}

/// Skips SVG's comma-wsp, that is wsp* (',' wsp*)?, and tells whether it skipped a comma.
inline bool skip_comma_wsp(std::string_view s, std::size_t& pos) {
  skip_wsp(s, pos);
  if (pos < s.size() && s[pos] == ',') {
    ++pos;
    skip_wsp(s, pos);
    return true;
  }
  return false;
}

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && (is_wsp(s.front()) || s.front() == '\f')) s.remove_prefix(1);
  while (!s.empty() && (is_wsp(s.back()) || s.back() == '\f')) s.remove_suffix(1);
  return s;
}

inline bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (to_lower(a[i]) != to_lower(b[i])) return false;
  }
  return true;
}

inline bool istarts_with(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}

enum class NumberScan { Ok, NotANumber, OutOfRange };

/// Scans one SVG number at s[pos]: sign? (digits ('.' digits?)? | '.' digits) ([eE] sign? digits)?.
/// The exponent is taken only when digits follow, so "1em" is 1 followed by "em" and "1e-3-2" is 0.001 then -2.
/// Ok: `value` is set and pos moves past the number. NotANumber: pos is unchanged. OutOfRange (magnitude too
/// large for a double): pos moves past the token so the caller can report it. Values too small for a double
/// become zero, as they would after any rounding.
inline NumberScan scan_number(std::string_view s, std::size_t& pos, double& value) {
  const std::size_t n = s.size();
  std::size_t i = pos;
  const bool negative = i < n && s[i] == '-';
  if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t int_begin = i;
  while (i < n && is_digit(s[i])) ++i;
  const std::size_t int_end = i;
  std::size_t frac_begin = i, frac_end = i;
  if (i < n && s[i] == '.') {
    frac_begin = frac_end = i + 1;
    while (frac_end < n && is_digit(s[frac_end])) ++frac_end;
    if (int_end > int_begin || frac_end > frac_begin) i = frac_end;
  }
  if (int_end == int_begin && frac_end == frac_begin) return NumberScan::NotANumber;
  long exponent = 0;
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    bool exp_negative = false;
    if (j < n && (s[j] == '+' || s[j] == '-')) exp_negative = s[j++] == '-';
    if (j < n && is_digit(s[j])) {
      while (j < n && is_digit(s[j])) {
        if (exponent < 100000) exponent = exponent * 10 + (s[j] - '0');  // clamped: only its sign matters then
        ++j;
      }
      if (exp_negative) exponent = -exponent;
      i = j;
    }
  }
  // from_chars does not accept a leading '+'.
  const char* first = s.data() + pos + (s[pos] == '+' ? 1 : 0);
  const char* last = s.data() + i;
  double parsed = 0;
  const auto result = std::from_chars(first, last, parsed, std::chars_format::general);
  if (result.ec == std::errc::result_out_of_range) {
    // Overflow or underflow: the decimal exponent of the leading significant digit tells which.
    long magnitude = 0;
    std::size_t lead = int_begin;
    while (lead < int_end && s[lead] == '0') ++lead;
    if (lead < int_end) {
      magnitude = static_cast<long>(int_end - lead) - 1;
    } else {
      std::size_t k = frac_begin;
      while (k < frac_end && s[k] == '0') ++k;
      magnitude = -static_cast<long>(k - frac_begin) - 1;
    }
    pos = i;
    if (magnitude + exponent < 0) {
      value = negative ? -0.0 : 0.0;
      return NumberScan::Ok;
    }
    return NumberScan::OutOfRange;
  }
  if (result.ec != std::errc() || result.ptr != last) return NumberScan::NotANumber;  // cannot happen: token checked
  value = parsed;
  pos = i;
  return NumberScan::Ok;
}

/// Pixels per unit of a CSS absolute length unit at `dpi` pixels per inch (CSS and the default: 96): px (and no
/// unit) is always 1, in is `dpi`, cm, mm, pt and pc follow from the inch (ASCII case-insensitive). 0 for any
/// other unit.
inline double absolute_unit_scale(std::string_view unit, double dpi) {
  static constexpr std::pair<std::string_view, double> kPerInch[] = {
      {"in", 1}, {"cm", 2.54}, {"mm", 25.4}, {"pt", 72}, {"pc", 6}};
  if (unit.empty() || iequals(unit, "px")) return 1;
  for (const auto& [name, per_inch] : kPerInch) {
    if (iequals(unit, name)) return dpi / per_inch;
  }
  return 0;
}

}  // namespace vraster::svg::detail
