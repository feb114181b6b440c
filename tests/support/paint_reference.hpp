// Test support: slow per-pixel references for compositing and paint, written from the specs' formulas in double
// precision and sharing no code with src/paint/:
//  - W3C Compositing and Blending Level 1: the Porter-Duff general form co = cs Fa + cb Fb, ao = as Fa + ab Fb;
//    blend modes cs' = (1 - ab) Cs + ab B(Cb, Cs), composited source-over, on premultiplied storage;
//  - HTML canvas: linear, two-circle radial (the cone of circles, largest t with r(t) >= 0) and conic gradients,
//    colours interpolated in straight (unpremultiplied) RGBA; patterns sampled at pixel centres.
#pragma once

#include <array>

#include "vraster/composite.hpp"
#include "vraster/paint.hpp"

namespace vraster::test {

/// Premultiplied RGBA in [0, 1].
using Rgba = std::array<double, 4>;

/// Op(s, d) on premultiplied colours, from the spec formulas.
Rgba reference_composite(CompositeOp op, const Rgba& s, const Rgba& d);

/// The whole per-pixel pipeline of a draw: the source scaled by coverage, Op, then lerp by clip.
Rgba reference_draw(CompositeOp op, const Rgba& s, const Rgba& d, double coverage, double clip);

/// The premultiplied colour `paint` gives the device point (x, y) (a pixel centre) under `user_to_device`.
/// Transparent where the paint paints nothing.
Rgba reference_paint(const Paint& paint, const Affine& user_to_device, double x, double y);

/// The gradient parameter (before the extend mode) at device point (x, y); false where the gradient paints
/// nothing (outside a radial gradient's cone, degenerate geometry).
bool reference_gradient_t(const Paint& paint, const Affine& user_to_device, double x, double y, double& t);

/// A pattern sampled at device point (x, y): nearest (the texel containing the point), bilinear (the four texels
/// around it, weights from the distances to their centres), bicubic (Catmull-Rom, 4 x 4 texels, clamped to a valid
/// premultiplied colour); texels outside the tile follow each axis's extend mode (None: transparent).
Rgba reference_pattern(const Paint& paint, const Affine& user_to_device, double x, double y);

/// Gradient colour at parameter t (after the extend mode), straight RGBA interpolated, returned premultiplied.
Rgba reference_gradient_color(const Paint& paint, double t);

}  // namespace vraster::test
