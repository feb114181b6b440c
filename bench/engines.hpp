// vraster_bench: the engines compared. Each one builds its own paths from a parsed Document before timing;
// a timed frame is clear to white + fill every item in file order (source-over, antialiased) + flush.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "svg_subset/svg.hpp"
#include "vraster/flatten.hpp"
#include "vraster/image.hpp"

namespace bench {

class Engine {
 public:
  virtual ~Engine() = default;
  virtual const char* name() const = 0;
  /// Builds the engine's device-space paths and its target for `doc` (not timed). Throws on unusable input.
  virtual void prepare(const vraster::svg::Document& doc) = 0;
  /// Renders one frame. Returns false when the engine cannot render this scene (reason in error()).
  virtual bool frame() = 0;
  /// The last frame as 8-bit premultiplied RGBA.
  virtual vraster::Image image() const = 0;
  virtual std::string error() const { return {}; }
  /// Library version for the report.
  virtual std::string version() const = 0;
  /// The largest distance between a curve and the lines it is drawn with, in device pixels, for the engines that
  /// take one (vraster, Cairo, Blend2D); set before prepare(). FreeType splits curves by its own fixed rule.
  virtual void set_tolerance(double tolerance) { tolerance_ = tolerance; }

 protected:
  double tolerance_ = vraster::kDefaultTolerance;
};

/// vraster with `threads` threads (Renderer::set_threads; a frame's fills are queued and flushed at its end); 1 is
/// the single-threaded engine of the comparison.
std::unique_ptr<Engine> make_vraster_engine(int threads = 1);
std::unique_ptr<Engine> make_cairo_engine();
std::unique_ptr<Engine> make_freetype_engine();
/// Only in builds configured with -DVRASTER_BENCH_BLEND2D_ROOT=PREFIX.
std::unique_ptr<Engine> make_blend2d_engine();

// The 8-bit source-over math vraster's compositor uses (one uint32 pixel, R in the low byte, two channels per
// multiply): scale8(px, f) = px * f / 255 per channel, rounded to nearest.
inline std::uint32_t scale8(std::uint32_t px, std::uint32_t f) {
  std::uint32_t rb = (px & 0x00FF00FFu) * f + 0x00800080u;
  rb = ((rb + ((rb >> 8) & 0x00FF00FFu)) >> 8) & 0x00FF00FFu;
  std::uint32_t ag = ((px >> 8) & 0x00FF00FFu) * f + 0x00800080u;
  ag = ((ag + ((ag >> 8) & 0x00FF00FFu)) >> 8) & 0x00FF00FFu;
  return rb | (ag << 8);
}

}  // namespace bench
