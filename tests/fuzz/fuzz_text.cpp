// libFuzzer target: the text path with mutated fonts: Font::load_memory (TrueType, CFF, collections) -> names,
// metrics, glyph outlines (unhinted and light-hinted) -> shaping and layout (HarfBuzz, fribidi: Latin with
// ligatures and kerning, Arabic, Devanagari, mixed directions) -> drawing (cached masks and direct outlines).
// Loading may fail with a vraster::Error; whatever loads must go through every stage without crashing, and every
// outline point must be finite.
//
// Input: byte 0 picks the size, hinting and text; byte 1 the face index (0 or 1); the rest is the font file.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "vraster/vraster.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;

namespace {

const char* const kTexts[] = {
    "Hamburg AVAWA office fluffy 0123",
    "\xd9\x85\xd8\xb1\xd8\xad\xd8\xa8\xd8\xa7 \xd8\xa8\xd8\xa7\xd9\x84\xd8\xb9\xd8\xa7\xd9\x84\xd9\x85",  // Arabic
    "\xe0\xa4\xa8\xe0\xa4\xae\xe0\xa4\xb8\xe0\xa5\x8d\xe0\xa4\xa4\xe0\xa5\x87",                              // Devanagari
    "abc \xd9\x85\xd8\xb1\xd8\xad\xd8\xa8\xd8\xa7 def\tx\x01y",                                                // mixed, controls
};

void check_finite(const Path& path) {
  for (const Point& p : path.points()) {
    if (!is_finite(p)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2 || size > 65536) return 0;  // size cap: the seed fonts are subsets of a few KiB
  const double sizes[] = {7, 12, 24, 61.5};
  const double px = sizes[data[0] & 3];
  const Hinting hinting = (data[0] >> 2) & 1 ? Hinting::Light : Hinting::None;
  const char* text = kTexts[(data[0] >> 3) & 3];
  const int face = data[1] & 1;
  std::shared_ptr<Font> font;
  try {
    font = Font::load_memory(std::vector<std::uint8_t>(data + 2, data + size), face, "fuzz.ttf");
  } catch (const Error&) {
    return 0;
  }
  try {
    (void)font->family_name();
    (void)font->style_name();
    const FontMetrics m = font->metrics(px);
    if (!std::isfinite(m.ascender) || !std::isfinite(m.descender) || !std::isfinite(m.line_gap)) std::abort();
    const int glyphs = std::min(font->glyph_count(), 64);
    for (int g = 0; g < glyphs; ++g) {
      const auto glyph = static_cast<std::uint32_t>(g);
      check_finite(font->outline_units(glyph));
      check_finite(font->outline(glyph, px, hinting));
      (void)font->advance(glyph, px);
    }
    FontList fonts(font);
    TextStyle style;
    style.size = px;
    LayoutOptions options;
    options.max_width = 90;
    const TextLayout layout = layout_text(text, fonts, style, options, {2, px});
    Image image(96, 64);
    TextRenderer renderer;
    GlyphRenderOptions cached;
    cached.hinting = hinting;
    renderer.draw(image, layout, Color{}, Affine{}, cached);
    GlyphRenderOptions direct = cached;
    direct.use_cache = false;
    renderer.draw(image, layout, Color{}, Affine::rotate(10), direct);
  } catch (const Error&) {
  }
  return 0;
}
