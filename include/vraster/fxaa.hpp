// vraster: FXAA, a post-filter antialiasing of a finished (aliased) image.
#pragma once

#include <span>

#include "vraster/image.hpp"

namespace vraster {

/// Tuning of fxaa() (the defaults are FXAA 3.11's "quality" defaults).
struct FxaaOptions {
  float edge_threshold = 0.125f;       ///< skip pixels whose local luma range is below this share of the local max
  float edge_threshold_min = 0.0312f;  ///< ... or below this absolute range (dark regions)
  float subpixel = 0.75f;              ///< strength of the sub-pixel aliasing removal (0: off, 1: soft)
};

/// FXAA (after Timothy Lottes' FXAA 3.11, "quality" variant): per pixel, the luma range over its 4 neighbours
/// decides whether it lies on an edge; if it does, the edge's orientation (horizontal or vertical) and the side with
/// the steeper gradient are found, the edge is followed in both directions to its ends (up to 12 search steps of
/// growing length), and the pixel is replaced by a bilinear sample of the image moved across the edge by the
/// share the position along the edge calls for (plus a sub-pixel term for isolated pixels).
/// Pixels whose 4-neighbourhood has a luma range below the thresholds are never changed, so only pixels next to an
/// edge change. Luma: of the premultiplied colour (0.299 R + 0.587 G + 0.114 B); in an image with any pixel not
/// opaque, the mean of that luma and alpha (so shapes over transparency have edges even when black).
void fxaa(Image& image, const FxaaOptions& options = {});
void fxaa(Image16& image, const FxaaOptions& options = {});

/// The same filter on one plane of values in [0, 1] (e.g. a coverage buffer), luma = value. plane.size() must be
/// width * height.
void fxaa(std::span<float> plane, int width, int height, const FxaaOptions& options = {});

}  // namespace vraster
