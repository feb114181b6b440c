// Safe echoing of input text in messages (see vraster/error.hpp).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <new>

#include "vraster/error.hpp"

namespace vraster {
namespace {

/// Length of the UTF-8 sequence starting at s[i] and its code point, or 0 when the bytes are not valid UTF-8
/// (overlong forms, surrogates and values above U+10FFFF included).
std::size_t utf8_sequence(std::string_view s, std::size_t i, std::uint32_t& code) {
  const auto b0 = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  std::uint32_t min = 0;
  if (b0 < 0x80) {
    code = b0;
    return 1;
  } else if ((b0 & 0xE0) == 0xC0) {
    n = 2, code = b0 & 0x1F, min = 0x80;
  } else if ((b0 & 0xF0) == 0xE0) {
    n = 3, code = b0 & 0x0F, min = 0x800;
  } else if ((b0 & 0xF8) == 0xF0) {
    n = 4, code = b0 & 0x07, min = 0x10000;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if ((b & 0xC0) != 0x80) return 0;
    code = code << 6 | (b & 0x3F);
  }
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return n;
}

/// Code points a terminal acts on or that reorder the text around them.
bool is_unsafe(std::uint32_t code) {
  return code < 0x20 || (code >= 0x7F && code <= 0x9F) || (code >= 0x202A && code <= 0x202E) ||
         (code >= 0x2066 && code <= 0x2069) || code == 0x200E || code == 0x200F || code == 0x061C;
}

}  // namespace

std::string printable(std::string_view text, std::size_t max_bytes) {
  std::string out;
  out.reserve(std::min(text.size(), max_bytes) + 8);
  std::size_t i = 0;
  while (i < text.size() && i < max_bytes) {
    std::uint32_t code = 0;
    const std::size_t n = utf8_sequence(text, i, code);
    char buffer[16];
    if (n == 0) {
      std::snprintf(buffer, sizeof buffer, "\\x%02x", static_cast<unsigned char>(text[i]));
      out += buffer;
      ++i;
      continue;
    }
    if (is_unsafe(code)) {
      if (code == '\n') {
        out += "\\n";
      } else if (code == '\t') {
        out += "\\t";
      } else if (code == '\r') {
        out += "\\r";
      } else if (code < 0x100) {
        std::snprintf(buffer, sizeof buffer, "\\x%02x", static_cast<unsigned>(code));
        out += buffer;
      } else {
        std::snprintf(buffer, sizeof buffer, "\\u{%04x}", static_cast<unsigned>(code));
        out += buffer;
      }
    } else {
      out.append(text.substr(i, n));
    }
    i += n;
  }
  if (i < text.size()) out += "...";
  return out;
}

std::string quoted(std::string_view text, std::size_t max_bytes) {
  std::string out = "'";
  out += printable(text, max_bytes);
  out += "'";
  return out;
}

std::string describe_current_exception() {
  try {
    throw;
  } catch (const std::bad_alloc&) {
    return "out of memory";
  } catch (const std::exception& e) {
    return printable(e.what(), kMaxMessageBytes);
  } catch (...) {
    return "unexpected error (not a std::exception)";
  }
}

}  // namespace vraster
