// vraster: the canvas, the front door for embedding programs, the SVG renderer, text and the CLI.
//
// The HTML Canvas 2D model over a vraster image:
//   state stack (transform, clip, paints, line style, alpha, operator, rule, antialiasing, smoothing, shadow)
//   + a current path (user coordinates mapped by the transform as each point is added)
//   -> fill / stroke (stroke = geometry: the outline is filled non-zero) / clip / images / coverage masks
//   -> the rasterizer's coverage -> clip -> Compositor (paint + operator) -> the target or the innermost layer.
//
// Drawing calls never throw for bad numbers: as the canvas spec says, a NaN or infinite argument makes the call do
// nothing (argument-less calls on an invalid path do nothing either). Errors a caller must see (sizes out of
// range, out of memory) throw vraster::Error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "vraster/composite.hpp"
#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/mesh.hpp"
#include "vraster/paint.hpp"
#include "vraster/path.hpp"
#include "vraster/raster.hpp"
#include "vraster/seed_fill.hpp"
#include "vraster/stroke.hpp"

namespace vraster {

/// How a layer's mask turns into coverage (SVG mask-type).
enum class MaskMode : std::uint8_t { Alpha, Luminance };

/// How begin_layer() composites the layer when it ends.
struct LayerOptions {
  float opacity = 1;
  CompositeOp op = CompositeOp::SourceOver;
  /// Optional mask in device pixels, its top-left pixel at (mask_x, mask_y); pixels outside it mask everything.
  std::shared_ptr<const Image> mask;
  int mask_x = 0, mask_y = 0;
  MaskMode mask_mode = MaskMode::Alpha;
};

/// A drop shadow as the HTML canvas has it: drawn under each shape when colour alpha > 0 and (blur > 0 or an
/// offset is non-zero). Offsets are in device pixels (not transformed), blur is the canvas shadowBlur (a
/// Gaussian with standard deviation blur / 2).
struct Shadow {
  Color color = Color::transparent();
  double offset_x = 0, offset_y = 0;
  double blur = 0;
};

struct Scene;
struct ScenePlan;
struct PixelBox;

class Canvas {
 public:
  /// Draws onto `target` (which must outlive the canvas). 16-bit targets get 16-bit paint and compositing.
  explicit Canvas(Image& target);
  explicit Canvas(Image16& target);
  /// Records into `scene` (which must outlive the canvas; its width and height are the canvas size, 1 to
  /// kMaxImageSide each) instead of drawing: every draw call is appended with the state it needs
  /// (vraster/scene.hpp). get_pixels() reads transparent pixels while recording.
  explicit Canvas(Scene& recording);
  ~Canvas();
  Canvas(Canvas&&) noexcept;
  Canvas& operator=(Canvas&&) noexcept;

  int width() const;
  int height() const;

  // ---- state ----
  /// Pushes the whole drawing state (not the current path).
  void save();
  /// Pops it; without a matching save() it does nothing.
  void restore();

  // Transform: each call post-multiplies (the new transform applies to coordinates first), as on the canvas.
  void translate(double x, double y);
  void scale(double sx, double sy);
  void rotate(double radians);
  void transform(const Affine& m);
  void set_transform(const Affine& m);
  void reset_transform();
  Affine get_transform() const;

  void set_fill_paint(const Paint& paint);
  void set_stroke_paint(const Paint& paint);
  void set_fill_color(Color color);
  void set_stroke_color(Color color);
  const Paint& fill_paint() const;
  const Paint& stroke_paint() const;

  void set_line_width(double width);  ///< <= 0 or non-finite: ignored
  void set_line_cap(LineCap cap);
  void set_line_join(LineJoin join);
  void set_miter_limit(double limit);  ///< <= 0 or non-finite: ignored
  /// Dash lengths; an odd count is repeated; any negative or non-finite value: the call is ignored.
  void set_line_dash(std::span<const double> dashes);
  void set_line_dash_offset(double offset);
  const StrokeStyle& line_style() const;

  void set_global_alpha(double alpha);  ///< outside [0, 1] or non-finite: ignored
  void set_composite(CompositeOp op);
  void set_fill_rule(FillRule rule);  ///< the rule of fill() and clip() without an explicit rule
  /// The rasterizer's coverage mode. (FXAA is not one: it is a post-filter, apply_fxaa().)
  void set_anti_alias(AntiAlias aa);
  void set_tolerance(double device_pixels);  ///< flattening tolerance; <= 0 or non-finite: ignored
  void set_image_smoothing(bool on);
  void set_image_filter(ImageFilter filter);  ///< the filter used by draw_image when smoothing is on
  void set_shadow(const Shadow& shadow);
  /// The 2.5D depth of what is drawn next (saved and restored with the state; non-finite values are ignored).
  /// Drawing onto an image ignores it; a recorded scene can be put in depth order (vraster/scene.hpp).
  void set_z(double z);

  // ---- the current path (points mapped by the transform current when they are added) ----
  void begin_path();
  void move_to(double x, double y);
  void line_to(double x, double y);
  void quad_to(double cx, double cy, double x, double y);
  void cubic_to(double x1, double y1, double x2, double y2, double x, double y);
  /// Circular arc around (cx, cy) from angle a0 to a1 (radians), clockwise on screen unless `ccw`.
  void arc(double cx, double cy, double r, double a0, double a1, bool ccw = false);
  void arc_to(double x1, double y1, double x2, double y2, double r);
  void ellipse(double cx, double cy, double rx, double ry, double rotation, double a0, double a1, bool ccw = false);
  void rect(double x, double y, double w, double h);
  /// Rounded rectangle with one radius for every corner (the canvas roundRect with a single radius).
  void round_rect(double x, double y, double w, double h, double radius);
  void close_path();

  // ---- drawing ----
  void fill();
  void fill(FillRule rule);
  /// Fills a path given in user space (mapped by the current transform); the current path is unchanged.
  void fill(const Path& path);
  void fill(const Path& path, FillRule rule);
  void stroke();
  void stroke(const Path& path);
  /// Intersects the clip with the current path (or `path`) under `rule`, antialiased as the current mode says.
  void clip();
  void clip(FillRule rule);
  void clip(const Path& path, FillRule rule);
  void fill_rect(double x, double y, double w, double h);
  void stroke_rect(double x, double y, double w, double h);
  /// Sets the pixels of the rectangle (inside the clip) to transparent.
  void clear_rect(double x, double y, double w, double h);

  /// Draws `image` (premultiplied) into the destination rectangle (user space), from the source rectangle.
  void draw_image(const Image& image, double dx, double dy);
  void draw_image(const Image& image, double dx, double dy, double dw, double dh);
  void draw_image(const Image& image, double sx, double sy, double sw, double sh, double dx, double dy, double dw,
                  double dh);
  /// The whole of a shared image into the destination rectangle: a recording canvas keeps the pointer instead of
  /// a copy (an image drawn many times, such as a colour glyph, is stored once).
  void draw_image(std::shared_ptr<const Image> image, double dx, double dy, double dw, double dh);
  /// Paints the current fill paint through an 8-bit coverage mask whose pixel (0, 0) lands on device pixel
  /// (x, y), untransformed (cached glyphs).
  void fill_mask(const std::uint8_t* mask, int width, int height, std::ptrdiff_t stride, int x, int y);

  /// Draws a triangle mesh (vraster/mesh.hpp): vertex positions in user space, mapped by the transform (depth,
  /// normals and colours as given), through the clip and with the operator; the global alpha multiplies
  /// options.opacity. A z-buffer is the call's own (what earlier calls drew does not hide it). Meshes cast no
  /// shadow. Triangles with non-finite numbers are skipped.
  void draw_mesh(const Mesh& mesh, const MeshOptions& options = {});

  // ---- layers ----
  /// Starts a layer: drawing goes to a transparent buffer covering only the area it can touch (the clip's
  /// bounds) until end_layer() composites it with the options given here. Layers nest; save/restore inside a
  /// layer are balanced by end_layer().
  void begin_layer(const LayerOptions& options = {});
  void begin_layer(float opacity) {
    LayerOptions options;
    options.opacity = opacity;
    begin_layer(options);
  }
  void end_layer();

  // ---- pixels ----
  /// Premultiplied RGBA of the rectangle (pixels outside the canvas are transparent).
  Image get_pixels(int x, int y, int w, int h) const;
  /// Writes premultiplied RGBA at (x, y), ignoring transform, clip, alpha and operator (putImageData).
  void put_pixels(const Image& pixels, int x, int y);
  /// FXAA over the target (a post-filter: call it when the drawing is done).
  void apply_fxaa();
  /// Seed (flood) fill of the target image from device pixel (x, y) (vraster/seed_fill.hpp): every pixel of the
  /// region gets `fill`, replacing it (as put_pixels: transform, clip, alpha, operator and layers do not apply).
  /// Returns the pixels written (0 for a seed outside the canvas or a non-finite colour); throws vraster::Error
  /// for a tolerance outside [0, 1]. While recording it returns 0.
  std::int64_t flood_fill(int x, int y, Color fill, const SeedFillOptions& options = {});

  // ---- scenes (vraster/scene.hpp) ----
  /// Replays a recorded scene in device space (its recorded transforms are used as they are), under this canvas's
  /// clip; every call the plan culls is skipped and every change it made is applied. Without a plan, every call
  /// is replayed as recorded. The canvas state is left as it was.
  void draw_scene(const Scene& scene, const ScenePlan* plan = nullptr);
  /// Draws `scene` with `plan` as the next frame of this canvas's image, which holds the frame drawn before:
  /// `previous` is the plan of that frame (drawn by draw_frame with the same background), or null when it is not
  /// known (the first frame), and then the whole image is cleared to `background`. Otherwise only
  /// changed_regions(plan, previous) are cleared and drawn into, which gives the same pixels as clearing
  /// everything. Returns the regions cleared (the only pixels that can differ from the frame before). Throws
  /// vraster::Error when the scene, the plan and the canvas differ in size, while recording, or inside a layer.
  std::vector<PixelBox> draw_frame(const Scene& scene, const ScenePlan& plan, const ScenePlan* previous,
                                   Color background);
  /// How many fills so far went over the exact-coverage work limit and were drawn analytic instead
  /// (Rasterizer::exact_fallbacks), so that callers can warn.
  std::uint64_t exact_fallbacks() const;

  // ---- threads ----
  /// Rasterizes large fills on up to `threads` threads (clamped to [1, 64]; Rasterizer::set_threads): bands of rows
  /// swept by workers this canvas owns. The pixels are the same, bit for bit, as with one thread (the default).
  /// Fills painted with gradients or patterns, and unbounded operators, stay on one thread.
  void set_threads(int threads);
  int threads() const;

  // ---- hit testing (user coordinates mapped by the current transform) ----
  bool is_point_in_path(double x, double y) const;
  bool is_point_in_path(double x, double y, FillRule rule) const;
  bool is_point_in_path(const Path& path, double x, double y, FillRule rule) const;
  bool is_point_in_stroke(double x, double y) const;
  bool is_point_in_stroke(const Path& path, double x, double y) const;

 private:
  struct Impl;  // src/canvas/
  std::unique_ptr<Impl> impl_;
};

}  // namespace vraster
