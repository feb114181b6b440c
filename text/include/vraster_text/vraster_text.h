/* vraster_text: text on a vr_canvas from C (C99; link vraster_text, pkg-config vraster-text).
 *
 * The font, size, alignment and baseline are part of the canvas state (saved and restored with it, as on the
 * HTML canvas); the default is the embedded Noto Sans at 10 px, alignment start, alphabetic baseline. Text is
 * shaped with HarfBuzz and its glyph outlines are filled or stroked through the canvas (its transform, paint,
 * clip, operator and layers). Errors as in vraster/vraster.h: -1 or NULL, and vr_last_error().
 *
 *   vr_font* font = vr_font_load("DejaVuSans.ttf");          (or NULL for the embedded default)
 *   vr_canvas_set_font(c, font, 24);
 *   vr_canvas_set_text_align(c, VR_ALIGN_CENTER);
 *   vr_canvas_fill_text(c, "Hello", 100, 50);
 *   vr_font_destroy(font);                                   (the canvas keeps what it uses)
 */
#ifndef VRASTER_TEXT_VRASTER_TEXT_H
#define VRASTER_TEXT_VRASTER_TEXT_H

#include <stddef.h>

#include "vraster/vraster.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A font face (FreeType). Use one font from one thread at a time. */
typedef struct vr_font vr_font;

/** canvas textAlign: start and end follow the text direction (left-to-right unless the text says otherwise). */
typedef enum vr_text_align {
  VR_ALIGN_START = 0,
  VR_ALIGN_END = 1,
  VR_ALIGN_LEFT = 2,
  VR_ALIGN_RIGHT = 3,
  VR_ALIGN_CENTER = 4,
  VR_TEXT_ALIGN_MAX_ENUM = 0x7fffffff
} vr_text_align;

/** canvas textBaseline: which line of the text the y coordinate is on. */
typedef enum vr_text_baseline {
  VR_BASELINE_ALPHABETIC = 0,
  VR_BASELINE_TOP = 1,
  VR_BASELINE_HANGING = 2,
  VR_BASELINE_MIDDLE = 3,
  VR_BASELINE_IDEOGRAPHIC = 4,
  VR_BASELINE_BOTTOM = 5,
  VR_TEXT_BASELINE_MAX_ENUM = 0x7fffffff
} vr_text_baseline;

/** canvas TextMetrics, in user-space pixels from the anchor point (ascents count upwards). */
typedef struct vr_text_metrics {
  double width;          /**< advance width */
  double actual_left;    /**< anchor to the ink's left edge (positive: to the left) */
  double actual_right;   /**< anchor to the ink's right edge */
  double actual_ascent;  /**< anchor to the ink's top (positive: above) */
  double actual_descent; /**< anchor to the ink's bottom (positive: below) */
  double font_ascent;    /**< anchor to the font's ascender line */
  double font_descent;   /**< anchor to the font's descender line */
} vr_text_metrics;

/** Loads face 0 of a font file (.ttf, .otf, .ttc); NULL when it is missing or not a font. */
VR_API vr_font* vr_font_load(const char* path);
/** Loads a font from bytes (copied); NULL when they are not a font. */
VR_API vr_font* vr_font_load_memory(const void* data, size_t size);
/** The embedded default font (Noto Sans Regular). */
VR_API vr_font* vr_font_load_default(void);
VR_API void vr_font_destroy(vr_font* font);

/** Sets the font (NULL: the embedded default) and its size in pixels (0 < size <= 4096, else -1). */
VR_API int vr_canvas_set_font(vr_canvas* c, const vr_font* font, double size);
VR_API int vr_canvas_set_text_align(vr_canvas* c, vr_text_align align);
VR_API int vr_canvas_set_text_baseline(vr_canvas* c, vr_text_baseline baseline);
/** HarfBuzz features, e.g. "liga=0,kern" ("" or NULL: the font's defaults); -1 for a list HarfBuzz rejects. */
VR_API int vr_canvas_set_font_features(vr_canvas* c, const char* features);

/** Fills UTF-8 text with its anchor at (x, y) (one line: line breaks count as spaces). */
VR_API int vr_canvas_fill_text(vr_canvas* c, const char* utf8, double x, double y);
/** Strokes the glyph outlines with the stroke paint and line style. */
VR_API int vr_canvas_stroke_text(vr_canvas* c, const char* utf8, double x, double y);
/** Measures text with the current font, size, alignment and baseline. */
VR_API int vr_canvas_measure_text(vr_canvas* c, const char* utf8, vr_text_metrics* out);

#ifdef __cplusplus
}
#endif

#endif /* VRASTER_TEXT_VRASTER_TEXT_H */
