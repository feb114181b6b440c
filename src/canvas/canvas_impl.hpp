// The canvas's private state: drawing state, clip, layers, and the drawing pipeline's reusable buffers.
//
// Every draw call goes the same way (src/canvas/draw.cpp):
//   1. a CoverageSource (path, coverage mask, blurred shadow plane) produces coverage for a device rectangle
//   2. ClipSink: offsets it to device pixels, adds the clip mask, and for unbounded operators covers the whole clip
//      region row by row (coverage 0 outside the shape)
//   3. Compositor<T> (src/paint/): paint + operator + global alpha onto the target or the innermost layer.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "canvas/arcs.hpp"
#include "vraster/canvas.hpp"
#include "vraster/renderer.hpp"
#include "vraster/scene.hpp"

namespace vraster::canvas_detail {

/// A rectangle of whole device pixels [x0, x1) x [y0, y1).
struct IntRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  IntRect intersect(const IntRect& o) const;
  IntRect expand(int d) const;
  IntRect offset(int dx, int dy) const;
  /// The pixels a device box touches (rounded outwards, clamped to +-2^30 so that nothing overflows).
  static IntRect covering(const Rect& r);
};

/// A clip's coverage over `box`, quantized to the canvas's channel type once, when the clip is made: levels 0 .. 255
/// on 8-bit canvases (one byte a pixel, as Cairo and pixman keep clips), 0 .. 65535 on 16-bit ones (as precise as
/// their compositing). The compositor quantized the clip to exactly these levels anyway; storing them saves 3/4 of
/// the traffic of a float mask and the conversion per pixel. Per row it also keeps the pixels that are not 0 and
/// one run that is full: drawing skips the rest and composites that run without the clip lerp.
struct ClipMask {
  struct RowExtent {
    int x0 = 0, x1 = 0;        ///< device x of the pixels not 0: [x0, x1)
    int full0 = 0, full1 = 0;  ///< the longest run of full coverage: [full0, full1)
  };
  IntRect box;
  std::vector<std::uint8_t> levels8;    // 8-bit canvases
  std::vector<std::uint16_t> levels16;  // 16-bit canvases
  std::vector<RowExtent> rows;

  template <class T>
  const T* at(int x, int y) const {
    const std::size_t i = static_cast<std::size_t>(y - box.y0) * box.width() + (x - box.x0);
    if constexpr (sizeof(T) == 1) {
      return levels8.data() + i;
    } else {
      return levels16.data() + i;
    }
  }
  const RowExtent& extent(int y) const { return rows[static_cast<std::size_t>(y - box.y0)]; }
};

/// The clip: pixels outside `box` are clipped away; inside it, `mask` (when set) multiplies coverage. A clip that
/// is a pixel-aligned rectangle has no mask. `box` lies inside mask->box.
struct Clip {
  IntRect box;
  std::shared_ptr<const ClipMask> mask;
};

/// Everything save() pushes: what a draw call draws with (the part a recorded scene keeps per call) and the clip.
struct State : SceneState {
  Clip clip;
  std::shared_ptr<const SceneClip> recorded_clip;  // recording: the clips in force, as geometry
};

/// Produces coverage for a device rectangle `region`, in coordinates relative to its top-left pixel, displaced
/// by `offset` device pixels (the shadow pass draws the shape moved by the shadow offset).
class CoverageSource {
 public:
  virtual ~CoverageSource() = default;
  /// Device pixels the coverage can touch (before the offset).
  virtual IntRect bounds() const = 0;
  virtual void produce(const IntRect& region, Point offset, CoverageSink& sink) = 0;
};

/// An offscreen layer: pixels of `box` (channels of the canvas's type), the options to composite it with, and the
/// state-stack depth at begin_layer().
struct Layer {
  IntRect box;
  std::vector<std::uint8_t> pixels8;
  std::vector<std::uint16_t> pixels16;
  LayerOptions options;
  std::size_t depth = 0;
};

}  // namespace vraster::canvas_detail

namespace vraster {

struct Canvas::Impl {
  using IntRect = canvas_detail::IntRect;
  using State = canvas_detail::State;

  Image* image8 = nullptr;
  Image16* image16 = nullptr;
  int width = 0, height = 0;

  Scene* recording = nullptr;  // set: draw calls are appended here instead of drawn (record.cpp)
  State state;
  std::vector<State> stack;
  std::vector<canvas_detail::Layer> layers;
  Path path;  // the current path, in device space

  // Reused by every draw call (nothing allocates per path once they have grown).
  Renderer renderer;  // flattening buffer + the one rasterizer
  MeshRenderer mesh_renderer;
  Compositor<std::uint8_t> compositor8;
  Compositor<std::uint16_t> compositor16;
  Polylines lines;                      // clip and hit-test flattening
  canvas_detail::ArcPoints arc;         // arc points before they join the path
  std::vector<float> row_coverage;      // ClipSink: one row of the clip region
  std::shared_ptr<canvas_detail::ClipMask> spare_mask;  // the last clip mask made: reused once no state holds it
  std::vector<float> mask_row;          // fill_mask: one row of the mask as floats
  std::vector<float> plane;             // shadow alpha / blur
  std::vector<float> plane_scratch;
  std::vector<std::uint8_t> shadow8;    // the shape drawn alone for its shadow
  std::vector<std::uint16_t> shadow16;

  Impl(Image* i8, Image16* i16, int w, int h);

  bool is16() const { return image16 != nullptr; }
  /// The device box drawing goes to: the innermost layer's, or the canvas.
  IntRect target_box() const;
  template <class T>
  ImageView<T> target_view();
  template <class T>
  Compositor<T>& compositor();

  // ---- drawing (draw.cpp) ----
  /// Draws `shape` with `paint` (in user space under `paint_to_device`), the state's operator, alpha, clip and
  /// (when `with_shadow`) shadow.
  void draw(canvas_detail::CoverageSource& shape, const Paint& paint, const Affine& paint_to_device,
            CompositeOp op, float alpha, bool with_shadow);
  template <class T>
  void draw_typed(canvas_detail::CoverageSource& shape, const Paint& paint, const Affine& paint_to_device,
                  CompositeOp op, float alpha, bool with_shadow);
  template <class T>
  void composite_layer(canvas_detail::Layer& layer);
  void fill_path(const Path& path, const Affine& to_device, FillRule rule, const Paint& paint);
  void stroke_user_path(const Path& user_path, const Affine& to_device);
  void clip_path(const Path& path, const Affine& to_device, FillRule rule);
  template <class T>
  IntRect make_clip_mask(canvas_detail::ClipMask& mask, const IntRect& area, FillRule rule);
  void begin_layer(const LayerOptions& options);
  void end_layer(bool composite = true);  ///< false: the layer is dropped without a trace
  /// `shared`: the same image when the caller shares it (recorded by reference), else null (recorded as a copy).
  void draw_image(const Image& image, Rect src, Rect dst, std::shared_ptr<const Image> shared = nullptr);
  void draw_mesh(const Mesh& mesh, const Affine& to_device, MeshOptions options);
  template <class T>
  void draw_mesh_onto_target(const Mesh& device_mesh, const MeshOptions& options);

  // ---- recording (record.cpp) ----
  /// Appends a command of `kind` with the current state (and clips) to the recording.
  SceneCommand& record(SceneCommand::Kind kind);

  // ---- state and path (canvas.cpp) ----
  void restore();
  bool has_subpath() const { return !path.empty(); }
  /// Appends arc points (user space) to the current path: a line (or a move, for an empty path) to the first,
  /// then the cubics. Does nothing when a mapped point is not finite.
  void add_arc_points();
  bool point_in(const Path& device_path, Point device_point, FillRule rule);
};

}  // namespace vraster
