// The default font (Noto Sans Regular, SIL OFL 1.1; text/fonts/) assembled into the library, so text works with
// no font files at run time and from any working directory.
#include <cstdint>
#include <span>

#include "vraster_text/font.hpp"

#ifndef VRASTER_TEXT_DEFAULT_FONT_PATH
#error "VRASTER_TEXT_DEFAULT_FONT_PATH must name the default font file"
#endif

__asm__(
    ".section .rodata\n"
    ".balign 16\n"
    "vraster_text_default_font_begin:\n"
    ".incbin \"" VRASTER_TEXT_DEFAULT_FONT_PATH "\"\n"
    "vraster_text_default_font_end:\n"
    ".balign 8\n"
    "vraster_text_default_font_size:\n"
    ".quad vraster_text_default_font_end - vraster_text_default_font_begin\n"
    ".previous\n");

extern "C" const std::uint8_t vraster_text_default_font_begin[];
extern "C" const std::uint64_t vraster_text_default_font_size;

namespace vraster::text {

std::span<const std::uint8_t> Font::default_font_data() {
  return {vraster_text_default_font_begin, static_cast<std::size_t>(vraster_text_default_font_size)};
}

}  // namespace vraster::text
