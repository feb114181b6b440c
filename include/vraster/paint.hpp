// vraster: paint sources (what colours a shape): solid colour, linear, two-circle radial and conic gradients,
// image patterns. A Paint is a description; the compositor (composite.hpp) shades spans from it.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "vraster/geometry.hpp"
#include "vraster/image.hpp"

namespace vraster {

/// What a gradient or pattern does outside its [0, 1] range or tile (SVG spreadMethod, canvas pattern repetition).
enum class Extend : std::uint8_t {
  Pad,      ///< the end colour (gradient) or edge pixel (pattern) continues
  Repeat,   ///< the range or tile repeats
  Reflect,  ///< the range or tile repeats mirrored every other time
  None,     ///< patterns only: transparent outside the tile (canvas "no-repeat" on that axis)
};

/// How a pattern's image is sampled.
enum class ImageFilter : std::uint8_t { Nearest, Bilinear, Bicubic };

/// A gradient stop: a straight (not premultiplied) colour at an offset in [0, 1].
struct ColorStop {
  double offset = 0;
  Color color;
};

/// A paint source. A value type: copying is cheap (a pattern shares its image).
///
/// Geometry (gradient points and radii, the pattern tile whose top-left corner is at the origin) is given in paint
/// space; transform() maps paint space to user space (CanvasPattern.setTransform, SVG gradientTransform). The
/// user-to-device transform comes from whoever draws (the canvas's current transform at the time of the fill).
class Paint {
 public:
  enum class Kind : std::uint8_t { Solid, Linear, Radial, Conic, Pattern };

  /// Solid opaque black.
  Paint();
  static Paint solid(Color color);
  /// Linear gradient: offset 0 at p0, 1 at p1, constant along lines perpendicular to p0-p1.
  static Paint linear(Point p0, Point p1);
  /// Two-circle radial gradient (HTML canvas createRadialGradient, SVG 2 fx/fy/fr -> cx/cy/r): offset 0 on the
  /// start circle (c0, r0), 1 on the end circle (c1, r1); a focal circle on or outside the end circle is handled
  /// as the HTML canvas spec says (the cone of circles; points that no circle with r >= 0 reaches are transparent).
  static Paint radial(Point c0, double r0, Point c1, double r1);
  /// Conic (sweep) gradient around `center`, offset 0 at `start_angle` (radians, measured from the +x axis
  /// towards +y, i.e. clockwise on a y-down screen, as createConicGradient), increasing the same way to 1 after a
  /// full turn.
  static Paint conic(double start_angle, Point center);
  /// Image pattern; the tile's top-left corner is at the paint-space origin, one image pixel per unit.
  static Paint pattern(std::shared_ptr<const Image> tile);
  static Paint pattern(std::shared_ptr<const Image16> tile);

  /// Adds a gradient stop. Stops are kept in offset order; stops with equal offsets keep the order they were
  /// added in (a hard step). Returns false and adds nothing for a non-finite offset or one outside [0, 1], a
  /// non-finite colour, or a paint that is not a gradient. A gradient without stops paints nothing (transparent);
  /// with one stop it paints that stop's colour everywhere.
  bool add_stop(double offset, Color color);
  /// Gradients: spread outside [0, 1]. Patterns: both axes.
  void set_extend(Extend both);
  /// Patterns: each axis on its own.
  void set_extend(Extend x, Extend y);
  void set_filter(ImageFilter filter);
  /// Maps paint space to user space. A non-invertible transform makes the paint draw nothing (as canvas and SVG).
  void set_transform(const Affine& paint_to_user);
  /// Ordered dithering of gradients for 8-bit targets (off by default).
  void set_dither(bool on);
  /// Multiplies every colour's alpha (fill-opacity, stop-opacity after the fact, canvas globalAlpha is separate).
  void set_opacity(float opacity);

  Kind kind() const { return kind_; }
  const Color& color() const { return color_; }  ///< Solid only
  const std::vector<ColorStop>& stops() const { return stops_; }
  Point p0() const { return p0_; }  ///< Linear: start; Radial: start circle centre; Conic: centre
  Point p1() const { return p1_; }  ///< Linear: end; Radial: end circle centre
  double r0() const { return r0_; }
  double r1() const { return r1_; }
  double angle() const { return angle_; }  ///< Conic start angle
  Extend extend_x() const { return extend_x_; }
  Extend extend_y() const { return extend_y_; }
  ImageFilter filter() const { return filter_; }
  const Affine& transform() const { return transform_; }
  bool dither() const { return dither_; }
  float opacity() const { return opacity_; }
  const std::shared_ptr<const Image>& image8() const { return image8_; }
  const std::shared_ptr<const Image16>& image16() const { return image16_; }

  /// True when every pixel it paints is fully opaque (lets source-over store instead of blending).
  bool is_opaque() const;
  /// True when it paints nothing anywhere (transparent colour, no stops, zero opacity, singular transform).
  bool is_invisible() const;

 private:
  Kind kind_ = Kind::Solid;
  Color color_{0, 0, 0, 1};
  std::vector<ColorStop> stops_;
  Point p0_{}, p1_{};
  double r0_ = 0, r1_ = 0, angle_ = 0;
  Extend extend_x_ = Extend::Pad, extend_y_ = Extend::Pad;
  ImageFilter filter_ = ImageFilter::Bilinear;
  Affine transform_{};
  bool dither_ = false;
  float opacity_ = 1;
  std::shared_ptr<const Image> image8_;
  std::shared_ptr<const Image16> image16_;
};

}  // namespace vraster
