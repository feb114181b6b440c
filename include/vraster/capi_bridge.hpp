// vraster: the C++ side of the C API's handles, for libraries that extend the C API (the text library's
// vr_canvas_fill_text) and for C++ programs that mix vr_* handles with the C++ API.
#pragma once

#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <type_traits>

#include "vraster/canvas.hpp"
#include "vraster/error.hpp"
#include "vraster/image.hpp"
#include "vraster/vraster.h"

namespace vraster::capi {

/// State another library attaches to a canvas handle (the text library keeps its font, alignment and baseline in
/// one). Immutable once attached: it is shared between saved states, and changes replace it (set_extension), so
/// save / restore / begin_layer / end_layer keep it in step with the canvas state for free.
class Extension {
 public:
  virtual ~Extension() = default;
};

/// The canvas behind a handle (nullptr for a null handle).
Canvas* canvas_of(vr_canvas* c);
const Canvas* canvas_of(const vr_canvas* c);
/// The image behind a handle (nullptr for a null handle).
const Image* image_of(const vr_image* img);

/// The extension stored under `key` (any address unique to the caller) in the current state, or nullptr.
std::shared_ptr<const Extension> extension(const vr_canvas* c, const void* key);
/// Replaces it in the current state (saved states keep theirs).
void set_extension(vr_canvas* c, const void* key, std::shared_ptr<const Extension> value);

/// The int a C caller passed for an enum parameter. C allows any int there; reading it through the enum type in
/// C++ is undefined behaviour when it is not one of the enumerators, so every entry point reads its enums with
/// this, then checks the range.
template <class E>
int raw(const E& value) {
  static_assert(std::is_enum_v<E> && sizeof(E) == sizeof(int));
  int v;
  std::memcpy(&v, &value, sizeof v);
  return v;
}

/// Sets this thread's vr_last_error() message (kept in a fixed buffer: long messages are cut, nothing allocates).
void set_error(std::string_view message) noexcept;

/// Runs `body` and turns every exception into a message for vr_last_error(); returns body's value, or `failed`
/// when it threw. The one way calls cross from C into C++ (no exception ever escapes).
template <class R, class F>
R guard(R failed, F&& body) noexcept {
  try {
    return body();
  } catch (const Error& e) {
    set_error(e.what());
  } catch (const std::bad_alloc&) {
    set_error("out of memory");
  } catch (const std::exception& e) {
    set_error(e.what());
  } catch (...) {
    set_error("unknown error");
  }
  return failed;
}

}  // namespace vraster::capi
