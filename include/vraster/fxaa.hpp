// vraster: FXAA, a post-filter antialiasing of a finished (aliased) image.
#pragma once

#include <span>
#include <string_view>

#include "vraster/image.hpp"
#include "vraster/raster.hpp"

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

/// An antialiasing method as tools name it: the rasterizer's coverage mode plus an optional post-filter. The one
/// place that knows what "fxaa" means (aliased coverage, then fxaa() over the finished image): the rasterizer has no
/// FXAA mode, so a caller cannot ask it for one and forget the filter.
struct AntiAliasMethod {
  AntiAlias coverage = AntiAlias::Analytic;
  bool fxaa = false;  ///< post-filter the finished image with fxaa() (coverage is then AntiAlias::None)

  friend bool operator==(const AntiAliasMethod&, const AntiAliasMethod&) = default;
};

/// Every rasterizer mode's name (parse_anti_alias), plus "fxaa"; false for anything else (out unchanged).
bool parse_anti_alias_method(std::string_view name, AntiAliasMethod& out);
std::string_view to_string(const AntiAliasMethod& method);
/// The post-filter `method` asks for, on a finished image or coverage plane: fxaa() when method.fxaa, else nothing.
/// Drawing code calls it once, when the drawing is done.
void post_filter(const AntiAliasMethod& method, Image& image);
void post_filter(const AntiAliasMethod& method, Image16& image);
void post_filter(const AntiAliasMethod& method, std::span<float> plane, int width, int height);

}  // namespace vraster
