// vraster_text C API: fonts and canvas text. The text state rides on the canvas handle as an extension
// (vraster/capi_bridge.hpp), so save / restore / layers keep it in step with the rest of the canvas state.
#include <cstdio>
#include <cstring>

#include "vraster/capi_bridge.hpp"
#include "vraster_text/canvas_text.hpp"
#include "vraster_text/vraster_text.h"

struct vr_font {
  std::shared_ptr<vraster::text::Font> font;
};

using namespace vraster;
using namespace vraster::text;
using vraster::capi::guard;
using vraster::capi::set_error;

namespace {

struct TextState final : capi::Extension {
  CanvasFont font;
};

const char kTextKey = 0;  // its address identifies the text library's extension

int fail(const char* function, const char* why) {
  char message[200];
  std::snprintf(message, sizeof message, "%s: %s", function, why);
  set_error(message);
  return -1;
}

// The canvas's text state (the default font at 10 px until one is set).
std::shared_ptr<const TextState> text_state(vr_canvas* c) {
  auto current = std::static_pointer_cast<const TextState>(capi::extension(c, &kTextKey));
  if (!current) {
    current = std::make_shared<const TextState>();
    capi::set_extension(c, &kTextKey, current);
  }
  return current;
}

// Changes a copy of the text state and puts it in place (saved states keep the old one).
template <class F>
int change_text_state(vr_canvas* c, const char* function, F&& change) {
  if (!c) return fail(function, "canvas is NULL");
  return guard(-1, [&] {
    auto next = std::make_shared<TextState>(*text_state(c));
    change(next->font);
    capi::set_extension(c, &kTextKey, std::move(next));
    return 0;
  });
}

// Runs a text drawing or measuring call on a present canvas and string.
template <class F>
int with_text(vr_canvas* c, const char* utf8, const char* function, F&& body) {
  if (!c) return fail(function, "canvas is NULL");
  if (!utf8) return fail(function, "text is NULL");
  return guard(-1, [&] {
    body(*capi::canvas_of(c), text_state(c)->font);
    return 0;
  });
}

}  // namespace

extern "C" {

vr_font* vr_font_load(const char* path) {
  if (!path) {
    fail("vr_font_load", "path is NULL");
    return nullptr;
  }
  return guard<vr_font*>(nullptr, [&] { return new vr_font{Font::load_file(path)}; });
}

vr_font* vr_font_load_memory(const void* data, size_t size) {
  if (!data && size > 0) {
    fail("vr_font_load_memory", "data is NULL");
    return nullptr;
  }
  return guard<vr_font*>(nullptr, [&] {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    return new vr_font{Font::load_memory(std::vector<std::uint8_t>(bytes, bytes + size))};
  });
}

vr_font* vr_font_load_default(void) {
  return guard<vr_font*>(nullptr, [] { return new vr_font{Font::load_default()}; });
}

void vr_font_destroy(vr_font* font) { delete font; }

int vr_canvas_set_font(vr_canvas* c, const vr_font* font, double size) {
  if (!(size > 0 && size <= kMaxFontSize)) return fail(__func__, "the size must be in (0, 4096] pixels");
  return change_text_state(c, __func__, [&](CanvasFont& f) {
    f.fonts = font ? FontList(font->font) : FontList::default_list();
    f.style.size = size;
  });
}

int vr_canvas_set_text_align(vr_canvas* c, vr_text_align align) {
  const int v = capi::raw(align);
  if (v < VR_ALIGN_START || v > VR_ALIGN_CENTER) return fail(__func__, "not a valid vr_text_align");
  return change_text_state(c, __func__, [&](CanvasFont& f) { f.align = static_cast<TextAlign>(v); });
}

int vr_canvas_set_text_baseline(vr_canvas* c, vr_text_baseline baseline) {
  const int v = capi::raw(baseline);
  if (v < VR_BASELINE_ALPHABETIC || v > VR_BASELINE_BOTTOM) return fail(__func__, "not a valid vr_text_baseline");
  return change_text_state(c, __func__, [&](CanvasFont& f) { f.baseline = static_cast<TextBaseline>(v); });
}

int vr_canvas_set_font_features(vr_canvas* c, const char* features) {
  return change_text_state(c, __func__, [&](CanvasFont& f) {
    const std::string list = features ? features : "";
    parse_features(list);  // throws, naming the item HarfBuzz rejects, before anything changes
    f.style.features = list;
  });
}

int vr_canvas_fill_text(vr_canvas* c, const char* utf8, double x, double y) {
  return with_text(c, utf8, __func__, [&](Canvas& canvas, const CanvasFont& f) { fill_text(canvas, f, utf8, x, y); });
}

int vr_canvas_stroke_text(vr_canvas* c, const char* utf8, double x, double y) {
  return with_text(c, utf8, __func__,
                   [&](Canvas& canvas, const CanvasFont& f) { stroke_text(canvas, f, utf8, x, y); });
}

int vr_canvas_measure_text(vr_canvas* c, const char* utf8, vr_text_metrics* out) {
  if (!out) return fail(__func__, "out is NULL");
  return with_text(c, utf8, __func__, [&](Canvas&, const CanvasFont& f) {
    const CanvasTextMetrics m = measure_text(f, utf8);
    *out = {m.width, m.actual_left, m.actual_right, m.actual_ascent, m.actual_descent, m.font_ascent,
            m.font_descent};
  });
}

}  // extern "C"
