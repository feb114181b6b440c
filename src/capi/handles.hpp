// vraster C API: what the opaque handles hold.
#pragma once

#include <cmath>

#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

#include "vraster/canvas.hpp"
#include "vraster/capi_bridge.hpp"
#include "vraster/composite.hpp"
#include "vraster/image.hpp"
#include "vraster/paint.hpp"

/// Shared, so that a canvas keeps its target alive after vr_image_destroy (no dangling pointer from C).
struct vr_image {
  std::shared_ptr<vraster::Image> image;
};

struct vr_paint {
  vraster::Paint paint;
};

/// What the C API keeps beside the canvas's own state stack, in step with it: the composite operator (which
/// vr_canvas_begin_layer needs and the canvas does not report) and extensions attached by other libraries.
struct vr_mirrored_state {
  vraster::CompositeOp op = vraster::CompositeOp::SourceOver;
  std::vector<std::pair<const void*, std::shared_ptr<const vraster::capi::Extension>>> extensions;
};

struct vr_canvas {
  std::shared_ptr<vraster::Image> target;
  vraster::Canvas canvas;
  vr_mirrored_state state;
  std::vector<vr_mirrored_state> saved;  // one per canvas save() (begin_layer saves too)
  std::vector<std::size_t> layer_floors;  // saved.size() just after each open layer's begin

  explicit vr_canvas(std::shared_ptr<vraster::Image> image) : target(std::move(image)), canvas(*target) {}
};

namespace vraster::capi {
/// Whether every value is finite (bad numbers make canvas calls do nothing, paint constructors fail).
inline bool finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

/// Reports a null handle or pointer (named with the function that got it); true when it is not null.
bool present(const void* handle, const char* function, const char* what) noexcept;
}  // namespace vraster::capi
