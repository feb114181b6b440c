// vraster C API: the error message, images, and the bridge for C++ code.
#include <algorithm>
#include <cstdio>
#include <cstring>

#include "capi/handles.hpp"
#include "vraster/png.hpp"

namespace vraster::capi {
namespace {
thread_local char last_error[1024] = "";
}

void set_error(std::string_view message) noexcept {
  const std::size_t n = std::min(message.size(), sizeof last_error - 1);
  std::memcpy(last_error, message.data(), n);
  last_error[n] = '\0';
}

Canvas* canvas_of(vr_canvas* c) { return c ? &c->canvas : nullptr; }
const Canvas* canvas_of(const vr_canvas* c) { return c ? &c->canvas : nullptr; }
const Image* image_of(const vr_image* img) { return img ? img->image.get() : nullptr; }

std::shared_ptr<const Extension> extension(const vr_canvas* c, const void* key) {
  if (!c) return nullptr;
  for (const auto& [k, value] : c->state.extensions) {
    if (k == key) return value;
  }
  return nullptr;
}

void set_extension(vr_canvas* c, const void* key, std::shared_ptr<const Extension> value) {
  if (!c) return;
  for (auto& [k, slot] : c->state.extensions) {
    if (k == key) {
      slot = std::move(value);
      return;
    }
  }
  c->state.extensions.emplace_back(key, std::move(value));
}

}  // namespace vraster::capi

using vraster::capi::guard;
using vraster::capi::set_error;

namespace vraster::capi {

bool present(const void* handle, const char* function, const char* what) noexcept {
  if (handle) return true;
  char message[160];
  std::snprintf(message, sizeof message, "%s: %s is NULL", function, what);
  set_error(message);
  return false;
}

}  // namespace vraster::capi

using vraster::capi::present;

extern "C" {

const char* vr_last_error(void) { return vraster::capi::last_error; }
void vr_clear_error(void) { vraster::capi::last_error[0] = '\0'; }

vr_image* vr_image_create(int w, int h) {
  return guard<vr_image*>(nullptr, [&] {
    auto image = std::make_shared<vraster::Image>(w, h);  // throws for bad sizes; pixels start transparent
    return new vr_image{std::move(image)};
  });
}

vr_image* vr_image_read_png(const char* path) {
  return guard<vr_image*>(nullptr, [&]() -> vr_image* {
    if (!present(path, "vr_image_read_png", "path")) return nullptr;
    return new vr_image{std::make_shared<vraster::Image>(vraster::read_png(path))};
  });
}

int vr_image_write_png(const vr_image* img, const char* path) {
  return guard(-1, [&] {
    if (!present(img, "vr_image_write_png", "image") || !present(path, "vr_image_write_png", "path")) return -1;
    vraster::write_png(path, *img->image);
    return 0;
  });
}

int vr_image_width(const vr_image* img) { return present(img, "vr_image_width", "image") ? img->image->width : 0; }
int vr_image_height(const vr_image* img) {
  return present(img, "vr_image_height", "image") ? img->image->height : 0;
}

const unsigned char* vr_image_pixels(const vr_image* img, int* stride) {
  if (!present(img, "vr_image_pixels", "image")) return nullptr;
  if (stride) *stride = img->image->width * 4;
  return img->image->data.data();
}

unsigned char* vr_image_pixels_mutable(vr_image* img, int* stride) {
  if (!present(img, "vr_image_pixels_mutable", "image")) return nullptr;
  if (stride) *stride = img->image->width * 4;
  return img->image->data.data();
}

void vr_image_destroy(vr_image* img) { delete img; }

}  // extern "C"
