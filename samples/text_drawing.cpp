// Sample: text inside a drawing: a badge with a filled shape, a caption on it, and a rotated label drawn from
// outlines (transformed text never comes from the glyph cache).
//
//   text_drawing_sample [OUT.png]
#include <cstdio>
#include <string>

#include "vraster/vraster.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "text_drawing.png";
  try {
    Image image(480, 320);
    image.clear(Color::rgb8(250, 248, 240));
    Renderer shapes;
    Path badge;
    badge.add_round_rect({40, 60, 440, 200}, 24, 24);
    shapes.fill(image, badge, {}, Color::rgb8(30, 90, 160), {});
    Path dot;
    dot.add_circle({80, 130}, 22);
    shapes.fill(image, dot, {}, Color::rgb8(250, 200, 60), {});

    const FontList fonts = FontList::default_list();
    TextRenderer text;
    TextStyle title;
    title.size = 40;
    LayoutOptions centred;
    centred.max_width = 320;
    centred.align = Align::Center;
    const TextLayout caption = layout_text("vraster text", fonts, title, centred, {80, 145});
    text.draw(image, caption, Color::rgb8(255, 255, 255));

    TextStyle small;
    small.size = 18;
    const TextLayout note = layout_text("outlines, any transform", fonts, small);
    text.draw(image, note, Color::rgb8(160, 40, 40), Affine::translate(250, 290) * Affine::rotate(-12));
    text.draw(image, note, Color::rgb8(40, 120, 40), Affine::translate(40, 250) * Affine::skew_x(-20));

    // The same caption as a path, stroked by filling a slightly offset copy underneath (a cheap shadow).
    Path outline;
    TextRenderer::append_outlines(caption, outline);
    shapes.fill(image, outline, Affine::translate(2, 60), Color::rgb8(0, 0, 0).with_alpha(0.25f), {});
    write_png(out, image);
    std::printf("wrote %s\n", out.c_str());
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "text_drawing_sample: %s\n", e.what());
    return 2;
  }
}
