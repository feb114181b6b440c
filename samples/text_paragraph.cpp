// Sample: one paragraph in three scripts (Latin, Arabic, Devanagari), wrapped to a width, with font fallback.
//
//   text_paragraph_sample [OUT.png] [FONT_DIR]
// FONT_DIR holds Amiri-Regular.ttf and NotoSansDevanagari-Regular.ttf (default: the repository's shared fonts).
#include <cstdio>
#include <string>

#include "vraster/error.hpp"
#include "vraster/png.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "text_paragraph.png";
#ifdef VRASTER_SOURCE_DIR
  const std::string dir = argc > 2 ? argv[2] : VRASTER_SOURCE_DIR "/../shared/conformance/fonts";
#else
  const std::string dir = argc > 2 ? argv[2] : ".";
#endif
  try {
    FontList fonts = FontList::default_list();  // Noto Sans (embedded) for Latin
    fonts.add(Font::load_file(dir + "/Amiri-Regular.ttf"));
    fonts.add(Font::load_file(dir + "/NotoSansDevanagari-Regular.ttf"));

    const std::string paragraph =
        "Typography in three scripts: office affinity, AVAWA kerning. "
        "\xd9\x85\xd8\xb1\xd8\xad\xd8\xa8\xd8\xa7 \xd8\xa8\xd8\xa7\xd9\x84\xd8\xb9\xd8\xa7\xd9\x84\xd9\x85 "  // مرحبا بالعالم
        "(hello, world) "
        "\xe0\xa4\xa8\xe0\xa4\xae\xe0\xa4\xb8\xe0\xa5\x8d\xe0\xa4\xa4\xe0\xa5\x87 "                        // नमस्ते
        "\xe0\xa4\xa6\xe0\xa5\x81\xe0\xa4\xa8\xe0\xa4\xbf\xe0\xa4\xaf\xe0\xa4\xbe "                        // दुनिया
        "and back to Latin with kerning pairs: AVA, To, Wa.";
    TextStyle style;
    style.size = 28;
    const double width = 560, margin = 20;
    Image image(static_cast<int>(width + 2 * margin), 540);
    image.clear(Color::rgb8(255, 255, 255));
    TextRenderer renderer;
    const Align aligns[] = {Align::Left, Align::Center, Align::Right};
    double y = margin - fonts.fonts[0]->metrics(style.size).ascender;
    for (Align align : aligns) {
      LayoutOptions lo;
      lo.max_width = width;
      lo.align = align;
      const TextLayout layout = layout_text(paragraph, fonts, style, lo, {margin, y});
      renderer.draw(image, layout, Color::rgb8(20, 30, 60));
      y = layout.logical.y1 + 14 - fonts.fonts[0]->metrics(style.size).ascender;
      if (y > image.height) break;
    }
    write_png(out, image);
    std::printf("wrote %s\n", out.c_str());
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "text_paragraph_sample: %s\n", e.what());
    return 2;
  }
}
