// The compositor: coverage spans and rows -> shaded paint -> operator -> clip -> an ImageView.
//
// Where each "only what a draw call needs" decision is taken (docs/design.md):
//   set():   invisible paint or zero global alpha with a bounded operator -> draws_nothing(), every call returns;
//            the paint is prepared once (solid colour premultiplied, gradient tables, inverse transforms).
//   span():  at full coverage, an opaque paint with source-over, or any paint with copy, replaces the target:
//            a constant colour is stored, other paints are shaded straight into the target (no blend, no read);
//            constant colours are never shaded into a buffer (the run loop reads one colour);
//   run loop (blend.hpp): bounded operators skip pixels with zero coverage, clip or source alpha.
//   clip levels arrive quantized (the canvas's mask, in the target's channel type): no conversion per pixel.
#include <algorithm>
#include <cstring>
#include <vector>

#include "blend.hpp"
#include "shade.hpp"
#include "vraster/composite.hpp"

namespace vraster {
namespace detail {

// The loops below are compiled for AVX2 and for any x86-64 and picked at load time.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VRASTER_PAINT_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define VRASTER_PAINT_CLONES
#endif

/// An opaque colour replacing n pixels: a plain store loop (memset-like), 32 bytes at a time in the AVX2 clone.
VRASTER_PAINT_CLONES void store8(std::uint32_t* px, int n, std::uint32_t c) {
  const int head = to_aligned32(px, n);
  for (int i = 0; i < head; ++i) px[i] = c;
  for (int i = head; i < n; ++i) px[i] = c;
}

/// One colour, one coverage for the whole run.
VRASTER_PAINT_CLONES void over8_constant_portable(std::uint32_t* px, int n, std::uint32_t s) {
  const std::uint32_t inv = 255u - (s >> 24);
  const int head = to_aligned32(px, n);
  for (int i = 0; i < head; ++i) px[i] = s + scale8(px[i], inv);
  for (int i = head; i < n; ++i) px[i] = s + scale8(px[i], inv);
}

VRASTER_PAINT_CLONES void over8_solid_portable(std::uint32_t* px, int n, const float* coverage, float scale,
                                               std::uint32_t c) {
  for (int i = 0; i < n; ++i) px[i] = over8(scale8(c, quantize8(coverage[i] * scale)), px[i]);
}

Over8ConstantFn over8_constant_for_cpu() {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (cpu_has_avx512bw()) return &over8_constant_avx512;
  if (cpu_has_avx2()) return &over8_constant_avx2;
#endif
  return &over8_constant_portable;
}

Over8SolidFn over8_solid_for_cpu() {
#ifdef VRASTER_HAVE_AVX2_KERNELS
  if (cpu_has_avx512bw()) return &over8_solid_avx512;
  if (cpu_has_avx2()) return &over8_solid_avx2;
#endif
  return &over8_solid_portable;
}

void over8_constant(std::uint32_t* px, int n, std::uint32_t s) { over8_constant_for_cpu()(px, n, s); }

void over8_solid(std::uint32_t* px, int n, const float* coverage, float scale, std::uint32_t c) {
  over8_solid_for_cpu()(px, n, coverage, scale, c);
}

/// A row of colours scaled by one coverage k.
VRASTER_PAINT_CLONES void over8_row(std::uint32_t* px, const std::uint32_t* src, int n, std::uint32_t k) {
  if (k == 255) {
    for (int i = 0; i < n; ++i) px[i] = over8(src[i], px[i]);
  } else {
    for (int i = 0; i < n; ++i) px[i] = over8(scale8(src[i], k), px[i]);
  }
}

/// Colours (src_step 0: one colour) scaled by per-pixel coverage x scale, optionally lerped by a clip. Each case
/// is its own loop so that the compiler vectorises it (a run-time source step would make every load a gather).
VRASTER_PAINT_CLONES void over8_masked(std::uint32_t* px, const std::uint32_t* src, int src_step,
                                       const float* coverage, float scale, const std::uint8_t* clip, int n) {
  const std::uint32_t k = quantize8(scale);
  if (src_step == 0) {
    const std::uint32_t c = src[0];
    // With a clip (without one, composite_run calls over8_constant or over8_solid).
    if (coverage == nullptr) {
      const std::uint32_t s = scale8(c, k);
      for (int i = 0; i < n; ++i) px[i] = lerp8(px[i], over8(s, px[i]), clip[i]);
    } else {
      for (int i = 0; i < n; ++i) {
        px[i] = lerp8(px[i], over8(scale8(c, quantize8(coverage[i] * scale)), px[i]), clip[i]);
      }
    }
  } else if (clip == nullptr) {
    for (int i = 0; i < n; ++i) px[i] = over8(scale8(src[i], quantize8(coverage[i] * scale)), px[i]);
  } else if (coverage == nullptr) {
    for (int i = 0; i < n; ++i) px[i] = lerp8(px[i], over8(scale8(src[i], k), px[i]), clip[i]);
  } else {
    for (int i = 0; i < n; ++i) {
      px[i] = lerp8(px[i], over8(scale8(src[i], quantize8(coverage[i] * scale)), px[i]), clip[i]);
    }
  }
}


template <class T>
CompositeRunFn<T> composite_run_for(CompositeOp op) {
  switch (op) {
#define VRASTER_OP(name) \
  case CompositeOp::name: return &composite_run<T, CompositeOp::name>;
    VRASTER_OP(SourceOver) VRASTER_OP(Copy) VRASTER_OP(SourceIn) VRASTER_OP(SourceOut) VRASTER_OP(SourceAtop)
    VRASTER_OP(DestinationOver) VRASTER_OP(DestinationIn) VRASTER_OP(DestinationOut) VRASTER_OP(DestinationAtop)
    VRASTER_OP(Xor) VRASTER_OP(Lighter) VRASTER_OP(Clear)
    VRASTER_OP(Multiply) VRASTER_OP(Screen) VRASTER_OP(Overlay) VRASTER_OP(Darken) VRASTER_OP(Lighten)
    VRASTER_OP(ColorDodge) VRASTER_OP(ColorBurn) VRASTER_OP(HardLight) VRASTER_OP(SoftLight)
    VRASTER_OP(Difference) VRASTER_OP(Exclusion) VRASTER_OP(Hue) VRASTER_OP(Saturation) VRASTER_OP(Color)
    VRASTER_OP(Luminosity)
#undef VRASTER_OP
  }
  return &composite_run<T, CompositeOp::SourceOver>;
}

template CompositeRunFn<std::uint8_t> composite_run_for<std::uint8_t>(CompositeOp);
template CompositeRunFn<std::uint16_t> composite_run_for<std::uint16_t>(CompositeOp);

}  // namespace detail

template <class T>
void blend_row(CompositeOp op, T* dst, const T* src, const float* coverage, const std::type_identity_t<T>* clip,
               int count) {
  if (count <= 0) return;
  detail::composite_run_for<T>(op)(dst, src, 4, coverage, 1.f, clip, count);
}

template void blend_row<std::uint8_t>(CompositeOp, std::uint8_t*, const std::uint8_t*, const float*,
                                      const std::uint8_t*, int);
template void blend_row<std::uint16_t>(CompositeOp, std::uint16_t*, const std::uint16_t*, const float*,
                                       const std::uint16_t*, int);

template <class T>
void blend_row_alpha(CompositeOp op, T* dst, const T* src, float alpha, const std::type_identity_t<T>* clip,
                     int count) {
  if (count <= 0) return;
  detail::composite_run_for<T>(op)(dst, src, 4, nullptr, alpha, clip, count);
}

template void blend_row_alpha<std::uint8_t>(CompositeOp, std::uint8_t*, const std::uint8_t*, float,
                                            const std::uint8_t*, int);
template void blend_row_alpha<std::uint16_t>(CompositeOp, std::uint16_t*, const std::uint16_t*, float,
                                             const std::uint16_t*, int);

template <class T>
struct Compositor<T>::State {
  ImageView<T> view;
  CompositeOp op = CompositeOp::SourceOver;
  float alpha = 1;
  bool nothing = true;
  bool solid_over = false;  // constant colour, source-over: the store fast path applies
  detail::Shader<T> shader;
  detail::CompositeRunFn<T> run = nullptr;
  std::vector<T> src;  // one shaded row, grown as needed, kept across draw calls

  // Clips [x0, x1) of row y to the view; false when nothing is left. `skip` is how many pixels were cut on the left.
  bool clip_to_view(int y, int& x0, int& x1, int& skip) const {
    if (y < view.y0 || y >= view.y0 + view.height) return false;
    const int lo = std::max(x0, view.x0), hi = std::min(x1, view.x0 + view.width);
    if (lo >= hi) return false;
    skip = lo - x0;
    x0 = lo;
    x1 = hi;
    return true;
  }

  const T* shade(int y, int x0, int n) {
    if (shader.is_constant()) return shader.color();
    if (src.size() < static_cast<std::size_t>(n) * 4) src.resize(static_cast<std::size_t>(n) * 4);
    shader.shade(y, x0, n, src.data());
    return src.data();
  }
};

template <class T>
Compositor<T>::Compositor() : state_(std::make_unique<State>()) {}
template <class T>
Compositor<T>::~Compositor() = default;
template <class T>
Compositor<T>::Compositor(Compositor&&) noexcept = default;
template <class T>
Compositor<T>& Compositor<T>::operator=(Compositor&&) noexcept = default;

template <class T>
void Compositor<T>::set(ImageView<T> target, const Paint& paint, const Affine& user_to_device, CompositeOp op,
                        float global_alpha) {
  State& s = *state_;
  s.view = target;
  s.op = op;
  s.alpha = std::isfinite(global_alpha) ? std::clamp(global_alpha, 0.f, 1.f) : 0.f;
  // An invisible paint leaves the shader a transparent constant: unbounded operators still clear with it.
  const bool visible = s.shader.prepare(paint, user_to_device);
  const bool empty_view = target.pixels == nullptr || target.width <= 0 || target.height <= 0;
  s.nothing = empty_view || (is_bounded(op) && (!visible || s.alpha <= 0));
  s.solid_over = op == CompositeOp::SourceOver && s.shader.is_constant();
  s.run = detail::composite_run_for<T>(op);
}

template <class T>
void Compositor<T>::expect(int y0, int y1, int x0, int x1) {
  if (!state_->nothing) detail::prefetch_pixels(state_->view, y0, y1, x0, x1);
}

template <class T>
bool Compositor<T>::takes_concurrent_rows() const {
  return state_->shader.is_constant();
}

template <class T>
bool Compositor<T>::solid_over8(SolidOver8& target) const {
  const State& s = *state_;
  if constexpr (sizeof(T) == 1) {
    // row() is then over8_solid(coverage, scale 1, the colour), which the rasterizer's blend reproduces.
    if (s.nothing || !s.solid_over || s.alpha < 1) return false;
    std::uint32_t packed;
    std::memcpy(&packed, s.shader.color(), 4);
    if (packed >> 24 == 0) return false;
    target = {s.view.pixels, s.view.stride, packed, s.view.x0, s.view.y0, s.view.width, s.view.height};
    return true;
  } else {
    return false;
  }
}

template <class T>
bool Compositor<T>::draws_nothing() const {
  return state_->nothing;
}

template <class T>
void Compositor<T>::span(int y, int x0, int x1, float coverage) {
  State& s = *state_;
  int skip = 0;
  if (s.nothing || !s.clip_to_view(y, x0, x1, skip)) return;
  const int n = x1 - x0;
  T* dst = s.view.pixel(x0, y);
  const bool full = coverage >= 1 && s.alpha >= 1;
  if (full && s.shader.is_constant() && (s.op == CompositeOp::Copy || (s.solid_over && s.shader.is_opaque()))) {
    // A constant colour that replaces the destination: a store.
    const T* c = s.shader.color();
    if constexpr (sizeof(T) == 1) {
      std::uint32_t packed;
      std::memcpy(&packed, c, 4);
      auto* px = reinterpret_cast<std::uint32_t*>(static_cast<void*>(dst));
      detail::store8(px, n, packed);
    } else {
      for (int i = 0; i < n; ++i) std::memcpy(dst + 4 * i, c, 4 * sizeof(T));
    }
    return;
  }
  if (full && !s.shader.is_constant() &&
      (s.op == CompositeOp::Copy || (s.op == CompositeOp::SourceOver && s.shader.is_opaque()))) {
    s.shader.shade(y, x0, n, dst);  // opaque paint that replaces the destination: shaded straight into it
    return;
  }
  const T* src = s.shade(y, x0, n);
  s.run(dst, src, s.shader.is_constant() ? 0 : 4, nullptr, coverage * s.alpha, nullptr, n);
}

template <class T>
void Compositor<T>::span(int y, int x0, int x1, float coverage, const T* clip) {
  if (clip == nullptr) {
    span(y, x0, x1, coverage);
    return;
  }
  State& s = *state_;
  int skip = 0;
  if (s.nothing || !s.clip_to_view(y, x0, x1, skip)) return;
  const int n = x1 - x0;
  const T* src = s.shade(y, x0, n);
  s.run(s.view.pixel(x0, y), src, s.shader.is_constant() ? 0 : 4, nullptr, coverage * s.alpha, clip + skip, n);
}

template <class T>
void Compositor<T>::row(int y, int x0, int x1, const float* coverage) {
  row(y, x0, x1, coverage, static_cast<const T*>(nullptr));
}

template <class T>
void Compositor<T>::rows(const CoverageRow* rows, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    row(rows[i].y, rows[i].x0, rows[i].x1, rows[i].coverage, static_cast<const T*>(nullptr));
  }
}

template <class T>
void Compositor<T>::row(int y, int x0, int x1, const float* coverage, const T* clip) {
  State& s = *state_;
  int skip = 0;
  if (s.nothing || !s.clip_to_view(y, x0, x1, skip)) return;
  const int n = x1 - x0;
  const T* src = s.shade(y, x0, n);
  s.run(s.view.pixel(x0, y), src, s.shader.is_constant() ? 0 : 4, coverage ? coverage + skip : nullptr, s.alpha,
        clip ? clip + skip : nullptr, n);
}

template class Compositor<std::uint8_t>;
template class Compositor<std::uint16_t>;

}  // namespace vraster
