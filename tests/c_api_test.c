/* The C API, compiled as C99 (not C++): pixels against tiny hand-made expectations, and error reporting.
 *   vraster_c_api_test WORK_DIR   (a writable folder for the PNG round trip)
 * Prints each failed check with its line; exits 1 when any failed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vraster/vraster.h"
#if VRASTER_WITH_TEXT
#include "vraster_text/vraster_text.h"
#endif

static int failures = 0;
static int checks = 0;

#define CHECK(cond)                                                         \
  do {                                                                      \
    ++checks;                                                               \
    if (!(cond)) {                                                          \
      ++failures;                                                           \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
    }                                                                       \
  } while (0)

/* Pixel (x, y) channel i (premultiplied RGBA). */
static int px(const vr_image* img, int x, int y, int i) {
  int stride = 0;
  const unsigned char* p = vr_image_pixels(img, &stride);
  return p[y * stride + x * 4 + i];
}

/* True when pixel (x, y) is (r, g, b, a) within `tol` per channel. */
static int pixel_is(const vr_image* img, int x, int y, int r, int g, int b, int a, int tol) {
  const int want[4] = {r, g, b, a};
  int i;
  for (i = 0; i < 4; ++i) {
    if (abs(px(img, x, y, i) - want[i]) > tol) {
      fprintf(stderr, "  pixel %d,%d = %d %d %d %d, want %d %d %d %d (+-%d)\n", x, y, px(img, x, y, 0),
              px(img, x, y, 1), px(img, x, y, 2), px(img, x, y, 3), r, g, b, a, tol);
      return 0;
    }
  }
  return 1;
}

static int error_mentions(const char* word) { return strstr(vr_last_error(), word) != NULL; }

/* A fresh w x h transparent image with a canvas on it. */
static vr_canvas* fresh(int w, int h, vr_image** img) {
  *img = vr_image_create(w, h);
  return vr_canvas_create(*img);
}

static void test_images(const char* work) {
  int stride = -1, x, y, all_zero = 1;
  char path[1024];
  vr_image* img = vr_image_create(4, 3);
  vr_image* back;
  unsigned char* data;
  CHECK(img != NULL);
  CHECK(vr_image_width(img) == 4 && vr_image_height(img) == 3);
  data = vr_image_pixels_mutable(img, &stride);
  CHECK(stride == 16);
  for (y = 0; y < 3; ++y)
    for (x = 0; x < 16; ++x) all_zero &= data[y * stride + x] == 0;
  CHECK(all_zero);

  /* PNG round trip of premultiplied pixels that survive un-premultiplying exactly (opaque, and alpha 0). */
  data[0] = 10; data[1] = 20; data[2] = 30; data[3] = 255;
  data[stride + 4] = 255; data[stride + 5] = 255; data[stride + 6] = 255; data[stride + 7] = 255;
  snprintf(path, sizeof path, "%s/c_api_round_trip.png", work);
  CHECK(vr_image_write_png(img, path) == 0);
  back = vr_image_read_png(path);
  CHECK(back != NULL);
  if (back) {
    CHECK(vr_image_width(back) == 4 && vr_image_height(back) == 3);
    CHECK(pixel_is(back, 0, 0, 10, 20, 30, 255, 0));
    CHECK(pixel_is(back, 1, 1, 255, 255, 255, 255, 0));
    CHECK(pixel_is(back, 3, 2, 0, 0, 0, 0, 0));
  }
  vr_image_destroy(back);
  vr_image_destroy(img);

  /* Failures: NULL plus a message. */
  vr_clear_error();
  CHECK(strcmp(vr_last_error(), "") == 0);
  CHECK(vr_image_create(0, 5) == NULL);
  CHECK(strlen(vr_last_error()) > 0);
  CHECK(vr_image_create(100000, 1) == NULL);
  CHECK(vr_image_create(-3, -3) == NULL);
  snprintf(path, sizeof path, "%s/no_such_file.png", work);
  CHECK(vr_image_read_png(path) == NULL);
  CHECK(error_mentions("no_such_file.png"));
  CHECK(vr_image_read_png(NULL) == NULL);
  CHECK(vr_image_width(NULL) == 0);
  CHECK(error_mentions("vr_image_width"));
  CHECK(vr_image_pixels(NULL, &stride) == NULL);
  CHECK(vr_image_write_png(NULL, path) == -1);
  vr_image_destroy(NULL); /* a no-op */
}

static void test_fill_and_rules(void) {
  vr_image* img;
  vr_canvas* c = fresh(8, 8, &img);
  int y;
  CHECK(c != NULL);
  /* A pixel-aligned opaque rectangle: exact inside, nothing outside. */
  CHECK(vr_canvas_set_fill_rgba(c, 1, 0, 0, 1) == 0);
  CHECK(vr_canvas_fill_rect(c, 2, 2, 4, 4) == 0);
  CHECK(pixel_is(img, 2, 2, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 5, 5, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 1, 2, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 6, 5, 0, 0, 0, 0, 0));
  /* Half a pixel column covered: alpha 128 (analytic coverage 0.5). */
  CHECK(vr_canvas_clear_rect(c, 0, 0, 8, 8) == 0);
  CHECK(pixel_is(img, 3, 3, 0, 0, 0, 0, 0));
  CHECK(vr_canvas_fill_rect(c, 0, 0, 0.5, 8) == 0);
  for (y = 0; y < 8; ++y) CHECK(pixel_is(img, 0, y, 128, 0, 0, 128, 1));
  CHECK(pixel_is(img, 1, 0, 0, 0, 0, 0, 0));
  /* Straight alpha in, premultiplied out. */
  CHECK(vr_canvas_set_fill_rgba(c, 0, 0, 1, 0.5) == 0);
  CHECK(vr_canvas_fill_rect(c, 4, 0, 4, 1) == 0);
  CHECK(pixel_is(img, 5, 0, 0, 0, 128, 128, 1));
  /* Channels outside [0, 1] are clamped. */
  CHECK(vr_canvas_set_fill_rgba(c, 2, -1, 0, 7) == 0);
  CHECK(vr_canvas_fill_rect(c, 4, 1, 1, 1) == 0);
  CHECK(pixel_is(img, 4, 1, 255, 0, 0, 255, 0));

  /* Two overlapping squares wound the same way: non-zero fills the overlap, even-odd leaves it empty;
   * aliased, so each pixel is all or nothing. */
  CHECK(vr_canvas_clear_rect(c, 0, 0, 8, 8) == 0);
  CHECK(vr_canvas_set_antialias(c, VR_AA_NONE) == 0);
  CHECK(vr_canvas_set_fill_rgba(c, 0, 1, 0, 1) == 0);
  vr_canvas_begin_path(c);
  vr_canvas_rect(c, 0, 0, 6, 6);
  vr_canvas_rect(c, 2, 2, 6, 6);
  CHECK(vr_canvas_fill(c, VR_FILL_EVENODD) == 0);
  CHECK(pixel_is(img, 1, 1, 0, 255, 0, 255, 0));
  CHECK(pixel_is(img, 3, 3, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 7, 7, 0, 255, 0, 255, 0));
  CHECK(vr_canvas_fill(c, VR_FILL_NONZERO) == 0);
  CHECK(pixel_is(img, 3, 3, 0, 255, 0, 255, 0));
  /* abs-geq-2 fills only the overlap. */
  CHECK(vr_canvas_clear_rect(c, 0, 0, 8, 8) == 0);
  CHECK(vr_canvas_fill(c, VR_FILL_ABS_GEQ_2) == 0);
  CHECK(pixel_is(img, 3, 3, 0, 255, 0, 255, 0));
  CHECK(pixel_is(img, 1, 1, 0, 0, 0, 0, 0));
  CHECK(vr_canvas_is_point_in_path(c, 3, 3, VR_FILL_EVENODD) == 0);
  CHECK(vr_canvas_is_point_in_path(c, 1, 1, VR_FILL_EVENODD) == 1);
  CHECK(vr_canvas_is_point_in_path(c, 3, 3, VR_FILL_NONZERO) == 1);
  CHECK(vr_canvas_is_point_in_path(c, 7.5, 0.5, VR_FILL_NONZERO) == 0);

  /* Bad numbers: the call does nothing and is no failure. */
  CHECK(vr_canvas_clear_rect(c, 0, 0, 8, 8) == 0);
  CHECK(vr_canvas_fill_rect(c, NAN, 0, 4, 4) == 0);
  CHECK(vr_canvas_fill_rect(c, 0, 0, INFINITY, 4) == 0);
  CHECK(vr_canvas_set_fill_rgba(c, NAN, 0, 0, 1) == 0); /* ignored: the fill stays green */
  vr_canvas_begin_path(c);
  CHECK(vr_canvas_move_to(c, NAN, 1) == 0);
  CHECK(vr_canvas_line_to(c, 1, INFINITY) == 0);
  CHECK(vr_canvas_arc(c, 4, 4, NAN, 0, 1, 0) == 0);
  CHECK(vr_canvas_rect(c, 0, 0, 8, 8) == 0);
  CHECK(vr_canvas_translate(c, NAN, 0) == 0);
  CHECK(vr_canvas_fill(c, VR_FILL_NONZERO) == 0);
  CHECK(pixel_is(img, 4, 4, 0, 255, 0, 255, 0)); /* only the valid rect reached the path, untransformed */

  vr_canvas_destroy(c);
  vr_image_destroy(img);
}

static void test_errors(void) {
  vr_image* img;
  vr_canvas* c = fresh(4, 4, &img);
  vr_composite op = VR_COMPOSITE_SOURCE_OVER;
  double dash = 2;
  CHECK(vr_canvas_create(NULL) == NULL);
  CHECK(error_mentions("vr_canvas_create"));
  CHECK(vr_canvas_fill(NULL, VR_FILL_NONZERO) == -1);
  CHECK(error_mentions("vr_canvas_fill"));
  CHECK(vr_canvas_fill_rect(NULL, 0, 0, 1, 1) == -1);
  CHECK(error_mentions("vr_canvas_fill_rect"));
  CHECK(vr_canvas_end_layer(NULL) == -1);
  CHECK(vr_canvas_set_fill_paint(c, NULL) == -1);
  CHECK(error_mentions("paint"));
  CHECK(vr_canvas_fill(c, (vr_fill_rule)99) == -1);
  CHECK(error_mentions("99"));
  CHECK(vr_canvas_set_composite(c, (vr_composite)27) == -1);
  CHECK(vr_canvas_set_line_cap(c, (vr_line_cap)-1) == -1);
  CHECK(vr_canvas_set_antialias(c, (vr_antialias)42) == -1);
  CHECK(vr_canvas_set_line_dash(c, NULL, 2, 0) == -1);
  CHECK(vr_canvas_set_line_dash(c, &dash, -1, 0) == -1);
  CHECK(vr_canvas_set_line_dash(c, NULL, 0, 0) == 0); /* solid */
  CHECK(vr_canvas_end_layer(c) == -1);
  CHECK(error_mentions("no layer"));
  CHECK(vr_canvas_is_point_in_path(NULL, 0, 0, VR_FILL_NONZERO) == -1);
  CHECK(vr_canvas_get_pixels(c, 0, 0, 0, 4) == NULL);
  CHECK(vr_canvas_draw_image(c, NULL, 0, 0, 1, 1) == -1);
  CHECK(vr_canvas_restore(c) == 0); /* unmatched restore: nothing, as the canvas */

  CHECK(vr_composite_from_name("multiply", &op) == 0 && op == VR_COMPOSITE_MULTIPLY);
  CHECK(vr_composite_from_name("color-dodge", &op) == 0 && op == VR_COMPOSITE_COLOR_DODGE);
  CHECK(vr_composite_from_name("plus-lighter", &op) == 0 && op == VR_COMPOSITE_LIGHTER);
  CHECK(vr_composite_from_name("destination-atop", &op) == 0 && op == VR_COMPOSITE_DESTINATION_ATOP);
  CHECK(vr_composite_from_name("bogus-op", &op) == -1 && op == VR_COMPOSITE_DESTINATION_ATOP);
  CHECK(error_mentions("bogus-op"));
  CHECK(vr_composite_from_name(NULL, &op) == -1);
  CHECK(strcmp(vr_composite_name(VR_COMPOSITE_SOFT_LIGHT), "soft-light") == 0);
  CHECK(strcmp(vr_composite_name(VR_COMPOSITE_SOURCE_OVER), "source-over") == 0);
  CHECK(strcmp(vr_composite_name((vr_composite)200), "") == 0);

  CHECK(vr_paint_linear(0, 0, NAN, 1) == NULL);
  CHECK(error_mentions("vr_paint_linear"));
  CHECK(vr_paint_radial(0, 0, -1, 0, 0, 5) == NULL);
  CHECK(vr_paint_pattern(NULL) == NULL);
  CHECK(vr_paint_add_stop(NULL, 0, 0, 0, 0, 1) == -1);
  vr_canvas_destroy(c);
  vr_image_destroy(img);
}

static void test_state_clip_transform(void) {
  vr_image* img;
  vr_canvas* c = fresh(8, 8, &img);
  double m[6];
  vr_canvas_set_fill_rgba(c, 1, 0, 0, 1);
  /* save / restore brings the fill colour back. */
  CHECK(vr_canvas_save(c) == 0);
  vr_canvas_set_fill_rgba(c, 0, 0, 1, 1);
  CHECK(vr_canvas_restore(c) == 0);
  vr_canvas_fill_rect(c, 0, 0, 1, 1);
  CHECK(pixel_is(img, 0, 0, 255, 0, 0, 255, 0));

  /* A clip to the left half, then a fill of everything; restore drops the clip. */
  vr_canvas_save(c);
  vr_canvas_begin_path(c);
  vr_canvas_rect(c, 0, 0, 4, 8);
  CHECK(vr_canvas_clip(c, VR_FILL_NONZERO) == 0);
  vr_canvas_set_fill_rgba(c, 0, 1, 0, 1);
  vr_canvas_fill_rect(c, 0, 0, 8, 8);
  CHECK(pixel_is(img, 3, 5, 0, 255, 0, 255, 0));
  CHECK(pixel_is(img, 4, 5, 0, 0, 0, 0, 0));
  vr_canvas_restore(c);
  vr_canvas_fill_rect(c, 4, 0, 4, 8);
  CHECK(pixel_is(img, 4, 5, 255, 0, 0, 255, 0));

  /* Transforms: translate then scale apply to coordinates in reverse order, as on the canvas. */
  vr_canvas_clear_rect(c, 0, 0, 8, 8);
  CHECK(vr_canvas_translate(c, 4, 2) == 0);
  CHECK(vr_canvas_scale(c, 2, 2) == 0);
  CHECK(vr_canvas_get_transform(c, m) == 0);
  CHECK(m[0] == 2 && m[1] == 0 && m[2] == 0 && m[3] == 2 && m[4] == 4 && m[5] == 2);
  vr_canvas_fill_rect(c, 0, 0, 1, 1); /* device (4, 2) .. (6, 4) */
  CHECK(pixel_is(img, 4, 2, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 5, 3, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 6, 3, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 3, 2, 0, 0, 0, 0, 0));
  CHECK(vr_canvas_set_transform(c, 1, 0, 0, 1, 0, 0) == 0);
  CHECK(vr_canvas_get_transform(c, m) == 0 && m[0] == 1 && m[4] == 0);
  /* rotate(pi/2) maps (x, y) to (-y, x): a unit square at (1, -2) lands on device (2 .. 3, 1 .. 2). */
  CHECK(vr_canvas_rotate(c, 3.14159265358979323846 / 2) == 0);
  vr_canvas_clear_rect(c, -8, -8, 16, 16);
  vr_canvas_fill_rect(c, 1, -3, 1, 1);
  CHECK(pixel_is(img, 2, 1, 255, 0, 0, 255, 1));
  CHECK(pixel_is(img, 1, 1, 0, 0, 0, 0, 1));
  vr_canvas_reset_transform(c);

  /* A stroke: a horizontal line 2 px wide along y = 4 covers rows 3 and 4 exactly. */
  vr_canvas_clear_rect(c, 0, 0, 8, 8);
  vr_canvas_set_stroke_rgba(c, 0, 0, 1, 1);
  CHECK(vr_canvas_set_line_width(c, 2) == 0);
  vr_canvas_begin_path(c);
  vr_canvas_move_to(c, 0, 4);
  vr_canvas_line_to(c, 8, 4);
  CHECK(vr_canvas_stroke(c) == 0);
  CHECK(pixel_is(img, 5, 3, 0, 0, 255, 255, 0));
  CHECK(pixel_is(img, 5, 4, 0, 0, 255, 255, 0));
  CHECK(pixel_is(img, 5, 2, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 5, 5, 0, 0, 0, 0, 0));
  CHECK(vr_canvas_is_point_in_stroke(c, 5, 4.5) == 1);
  CHECK(vr_canvas_is_point_in_stroke(c, 5, 6.5) == 0);
  vr_canvas_destroy(c);
  vr_image_destroy(img);
}

static void test_composite_and_layers(void) {
  vr_image* img;
  vr_canvas* c = fresh(4, 4, &img);
  /* multiply: red x green = black, opaque. */
  vr_canvas_set_fill_rgba(c, 1, 0, 0, 1);
  vr_canvas_fill_rect(c, 0, 0, 4, 4);
  CHECK(vr_canvas_set_composite(c, VR_COMPOSITE_MULTIPLY) == 0);
  vr_canvas_set_fill_rgba(c, 0, 1, 0, 1);
  vr_canvas_fill_rect(c, 0, 0, 2, 4);
  CHECK(pixel_is(img, 0, 0, 0, 0, 0, 255, 0));
  CHECK(pixel_is(img, 3, 0, 255, 0, 0, 255, 0));
  /* destination-out removes what the shape covers. */
  vr_canvas_set_composite(c, VR_COMPOSITE_DESTINATION_OUT);
  vr_canvas_fill_rect(c, 0, 0, 4, 1);
  CHECK(pixel_is(img, 3, 0, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 3, 1, 255, 0, 0, 255, 0));
  /* copy is unbounded: outside the shape the destination becomes transparent. */
  vr_canvas_set_composite(c, VR_COMPOSITE_COPY);
  vr_canvas_set_fill_rgba(c, 0, 0, 1, 1);
  vr_canvas_fill_rect(c, 0, 3, 1, 1);
  CHECK(pixel_is(img, 0, 3, 0, 0, 255, 255, 0));
  CHECK(pixel_is(img, 3, 1, 0, 0, 0, 0, 0));
  vr_canvas_set_composite(c, VR_COMPOSITE_SOURCE_OVER);

  /* A layer at opacity 0.5: an opaque red square inside it ends up half transparent. */
  vr_canvas_clear_rect(c, 0, 0, 4, 4);
  CHECK(vr_canvas_begin_layer(c, 0.5f) == 0);
  vr_canvas_set_fill_rgba(c, 1, 0, 0, 1);
  vr_canvas_fill_rect(c, 0, 0, 2, 2);
  vr_canvas_fill_rect(c, 1, 1, 2, 2); /* overlapping inside the layer: still 0.5 after it, not 0.75 */
  CHECK(pixel_is(img, 0, 0, 0, 0, 0, 0, 0)); /* nothing reaches the target before end_layer */
  CHECK(vr_canvas_end_layer(c) == 0);
  CHECK(pixel_is(img, 0, 0, 128, 0, 0, 128, 1));
  CHECK(pixel_is(img, 1, 1, 128, 0, 0, 128, 1));
  CHECK(pixel_is(img, 3, 3, 0, 0, 0, 0, 0));
  /* A layer takes the operator current at its begin: destination-out with the layer's opacity 1. */
  vr_canvas_set_composite(c, VR_COMPOSITE_DESTINATION_OUT);
  CHECK(vr_canvas_begin_layer(c, 1.0f) == 0);
  vr_canvas_fill_rect(c, 0, 0, 1, 1); /* source-over inside the layer */
  CHECK(vr_canvas_end_layer(c) == 0);
  CHECK(pixel_is(img, 0, 0, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 1, 1, 128, 0, 0, 128, 1));
  vr_canvas_destroy(c);
  vr_image_destroy(img);
}

static void test_paints_and_images(void) {
  vr_image* img;
  vr_canvas* c = fresh(8, 4, &img);
  vr_paint* g = vr_paint_linear(0, 0, 8, 0);
  vr_image* tile = vr_image_create(2, 2);
  vr_image* part;
  vr_paint* pattern;
  unsigned char* t;
  int stride, x;
  /* Black to white along x: pixel centres at t = (x + 0.5) / 8. */
  CHECK(g != NULL);
  CHECK(vr_paint_add_stop(g, 0, 0, 0, 0, 1) == 0);
  CHECK(vr_paint_add_stop(g, 1, 1, 1, 1, 1) == 0);
  CHECK(vr_paint_add_stop(g, 1.5, 1, 1, 1, 1) == -1);
  CHECK(vr_paint_add_stop(g, NAN, 1, 1, 1, 1) == -1);
  CHECK(vr_paint_set_extend(g, VR_EXTEND_NONE) == -1); /* patterns only */
  CHECK(vr_paint_set_extend(g, VR_EXTEND_REPEAT) == 0);
  CHECK(vr_canvas_set_fill_paint(c, g) == 0);
  vr_paint_destroy(g); /* the canvas keeps its own copy */
  vr_canvas_fill_rect(c, 0, 0, 8, 1);
  for (x = 0; x < 8; ++x) {
    const int v = (int)floor((x + 0.5) / 8 * 255 + 0.5);
    CHECK(pixel_is(img, x, 0, v, v, v, 255, 2));
  }

  /* A 2 x 2 pattern, nearest filtering, repeats every 2 px. */
  t = vr_image_pixels_mutable(tile, &stride);
  t[0] = 255; t[3] = 255;                               /* (0, 0) red */
  t[5] = 255; t[7] = 255;                               /* (1, 0) green */
  t[stride + 2] = 255; t[stride + 3] = 255;             /* (0, 1) blue */
  t[stride + 4] = 255; t[stride + 5] = 255; t[stride + 6] = 255; t[stride + 7] = 255; /* (1, 1) white */
  pattern = vr_paint_pattern(tile);
  CHECK(pattern != NULL);
  CHECK(vr_paint_set_filter(pattern, VR_FILTER_NEAREST) == 0);
  CHECK(vr_paint_add_stop(pattern, 0, 0, 0, 0, 1) == -1);
  vr_canvas_set_fill_paint(c, pattern);
  vr_canvas_fill_rect(c, 0, 1, 8, 3);
  CHECK(pixel_is(img, 0, 2, 255, 0, 0, 255, 0)); /* rows 1..3 start with tile row 1 (the tile is at y = 0) */
  CHECK(pixel_is(img, 4, 2, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 5, 2, 0, 255, 0, 255, 0));
  CHECK(pixel_is(img, 6, 1, 0, 0, 255, 255, 0));
  CHECK(pixel_is(img, 7, 3, 255, 255, 255, 255, 0));
  /* The pattern moved by its transform: one pixel to the right. */
  CHECK(vr_paint_set_transform(pattern, 1, 0, 0, 1, 1, 0) == 0);
  CHECK(vr_paint_set_transform(pattern, 1, 0, 0, NAN, 1, 0) == -1);
  vr_canvas_set_fill_paint(c, pattern);
  vr_canvas_fill_rect(c, 0, 2, 8, 1);
  CHECK(pixel_is(img, 1, 2, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 2, 2, 0, 255, 0, 255, 0));
  vr_paint_destroy(pattern);

  /* draw_image without smoothing: each tile pixel becomes a 2 x 2 block. */
  vr_canvas_clear_rect(c, 0, 0, 8, 4);
  CHECK(vr_canvas_set_image_smoothing(c, 0, VR_FILTER_BILINEAR) == 0);
  CHECK(vr_canvas_draw_image(c, tile, 4, 0, 4, 4) == 0);
  CHECK(pixel_is(img, 4, 0, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 5, 1, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 6, 1, 0, 255, 0, 255, 0));
  CHECK(pixel_is(img, 7, 3, 255, 255, 255, 255, 0));
  CHECK(pixel_is(img, 3, 0, 0, 0, 0, 0, 0));

  /* get_pixels / put_pixels: a copy of a region, and back elsewhere, untouched by transform or alpha. */
  part = vr_canvas_get_pixels(c, 6, 0, 2, 2);
  CHECK(part != NULL && vr_image_width(part) == 2);
  if (part) {
    CHECK(pixel_is(part, 0, 0, 0, 255, 0, 255, 0));
    vr_canvas_set_global_alpha(c, 0.25);
    vr_canvas_translate(c, 3, 3);
    CHECK(vr_canvas_put_pixels(c, part, 0, 2) == 0);
    CHECK(pixel_is(img, 0, 2, 0, 255, 0, 255, 0));
    CHECK(pixel_is(img, 1, 3, 0, 255, 0, 255, 0));
  }
  vr_image_destroy(part);
  vr_image_destroy(tile);

  /* The canvas keeps its target alive after the caller lets go of it. */
  vr_image_destroy(img);
  CHECK(vr_canvas_fill_rect(c, 0, 0, 8, 4) == 0);
  vr_canvas_destroy(c);
}


#if VRASTER_WITH_TEXT
static long ink(const vr_image* img) {
  long sum = 0;
  int x, y;
  for (y = 0; y < vr_image_height(img); ++y)
    for (x = 0; x < vr_image_width(img); ++x) sum += px(img, x, y, 3);
  return sum;
}

static void test_text(void) {
  vr_image* img;
  vr_canvas* c = fresh(160, 48, &img);
  vr_text_metrics left, centre, top, big;
  const char garbage[16] = "not a font file";
  vr_font* file = vr_font_load(VRASTER_SOURCE_DIR "/text/fonts/NotoSans-Regular.ttf");
  vr_font* def = vr_font_load_default();
  CHECK(file != NULL && def != NULL);
  CHECK(vr_font_load("no_such_font.ttf") == NULL);
  CHECK(error_mentions("no_such_font.ttf"));
  CHECK(vr_font_load_memory(garbage, sizeof garbage) == NULL);
  CHECK(vr_font_load(NULL) == NULL);

  CHECK(vr_canvas_set_font(c, file, 0) == -1);
  CHECK(vr_canvas_set_font(c, file, 5000) == -1);
  CHECK(vr_canvas_set_font(c, file, NAN) == -1);
  CHECK(vr_canvas_set_font(NULL, file, 10) == -1);
  CHECK(vr_canvas_set_text_align(c, (vr_text_align)9) == -1);
  CHECK(vr_canvas_set_text_baseline(c, (vr_text_baseline)-2) == -1);
  CHECK(vr_canvas_set_font_features(c, "+++") == -1);
  CHECK(vr_canvas_fill_text(c, NULL, 0, 0) == -1);
  CHECK(vr_canvas_measure_text(c, "x", NULL) == -1);

  /* Alignment and baseline move the anchor: centre is half the advance left of start, top puts the anchor on
   * the ascender line. */
  CHECK(vr_canvas_set_font(c, file, 20) == 0);
  vr_font_destroy(file); /* the canvas keeps the font it uses */
  CHECK(vr_canvas_measure_text(c, "Hello", &left) == 0);
  CHECK(left.width > 20 && left.width < 100);
  CHECK(left.actual_ascent > 10 && left.actual_ascent < 20); /* "H" and "l" reach about 0.7 em up */
  CHECK(vr_canvas_set_text_align(c, VR_ALIGN_CENTER) == 0);
  CHECK(vr_canvas_measure_text(c, "Hello", &centre) == 0);
  CHECK(fabs(centre.actual_left - (left.actual_left + left.width / 2)) < 1e-9);
  CHECK(vr_canvas_set_text_baseline(c, VR_BASELINE_TOP) == 0);
  CHECK(vr_canvas_measure_text(c, "Hello", &top) == 0);
  CHECK(fabs(top.font_ascent) < 1e-9);

  /* The text state is saved and restored with the canvas state. */
  CHECK(vr_canvas_save(c) == 0);
  CHECK(vr_canvas_set_font(c, def, 40) == 0);
  CHECK(vr_canvas_measure_text(c, "Hello", &big) == 0);
  CHECK(fabs(big.width - 2 * left.width) < 1e-6); /* the same font (the embedded one) at twice the size */
  CHECK(vr_canvas_restore(c) == 0);
  CHECK(vr_canvas_measure_text(c, "Hello", &big) == 0);
  CHECK(big.width == left.width && fabs(big.font_ascent) < 1e-9);

  /* Drawing: bad numbers draw nothing; a real call draws ink in the fill colour, inside its box. */
  vr_canvas_set_fill_rgba(c, 0, 0, 1, 1);
  CHECK(vr_canvas_fill_text(c, "Hello", NAN, 10) == 0);
  CHECK(vr_canvas_fill_text(c, "Hello", 80, INFINITY) == 0);
  CHECK(ink(img) == 0);
  CHECK(vr_canvas_fill_text(c, "Hello", 80, 10) == 0);
  CHECK(ink(img) > 255 * 40);
  CHECK(px(img, 80 - (int)(left.width / 2) - 2, 20, 3) == 0); /* left of the centred text */
  CHECK(px(img, 80, 8, 3) == 0);                              /* above the top baseline */
  CHECK(vr_canvas_stroke_text(c, "Hello", 80, 30) == 0);
  vr_font_destroy(def);
  vr_canvas_destroy(c);
  vr_image_destroy(img);
}
#endif

/* Flood fill: a ring drawn aliased splits the canvas; the fill stays on its side, 4-connected leaks through no
 * diagonal gap, boundary-defined fills up to the ring. */
static void test_flood_fill(void) {
  vr_image* img = NULL;
  vr_canvas* c = fresh(20, 20, &img);
  vr_canvas_set_antialias(c, VR_AA_NONE);
  vr_canvas_set_fill_rgba(c, 0, 0, 0, 1);
  vr_canvas_fill_rect(c, 5, 5, 10, 1);
  vr_canvas_fill_rect(c, 5, 14, 10, 1);
  vr_canvas_fill_rect(c, 5, 5, 1, 10);
  vr_canvas_fill_rect(c, 14, 5, 1, 10);
  /* inside the ring: 8 x 8 transparent pixels */
  CHECK(vr_canvas_flood_fill(c, 9, 9, 1, 0, 0, 1, 4, 0) == 64);
  CHECK(pixel_is(img, 6, 6, 255, 0, 0, 255, 0));
  CHECK(pixel_is(img, 2, 2, 0, 0, 0, 0, 0));
  CHECK(pixel_is(img, 5, 5, 0, 0, 0, 255, 0));
  /* outside: everything but the ring and its inside */
  CHECK(vr_canvas_flood_fill_to_boundary(c, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1, 8, 0) == 400 - 100);
  CHECK(pixel_is(img, 2, 2, 0, 0, 255, 255, 0));
  CHECK(pixel_is(img, 6, 6, 255, 0, 0, 255, 0));
  /* errors and ignored values */
  CHECK(vr_canvas_flood_fill(c, 0, 0, 1, 1, 1, 1, 6, 0) == -1 && error_mentions("connectivity"));
  CHECK(vr_canvas_flood_fill(c, 0, 0, 1, 1, 1, 1, 4, 2) == -1 && error_mentions("tolerance"));
  CHECK(vr_canvas_flood_fill(c, 0, 0, NAN, 1, 1, 1, 4, 0) == 0);
  CHECK(vr_canvas_flood_fill(c, -3, 50, 1, 1, 1, 1, 4, 0) == 0);
  CHECK(vr_canvas_flood_fill(NULL, 0, 0, 1, 1, 1, 1, 4, 0) == -1);
  vr_canvas_destroy(c);
  vr_image_destroy(img);
}

/* Triangles: two aliased triangles making a rectangle give fill_rect's pixels; with the z-buffer the nearer of two
 * overlapping triangles shows whatever the order; bad input is refused or skipped. */
static void test_triangles(void) {
  vr_image* img = NULL;
  vr_canvas* c = fresh(16, 12, &img);
  vr_canvas_set_antialias(c, VR_AA_NONE);
  const double quad[4 * 7] = {2, 2, 0, 1, 0, 0, 1, 10, 2, 0, 1, 0, 0, 1, 10, 8, 0, 1, 0, 0, 1, 2, 8, 0, 1, 0, 0, 1};
  const unsigned two[6] = {0, 1, 2, 0, 2, 3};
  CHECK(vr_canvas_draw_triangles(c, quad, 4, two, 2, 0, 0, 0) == 0);
  int inside = 1, outside = 1;
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 16; ++x) {
      const int in = x >= 2 && x < 10 && y >= 2 && y < 8;
      if (in) inside = inside && pixel_is(img, x, y, 255, 0, 0, 255, 0);
      else outside = outside && pixel_is(img, x, y, 0, 0, 0, 0, 0);
    }
  }
  CHECK(inside && outside);
  /* a far green triangle drawn after a near blue one over the same pixels: blue stays with the z-buffer */
  const double near_far[6 * 7] = {0, 0, 0.2, 0, 0, 1, 1, 16, 0, 0.2, 0, 0, 1, 1, 0, 12, 0.2, 0, 0, 1, 1,
                                  0, 0, 0.8, 0, 1, 0, 1, 16, 0, 0.8, 0, 1, 0, 1, 0, 12, 0.8, 0, 1, 0, 1};
  const unsigned pair[6] = {0, 1, 2, 3, 4, 5};
  CHECK(vr_canvas_draw_triangles(c, near_far, 6, pair, 2, 1, 1, 0) == 0);
  CHECK(pixel_is(img, 1, 1, 0, 0, 255, 255, 0));
  CHECK(vr_canvas_draw_triangles(c, near_far, 6, pair, 2, 1, 0, 0) == 0);
  CHECK(pixel_is(img, 1, 1, 0, 255, 0, 255, 0));
  /* errors and skipped triangles */
  CHECK(vr_canvas_draw_triangles(c, NULL, 3, two, 1, 0, 0, 0) == -1 && error_mentions("null"));
  const unsigned out_of_range[3] = {0, 1, 99};
  CHECK(vr_canvas_draw_triangles(c, quad, 4, out_of_range, 1, 0, 0, 0) == 0);
  CHECK(vr_canvas_draw_triangles(NULL, quad, 4, two, 2, 0, 0, 0) == -1);
  CHECK(vr_canvas_draw_triangles(c, NULL, 0, NULL, 0, 0, 0, 0) == 0);
  vr_canvas_destroy(c);
  vr_image_destroy(img);
}

int main(int argc, char** argv) {
  const char* work = argc > 1 ? argv[1] : ".";
  test_images(work);
  test_fill_and_rules();
  test_errors();
  test_state_clip_transform();
  test_composite_and_layers();
  test_paints_and_images();
  test_flood_fill();
  test_triangles();
#if VRASTER_WITH_TEXT
  test_text();
#endif
  printf("c_api_test: %d checks, %d failed\n", checks, failures);
  return failures == 0 ? 0 : 1;
}
