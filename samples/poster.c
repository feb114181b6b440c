/* Sample: a small poster through the C API (vraster/vraster.h and vraster_text/vraster_text.h): a gradient sky, a
 * sun with a radial gradient clipped to a rounded frame, hills, a translucent layer of screen-blended discs, a
 * conic-gradient ring, a dashed border and a title with a shadow. samples/poster.cpp draws the same picture
 * through the C++ canvas; both print the same probe pixels (tests/package_test.sh checks them).
 *
 *   poster_c [OUT.png]
 *
 * Build against an installed vraster:  cc poster.c $(pkg-config --cflags --libs vraster-text) */
#include <stdio.h>

#include "vraster/vraster.h"
#include "vraster_text/vraster_text.h"

#define W 480
#define H 320
static const double kPi = 3.14159265358979323846;

/* Every failure goes through here: print vr_last_error() and give up. */
static int failed(const char* what) {
  fprintf(stderr, "poster_c: %s: %s\n", what, vr_last_error());
  return 2;
}

static void probe(const vr_image* img, int x, int y) {
  int stride = 0;
  const unsigned char* p = vr_image_pixels(img, &stride) + y * stride + x * 4;
  printf("pixel %d,%d = %d %d %d %d\n", x, y, p[0], p[1], p[2], p[3]);
}

static void draw(vr_canvas* c) {
  vr_paint* sky = vr_paint_linear(0, 0, 0, H);
  vr_paint* sun = vr_paint_radial(420, 70, 0, 420, 70, 80);
  vr_paint* hills = vr_paint_linear(0, 150, 0, 240);
  vr_paint* ring = vr_paint_conic(0, 100, 200);
  vr_paint* title = vr_paint_linear(120, 0, 360, 0);
  const double dashes[2] = {12, 6};
  const double disc_x[3] = {190, 226, 208}, disc_y[3] = {92, 92, 123};
  int i;

  /* Sky: a vertical gradient over everything. */
  vr_paint_add_stop(sky, 0, 20 / 255.0, 30 / 255.0, 60 / 255.0, 1);
  vr_paint_add_stop(sky, 1, 90 / 255.0, 30 / 255.0, 90 / 255.0, 1);
  vr_canvas_set_fill_paint(c, sky);
  vr_canvas_fill_rect(c, 0, 0, W, H);

  /* The frame: sun and hills clipped to a rounded rectangle (the sun reaches past its right edge). */
  vr_canvas_save(c);
  vr_canvas_begin_path(c);
  vr_canvas_round_rect(c, 40, 40, 400, 200, 24);
  vr_canvas_clip(c, VR_FILL_NONZERO);
  vr_canvas_set_fill_rgba(c, 1, 1, 1, 0.08); /* the frame itself, faintly */
  vr_canvas_fill(c, VR_FILL_NONZERO);
  vr_paint_add_stop(sun, 0, 1, 0.95, 0.6, 1);
  vr_paint_add_stop(sun, 0.6, 1, 0.6, 0.2, 1);
  vr_paint_add_stop(sun, 1, 1, 0.3, 0.1, 0);
  vr_canvas_set_fill_paint(c, sun);
  vr_canvas_begin_path(c);
  vr_canvas_arc(c, 420, 70, 80, 0, 2 * kPi, 0);
  vr_canvas_fill(c, VR_FILL_NONZERO);
  vr_paint_add_stop(hills, 0, 0.2, 0.5, 0.3, 1);
  vr_paint_add_stop(hills, 1, 0.05, 0.2, 0.1, 1);
  vr_canvas_set_fill_paint(c, hills);
  vr_canvas_begin_path(c);
  vr_canvas_move_to(c, 40, 240);
  vr_canvas_cubic_to(c, 120, 120, 200, 230, 280, 170);
  vr_canvas_cubic_to(c, 340, 130, 400, 190, 440, 160);
  vr_canvas_line_to(c, 440, 240);
  vr_canvas_close_path(c);
  vr_canvas_fill(c, VR_FILL_NONZERO);
  vr_canvas_restore(c);

  /* A layer at 70% opacity: three discs blended with "screen" among themselves, then composited as one. */
  vr_canvas_begin_layer(c, 0.7f);
  vr_canvas_set_composite(c, VR_COMPOSITE_SCREEN);
  for (i = 0; i < 3; ++i) {
    vr_canvas_set_fill_rgba(c, i == 0, i == 1, i == 2, 1);
    vr_canvas_begin_path(c);
    vr_canvas_arc(c, disc_x[i], disc_y[i], 34, 0, 2 * kPi, 0);
    vr_canvas_fill(c, VR_FILL_NONZERO);
  }
  vr_canvas_end_layer(c);

  /* A conic-gradient ring. */
  vr_paint_add_stop(ring, 0, 1, 0.2, 0.2, 1);
  vr_paint_add_stop(ring, 0.33, 1, 0.9, 0.2, 1);
  vr_paint_add_stop(ring, 0.66, 0.2, 0.6, 1, 1);
  vr_paint_add_stop(ring, 1, 1, 0.2, 0.2, 1);
  vr_canvas_set_stroke_paint(c, ring);
  vr_canvas_set_line_width(c, 12);
  vr_canvas_begin_path(c);
  vr_canvas_arc(c, 100, 200, 26, 0, 2 * kPi, 0);
  vr_canvas_stroke(c);

  /* A dashed border with round caps. */
  vr_canvas_set_stroke_rgba(c, 1, 1, 1, 0.8);
  vr_canvas_set_line_width(c, 3);
  vr_canvas_set_line_cap(c, VR_CAP_ROUND);
  vr_canvas_set_line_dash(c, dashes, 2, 0);
  vr_canvas_stroke_rect(c, 10, 10, W - 20, H - 20);
  vr_canvas_set_line_dash(c, NULL, 0, 0);

  /* The title: centred on its alphabetic baseline, a gradient fill, a soft shadow. */
  vr_paint_add_stop(title, 0, 1, 1, 1, 1);
  vr_paint_add_stop(title, 1, 1, 0.8, 0.4, 1);
  vr_canvas_set_font(c, NULL, 40);
  vr_canvas_set_text_align(c, VR_ALIGN_CENTER);
  vr_canvas_set_shadow(c, 0, 0, 0, 0.6, 2, 3, 4);
  vr_canvas_set_fill_paint(c, title);
  vr_canvas_fill_text(c, "vraster canvas", W / 2.0, 292);
  vr_canvas_set_shadow(c, 0, 0, 0, 0, 0, 0, 0);

  vr_paint_destroy(sky);
  vr_paint_destroy(sun);
  vr_paint_destroy(hills);
  vr_paint_destroy(ring);
  vr_paint_destroy(title);
}

int main(int argc, char** argv) {
  const char* out = argc > 1 ? argv[1] : "poster.png";
  vr_image* img = vr_image_create(W, H);
  vr_canvas* c;
  if (!img) return failed("image");
  c = vr_canvas_create(img);
  if (!c) return failed("canvas");
  draw(c);
  vr_canvas_destroy(c);
  if (vr_image_write_png(img, out) != 0) return failed("writing the PNG");
  probe(img, 2, 160);   /* sky, half way down */
  probe(img, 2, 70);    /* sky beside ... */
  probe(img, 450, 70);  /* ... the sun, which the frame clips away here */
  probe(img, 420, 70);  /* the sun's centre */
  printf("wrote %s\n", out);
  vr_image_destroy(img);
  return 0;
}
