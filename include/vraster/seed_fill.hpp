// vraster: seed (flood) fill on an image, by scanline spans with an explicit stack.
//
//   1. decide, per pixel, whether it belongs to the region (interior-defined: its colour is within a tolerance of
//      the seed's colour; boundary-defined: it is not the boundary colour)
//   2. from the seed, grow the region span by span: pop a pixel, extend it left and right into a run, mark the run,
//      push the start of every run of region pixels on the rows above and below that touches it
//   3. flood_fill() then stores the fill colour into every marked pixel
//
// The stack is a std::vector (never recursion), so a 4096 x 4096 maze costs memory on the heap, not call stack.
// Each region pixel is marked once, so a fill colour that itself matches the region cannot loop.
#pragma once

#include <cstdint>
#include <vector>

#include "vraster/image.hpp"

namespace vraster {

/// Which neighbours of a pixel are connected to it.
enum class Connectivity : std::uint8_t {
  Four,   ///< left, right, up, down
  Eight,  ///< the four plus the four diagonal neighbours
};

/// How the region grown from the seed is defined (the seeds' "interior-defined" and "boundary-defined" regions).
enum class SeedRegion : std::uint8_t {
  /// Pixels whose colour is within the tolerance of the seed pixel's colour (replace a colour).
  Interior,
  /// Pixels whose colour is NOT within the tolerance of the boundary colour (fill up to the boundary). Pixels that
  /// already have the fill colour are part of the region too (the seeds' recursive version stops at them only to
  /// end its recursion).
  Boundary,
};

/// What a seed fill compares against.
struct SeedFillOptions {
  Connectivity connectivity = Connectivity::Four;
  SeedRegion region = SeedRegion::Interior;
  /// Largest difference per channel that still counts as the same colour, as a fraction of the channel range
  /// ([0, 1]; 0: exact match). Channels are compared premultiplied, as stored.
  double tolerance = 0;
  /// The boundary colour (SeedRegion::Boundary only; compared premultiplied after conversion to the image depth).
  Color boundary = Color{0, 0, 0, 1};
};

/// The pixels a seed fill reaches: one byte per pixel of the image (1: in the region), with its bounding box.
struct SeedFillRegion {
  int width = 0, height = 0;
  std::vector<std::uint8_t> mask;  ///< row-major, width x height
  std::int64_t pixel_count = 0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< bounding box [x0, x1) x [y0, y1) of the region (empty when count is 0)
  bool contains(int x, int y) const { return mask[static_cast<std::size_t>(y) * width + x] != 0; }
};

/// Grows the region of `options` from the seed pixel (x, y) without changing the image. A seed outside the image,
/// or a boundary-defined seed that is itself boundary-coloured, gives an empty region.
/// Throws vraster::Error for a tolerance that is not a number in [0, 1].
template <class T>
SeedFillRegion seed_fill_region(const BasicImage<T>& image, int x, int y, const SeedFillOptions& options);

/// Stores `fill` (premultiplied, replacing what was there: the seeds' SetPixel) into every pixel of the region
/// grown from (x, y); returns the number of pixels written. Same errors as seed_fill_region().
template <class T>
std::int64_t flood_fill(BasicImage<T>& image, int x, int y, Color fill, const SeedFillOptions& options = {});

/// A colour premultiplied and scaled to channels of type T, rounded to nearest (as BasicImage::clear stores it).
template <class T>
void premultiply_to(Color c, T out[4]);

extern template SeedFillRegion seed_fill_region(const BasicImage<std::uint8_t>&, int, int, const SeedFillOptions&);
extern template SeedFillRegion seed_fill_region(const BasicImage<std::uint16_t>&, int, int, const SeedFillOptions&);
extern template std::int64_t flood_fill(BasicImage<std::uint8_t>&, int, int, Color, const SeedFillOptions&);
extern template std::int64_t flood_fill(BasicImage<std::uint16_t>&, int, int, Color, const SeedFillOptions&);

}  // namespace vraster
