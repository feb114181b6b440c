/* vraster: the C API (C99; usable from C and from any FFI).
 *
 * Opaque handles over the C++ library (vraster::Image, vraster::Canvas, vraster::Paint). No exception crosses
 * this boundary. Every function that can fail says so by its return value (NULL, or an int that is negative)
 * and leaves a message for vr_last_error(). A message stays until the next failure on the same thread.
 *
 * Drawing calls follow the HTML canvas: a NaN or infinite argument makes the call do nothing; that is not a
 * failure (they return 0). A NULL handle, an enum value out of range, a size out of range or exhausted memory
 * are failures (-1).
 *
 * Colours are straight (not premultiplied) RGBA with channels in [0, 1] (values outside are clamped); images are
 * 8-bit RGBA, premultiplied. Transforms are given as SVG matrices (a, b, c, d, e, f):
 *   x' = a x + c y + e,   y' = b x + d y + f.
 *
 *   vr_image*  img = vr_image_create(200, 100);
 *   vr_canvas* c = vr_canvas_create(img);
 *   vr_canvas_set_fill_rgba(c, 0.9, 0.2, 0.1, 1);
 *   vr_canvas_fill_rect(c, 10, 10, 180, 80);
 *   vr_canvas_destroy(c);
 *   if (vr_image_write_png(img, "out.png") != 0) fprintf(stderr, "%s\n", vr_last_error());
 *   vr_image_destroy(img);
 */
#ifndef VRASTER_VRASTER_H
#define VRASTER_VRASTER_H

#include <stddef.h>

#if defined(__GNUC__)
#define VR_API __attribute__((visibility("default")))
#else
#define VR_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** An RGBA image, 8 bits a channel, premultiplied, rows stored top to bottom. */
typedef struct vr_image vr_image;
/** A drawing context over an image (the HTML Canvas 2D model). */
typedef struct vr_canvas vr_canvas;
/** A paint source: solid colour, gradient or image pattern. */
typedef struct vr_paint vr_paint;

/** Which points a path fills (w: the winding number of the point). */
typedef enum vr_fill_rule {
  VR_FILL_NONZERO = 0,     /**< w != 0 */
  VR_FILL_EVENODD = 1,     /**< w odd */
  VR_FILL_NONEXTERIOR = 2, /**< every point that cannot reach infinity without crossing the path */
  VR_FILL_POSITIVE = 3,    /**< w > 0 */
  VR_FILL_NEGATIVE = 4,    /**< w < 0 */
  VR_FILL_ABS_GEQ_2 = 5,   /**< |w| >= 2 */
  VR_FILL_RULE_MAX_ENUM = 0x7fffffff /**< (every enum has one: it keeps the type as wide as an int) */
} vr_fill_rule;

/** How coverage is computed. */
typedef enum vr_antialias {
  VR_AA_NONE = 0,     /**< one sample at the pixel centre */
  VR_AA_ANALYTIC = 1, /**< area coverage (exact unless edges cross inside a pixel); the default */
  VR_AA_EXACT = 2,    /**< true area coverage for every rule */
  VR_AA_SSAA_4 = 3,   /**< 4 x 4 regular samples per pixel (for comparison) */
  VR_AA_MSAA_16 = 4,  /**< 16 sparse samples per pixel (for comparison) */
  VR_ANTIALIAS_MAX_ENUM = 0x7fffffff
} vr_antialias;

typedef enum vr_line_cap {
  VR_CAP_BUTT = 0,
  VR_CAP_ROUND = 1,
  VR_CAP_SQUARE = 2,
  VR_LINE_CAP_MAX_ENUM = 0x7fffffff
} vr_line_cap;
typedef enum vr_line_join {
  VR_JOIN_MITER = 0,
  VR_JOIN_ROUND = 1,
  VR_JOIN_BEVEL = 2,
  VR_LINE_JOIN_MAX_ENUM = 0x7fffffff
} vr_line_join;

/** The HTML canvas globalCompositeOperation values (Porter-Duff, lighter, and the W3C blend modes). */
typedef enum vr_composite {
  VR_COMPOSITE_SOURCE_OVER = 0,
  VR_COMPOSITE_COPY,
  VR_COMPOSITE_SOURCE_IN,
  VR_COMPOSITE_SOURCE_OUT,
  VR_COMPOSITE_SOURCE_ATOP,
  VR_COMPOSITE_DESTINATION_OVER,
  VR_COMPOSITE_DESTINATION_IN,
  VR_COMPOSITE_DESTINATION_OUT,
  VR_COMPOSITE_DESTINATION_ATOP,
  VR_COMPOSITE_XOR,
  VR_COMPOSITE_LIGHTER,
  VR_COMPOSITE_CLEAR,
  VR_COMPOSITE_MULTIPLY,
  VR_COMPOSITE_SCREEN,
  VR_COMPOSITE_OVERLAY,
  VR_COMPOSITE_DARKEN,
  VR_COMPOSITE_LIGHTEN,
  VR_COMPOSITE_COLOR_DODGE,
  VR_COMPOSITE_COLOR_BURN,
  VR_COMPOSITE_HARD_LIGHT,
  VR_COMPOSITE_SOFT_LIGHT,
  VR_COMPOSITE_DIFFERENCE,
  VR_COMPOSITE_EXCLUSION,
  VR_COMPOSITE_HUE,
  VR_COMPOSITE_SATURATION,
  VR_COMPOSITE_COLOR,
  VR_COMPOSITE_LUMINOSITY,
  VR_COMPOSITE_MAX_ENUM = 0x7fffffff
} vr_composite;

/** What a gradient or pattern does outside its range or tile. VR_EXTEND_NONE is for patterns only. */
typedef enum vr_extend {
  VR_EXTEND_PAD = 0,
  VR_EXTEND_REPEAT = 1,
  VR_EXTEND_REFLECT = 2,
  VR_EXTEND_NONE = 3,
  VR_EXTEND_MAX_ENUM = 0x7fffffff
} vr_extend;
/** How images are sampled (patterns, draw_image). */
typedef enum vr_filter {
  VR_FILTER_NEAREST = 0,
  VR_FILTER_BILINEAR = 1,
  VR_FILTER_BICUBIC = 2,
  VR_FILTER_MAX_ENUM = 0x7fffffff
} vr_filter;
/** How a layer mask becomes coverage. */
typedef enum vr_mask_mode {
  VR_MASK_ALPHA = 0,
  VR_MASK_LUMINANCE = 1,
  VR_MASK_MODE_MAX_ENUM = 0x7fffffff
} vr_mask_mode;

/* ---- errors ---- */

/** The message of the last failed call on this thread ("" when none failed). Valid until the next failure. */
VR_API const char* vr_last_error(void);
/** Forgets the last message (vr_last_error() returns "" afterwards). */
VR_API void vr_clear_error(void);

/* ---- images ---- */

/** A transparent w x h image; NULL when a side is <= 0 or too large (32768 px a side, 2^28 pixels). */
VR_API vr_image* vr_image_create(int w, int h);
/** Reads any PNG as 8-bit premultiplied RGBA; NULL when the file is missing or malformed. */
VR_API vr_image* vr_image_read_png(const char* path);
/** Writes an 8-bit RGBA PNG (whole or not at all); 0 on success, -1 on failure. */
VR_API int vr_image_write_png(const vr_image* img, const char* path);
/** Width and height in pixels (0 for a NULL image, which is a failure). */
VR_API int vr_image_width(const vr_image* img);
VR_API int vr_image_height(const vr_image* img);
/** The pixels (premultiplied RGBA); *stride (may be NULL) receives the bytes between rows. */
VR_API const unsigned char* vr_image_pixels(const vr_image* img, int* stride);
/** The same pixels for writing (they must stay premultiplied: each colour channel <= alpha). */
VR_API unsigned char* vr_image_pixels_mutable(vr_image* img, int* stride);
/** Frees an image (NULL: nothing). A canvas drawing on it keeps it alive until the canvas is destroyed. */
VR_API void vr_image_destroy(vr_image* img);

/* ---- canvas ---- */

/** A canvas drawing onto `target` (which it keeps alive); NULL on failure. */
VR_API vr_canvas* vr_canvas_create(vr_image* target);
VR_API void vr_canvas_destroy(vr_canvas* c);

/* State stack: transform, clip, paints, line style, alpha, operator, antialiasing, smoothing, shadow. */
VR_API int vr_canvas_save(vr_canvas* c);
/** Pops the state; without a matching save it does nothing. */
VR_API int vr_canvas_restore(vr_canvas* c);

/* Transform: each call applies to coordinates before the transform already there (as the canvas does). */
VR_API int vr_canvas_translate(vr_canvas* c, double x, double y);
VR_API int vr_canvas_scale(vr_canvas* c, double sx, double sy);
VR_API int vr_canvas_rotate(vr_canvas* c, double radians);
VR_API int vr_canvas_transform(vr_canvas* canvas, double a, double b, double c, double d, double e, double f);
VR_API int vr_canvas_set_transform(vr_canvas* canvas, double a, double b, double c, double d, double e, double f);
VR_API int vr_canvas_reset_transform(vr_canvas* c);
/** Writes the current transform to m[0..5] as (a, b, c, d, e, f). */
VR_API int vr_canvas_get_transform(const vr_canvas* c, double m[6]);

/* The current path (points are mapped by the transform current when they are added). */
VR_API int vr_canvas_begin_path(vr_canvas* c);
VR_API int vr_canvas_move_to(vr_canvas* c, double x, double y);
VR_API int vr_canvas_line_to(vr_canvas* c, double x, double y);
VR_API int vr_canvas_quad_to(vr_canvas* c, double cx, double cy, double x, double y);
VR_API int vr_canvas_cubic_to(vr_canvas* c, double x1, double y1, double x2, double y2, double x, double y);
/** Circular arc around (cx, cy) from angle a0 to a1 (radians), clockwise on screen unless ccw != 0. */
VR_API int vr_canvas_arc(vr_canvas* c, double cx, double cy, double r, double a0, double a1, int ccw);
/** The canvas arcTo: a line towards (x1, y1), rounded with radius r into the line towards (x2, y2). */
VR_API int vr_canvas_arc_to(vr_canvas* c, double x1, double y1, double x2, double y2, double r);
VR_API int vr_canvas_ellipse(vr_canvas* c, double cx, double cy, double rx, double ry, double rotation, double a0,
                             double a1, int ccw);
VR_API int vr_canvas_rect(vr_canvas* c, double x, double y, double w, double h);
/** Rectangle with every corner rounded by `radius`. */
VR_API int vr_canvas_round_rect(vr_canvas* c, double x, double y, double w, double h, double radius);
VR_API int vr_canvas_close_path(vr_canvas* c);

/* Drawing. */
VR_API int vr_canvas_fill(vr_canvas* c, vr_fill_rule rule);
VR_API int vr_canvas_stroke(vr_canvas* c);
/** Intersects the clip with the current path under `rule` (antialiased as the current mode says). */
VR_API int vr_canvas_clip(vr_canvas* c, vr_fill_rule rule);
VR_API int vr_canvas_fill_rect(vr_canvas* c, double x, double y, double w, double h);
VR_API int vr_canvas_stroke_rect(vr_canvas* c, double x, double y, double w, double h);
/** Makes the rectangle (inside the clip) transparent. */
VR_API int vr_canvas_clear_rect(vr_canvas* c, double x, double y, double w, double h);
/** Draws `img` scaled into the rectangle (dx, dy, dw, dh) of user space. */
VR_API int vr_canvas_draw_image(vr_canvas* c, const vr_image* img, double dx, double dy, double dw, double dh);
/** Draws the source rectangle (sx, sy, sw, sh) of `img` into the destination rectangle. */
VR_API int vr_canvas_draw_image_part(vr_canvas* c, const vr_image* img, double sx, double sy, double sw, double sh,
                                     double dx, double dy, double dw, double dh);

/* Style. */
VR_API int vr_canvas_set_fill_rgba(vr_canvas* c, double r, double g, double b, double a);
VR_API int vr_canvas_set_stroke_rgba(vr_canvas* c, double r, double g, double b, double a);
/** Uses a copy of `p` (the paint may be changed or destroyed afterwards). */
VR_API int vr_canvas_set_fill_paint(vr_canvas* c, const vr_paint* p);
VR_API int vr_canvas_set_stroke_paint(vr_canvas* c, const vr_paint* p);
/** <= 0 or non-finite: ignored. */
VR_API int vr_canvas_set_line_width(vr_canvas* c, double width);
VR_API int vr_canvas_set_line_cap(vr_canvas* c, vr_line_cap cap);
VR_API int vr_canvas_set_line_join(vr_canvas* c, vr_line_join join);
/** <= 0 or non-finite: ignored. */
VR_API int vr_canvas_set_miter_limit(vr_canvas* c, double limit);
/** Dash lengths (n of them; n == 0: solid) and the dash offset. A negative or non-finite length: the dashes are
 *  left as they were; a non-finite offset: the offset is. */
VR_API int vr_canvas_set_line_dash(vr_canvas* c, const double* dashes, int n, double offset);
/** Outside [0, 1] or non-finite: ignored. */
VR_API int vr_canvas_set_global_alpha(vr_canvas* c, double alpha);
VR_API int vr_canvas_set_composite(vr_canvas* c, vr_composite op);
VR_API int vr_canvas_set_antialias(vr_canvas* c, vr_antialias aa);
/** Flattening tolerance in device pixels (default 0.1); <= 0 or non-finite: ignored. */
VR_API int vr_canvas_set_tolerance(vr_canvas* c, double device_pixels);
/** draw_image smoothing: off samples nearest pixels; on uses `filter`. */
VR_API int vr_canvas_set_image_smoothing(vr_canvas* c, int on, vr_filter filter);
/** A drop shadow under each shape (offsets in device pixels, blur as the canvas shadowBlur); alpha 0: none. */
VR_API int vr_canvas_set_shadow(vr_canvas* c, double r, double g, double b, double a, double offset_x,
                                double offset_y, double blur);

/* Layers. */
/** Starts a layer, composited at vr_canvas_end_layer with `opacity` and the operator current now. */
VR_API int vr_canvas_begin_layer(vr_canvas* c, float opacity);
/** Starts a layer composited with `opacity`, `op`, and, when `mask` is not NULL, masked by it (its top-left pixel
 *  at device pixel (mask_x, mask_y); the mask is copied). */
VR_API int vr_canvas_begin_layer_masked(vr_canvas* c, float opacity, vr_composite op, const vr_image* mask, int mask_x,
                                        int mask_y, vr_mask_mode mode);
/** Ends the innermost layer; -1 when none is open. */
VR_API int vr_canvas_end_layer(vr_canvas* c);

/* Pixels and hit testing. */
/** A new image with the premultiplied pixels of the rectangle (outside the canvas: transparent); NULL on failure. */
VR_API vr_image* vr_canvas_get_pixels(const vr_canvas* c, int x, int y, int w, int h);
/** Writes the pixels of `img` at (x, y), ignoring transform, clip, alpha and operator. */
VR_API int vr_canvas_put_pixels(vr_canvas* c, const vr_image* img, int x, int y);
/** 1 when (x, y) (user space) is inside the current path under `rule`, 0 when not, -1 on failure. */
VR_API int vr_canvas_is_point_in_path(const vr_canvas* c, double x, double y, vr_fill_rule rule);
/** 1 when (x, y) is inside the stroke of the current path, 0 when not, -1 on failure. */
VR_API int vr_canvas_is_point_in_stroke(const vr_canvas* c, double x, double y);
/** FXAA over the whole target (a post-filter: call it when the drawing is done). */
VR_API int vr_canvas_apply_fxaa(vr_canvas* c);
/** Seed (flood) fill of the target from device pixel (x, y), by scanline spans (no recursion): the region of
 *  pixels whose premultiplied channels are all within `tolerance` (0..1) of the seed pixel's, 4- or 8-connected
 *  (`connectivity` 4 or 8), gets the colour (r, g, b, a: straight, 0..1), replacing it (transform, clip, alpha
 *  and operator do not apply). Returns the number of pixels written (0 for a seed outside the canvas or a
 *  non-finite colour), -1 on failure (connectivity not 4 or 8, tolerance outside [0, 1]). */
VR_API long long vr_canvas_flood_fill(vr_canvas* c, int x, int y, double r, double g, double b, double a,
                                      int connectivity, double tolerance);
/** The boundary-defined form: the region grows from (x, y) up to pixels within `tolerance` of the boundary colour
 *  (br, bg, bb, ba: straight, 0..1). Same return values. */
VR_API long long vr_canvas_flood_fill_to_boundary(vr_canvas* c, int x, int y, double r, double g, double b, double a,
                                                  double br, double bg, double bb, double ba, int connectivity,
                                                  double tolerance);
/** Draws a triangle mesh. `vertices` holds `vertex_count` vertices of 7 doubles each: x, y (user space, mapped by
 *  the transform), depth (smaller is nearer), r, g, b, a (straight colour, 0..1); `indices` holds `triangle_count`
 *  triples of vertex indices. `gouraud` 1 interpolates the colours, 0 gives each triangle its mean colour;
 *  `zbuffer` 1 resolves hidden surfaces per pixel (a buffer of the call's own), 0 draws in the order given;
 *  `antialias` 1 gives analytic coverage without seams between triangles. Drawn through the clip with the operator;
 *  the global alpha multiplies every colour's alpha. Triangles with a non-finite number or an index out of range are
 *  skipped. Returns 0, or -1 on failure (a null array with a non-zero count, more than 2^22 vertices or 2^23
 *  triangles). */
VR_API int vr_canvas_draw_triangles(vr_canvas* c, const double* vertices, size_t vertex_count, const unsigned* indices,
                                    size_t triangle_count, int gouraud, int zbuffer, int antialias);

/* ---- composite operator names ---- */

/** Parses a CSS name ("source-over", "multiply", "color-dodge", ...) into *out; 0 on success, -1 when unknown. */
VR_API int vr_composite_from_name(const char* css_name, vr_composite* out);
/** The CSS name of an operator ("" for a value out of range). */
VR_API const char* vr_composite_name(vr_composite op);

/* ---- paints ----
 * Geometry is in paint space; vr_paint_set_transform maps paint space to user space (CanvasPattern.setTransform,
 * SVG gradientTransform); user space is the canvas transform at the time of the fill or stroke. Constructors
 * return NULL for non-finite numbers or negative radii. */

VR_API vr_paint* vr_paint_solid(double r, double g, double b, double a);
/** Linear gradient: offset 0 at (x0, y0), 1 at (x1, y1). */
VR_API vr_paint* vr_paint_linear(double x0, double y0, double x1, double y1);
/** Two-circle radial gradient (createRadialGradient): offset 0 on the circle (x0, y0, r0), 1 on (x1, y1, r1). */
VR_API vr_paint* vr_paint_radial(double x0, double y0, double r0, double x1, double y1, double r1);
/** Conic gradient around (x, y), offset 0 at `angle` radians from +x, clockwise on screen. */
VR_API vr_paint* vr_paint_conic(double angle, double x, double y);
/** Image pattern of a copy of `img`, its top-left corner at the paint-space origin; repeats in x and y. */
VR_API vr_paint* vr_paint_pattern(const vr_image* img);
/** Adds a stop (straight colour); -1 for an offset outside [0, 1], a non-finite value or a paint that is not a
 *  gradient. Equal offsets make a hard step. */
VR_API int vr_paint_add_stop(vr_paint* p, double offset, double r, double g, double b, double a);
VR_API int vr_paint_set_extend(vr_paint* p, vr_extend extend);
/** Patterns: x and y on their own. */
VR_API int vr_paint_set_extend_xy(vr_paint* p, vr_extend x, vr_extend y);
VR_API int vr_paint_set_filter(vr_paint* p, vr_filter filter);
/** Maps paint space to user space; -1 for non-finite values. A singular matrix makes the paint draw nothing. */
VR_API int vr_paint_set_transform(vr_paint* p, double a, double b, double c, double d, double e, double f);
/** Ordered dithering of gradients on 8-bit targets (off by default). */
VR_API int vr_paint_set_dither(vr_paint* p, int on);
VR_API void vr_paint_destroy(vr_paint* p);

#ifdef __cplusplus
}
#endif

#endif /* VRASTER_VRASTER_H */
