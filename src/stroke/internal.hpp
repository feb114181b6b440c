// Internal helpers shared by the stroke/ sources.
#pragma once

#include <vector>

#include "vraster/stroke.hpp"

namespace vraster {

/// flatten_for_stroke with a clip rectangle: curves whose control hull misses `clip` become their chords.
void flatten_for_stroke_clipped(const Path& path, double tolerance, const Rect& clip, std::vector<StrokePolyline>& out);

}  // namespace vraster

namespace vraster {

/// Liang-Barsky: clips the segment p-q to the closed rectangle r in place. False when nothing is left.
bool clip_segment(Point& p, Point& q, const Rect& r);

}  // namespace vraster

namespace vraster {

/// The SVG dash pattern normalized: an odd count repeated once; an invalid pattern (a negative or non-finite
/// entry, or a zero sum) gives an empty vector, which means a solid stroke.
std::vector<double> normalize_dashes(const std::vector<double>& dashes);

}  // namespace vraster

namespace vraster::detail {

/// The buffers a Renderer keeps for hairlines and coverage masks (kept between calls).
struct RendererScratch {
  struct PixelHit {
    int y, x;
    float coverage;
  };
  std::vector<StrokePolyline> pieces;  // hairlines: device-space polylines
  std::vector<PixelHit> hits;          // hairlines: per-pixel coverage before sorting into rows
  std::vector<float> run;              // hairlines: one run of adjacent pixels
  Path outline;                        // analytic hairlines: the 1-px stroke outline
  std::vector<float> row;              // masks: one row of coverage
};

}  // namespace vraster::detail
