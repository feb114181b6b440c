// vraster: a recorded scene and the planner that renders only what it calls for.
//
//   1. record: a Canvas built over a Scene (Canvas(Scene&)) appends every draw call, with the state it needs
//      (transform, paint, line style, alpha, operator, antialiasing, shadow) and the clip chain it is drawn
//      under, instead of drawing it
//   2. plan_scene(): one pass over the scene decides per call what it needs: culled (outside the canvas or its
//      clip, invisible, empty, or hidden under later opaque content), its coverage method, whether a layer is
//      needed at all, whether a mesh can be drawn front to back, and which tiles of the canvas the scene touches
//   3. Canvas::draw_scene(scene, &plan) replays it onto any canvas, doing only what the plan kept;
//      draw_scene(scene) without a plan replays every call as recorded (the naive render)
//   4. explain_plan() prints every decision and what it saved (`vraster explain`)
//
// A plan never changes the picture beyond rounding (tests/scene_test.cpp compares planned and naive renders).
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "vraster/canvas.hpp"

namespace vraster {

/// The part of the canvas state a recorded call draws with (everything save() pushes but the clip; the canvas's
/// own state extends it).
// (A field added here is also copied by Canvas::draw_scene for fills, src/canvas/record.cpp.)
struct SceneState {
  Affine transform;
  Paint fill_paint, stroke_paint;
  StrokeStyle line;
  float global_alpha = 1;
  CompositeOp op = CompositeOp::SourceOver;
  FillRule rule = FillRule::NonZero;
  AntiAlias aa = AntiAlias::Analytic;
  double tolerance = kDefaultTolerance;
  bool smoothing = true;
  ImageFilter filter = ImageFilter::Bilinear;
  Shadow shadow;
  double z = 0;  ///< Canvas::set_z(): order_by_depth() draws smaller z first
};

/// One clip() of a recorded scene, linked to the clips it intersects (its parent). Calls drawn under the same
/// clips share the same node, so "drawn under the same clip" is a pointer comparison.
struct SceneClip {
  Path path;        ///< as given to clip()
  Affine to_device;  ///< maps `path` to device pixels
  FillRule rule = FillRule::NonZero;
  AntiAlias aa = AntiAlias::Analytic;
  double tolerance = kDefaultTolerance;
  std::shared_ptr<const SceneClip> parent;
};

/// A recorded draw call.
struct SceneCommand {
  enum class Kind : std::uint8_t {
    Fill,        ///< path (mapped by to_device) filled with state.fill_paint under `rule`
    Stroke,      ///< path (user space, mapped by to_device) stroked with state.line and state.stroke_paint
    DrawImage,   ///< image drawn from `src` (image pixels) into `dst` (user space)
    FillMask,    ///< fill_mask: state.fill_paint through the coverage in image's alpha, top-left at (x, y)
    PutPixels,   ///< put_pixels: image written at (x, y), ignoring every state
    BeginLayer,  ///< begin_layer(layer)
    EndLayer,    ///< end_layer()
    Fxaa,        ///< apply_fxaa(): a post-filter over the whole target
    FloodFill,   ///< flood_fill() from (x, y) with state.fill_paint's colour and `seed`
    Mesh,        ///< draw_mesh(): `mesh` (positions mapped by to_device) drawn with `mesh_options`
  };
  Kind kind = Kind::Fill;
  Path path;
  Affine to_device;
  FillRule rule = FillRule::NonZero;
  SceneState state;
  std::shared_ptr<const SceneClip> clip;  ///< the clips in force (null: none)
  std::shared_ptr<const Image> image;
  Rect src, dst;
  int x = 0, y = 0;
  LayerOptions layer;
  SeedFillOptions seed;
  std::shared_ptr<const Mesh> mesh;
  MeshOptions mesh_options;
};

/// A list of draw calls on a canvas of a given size, replayable onto any canvas (Canvas::draw_scene).
struct Scene {
  int width = 0, height = 0;
  /// A deque: a recording grows in blocks, never copying (or holding twice) what it has so far, which for a
  /// document of a million elements was most of the time spent recording it.
  std::deque<SceneCommand> commands;
};

/// A device rectangle of whole pixels [x0, x1) x [y0, y1).
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  std::int64_t area() const { return empty() ? 0 : std::int64_t{x1 - x0} * (y1 - y0); }
};

/// Why the planner decided what it did (describe_decision() turns it into a sentence).
enum class PlanReason : std::uint8_t {
  Drawn,                 ///< drawn (describe_decision says how: aliased, stored, blended, folded opacity)
  OutsideCanvas,         ///< culled: nothing of it reaches the canvas
  OutsideClip,           ///< culled: nothing of it reaches its clip
  GlobalAlphaZero,       ///< culled: alpha 0 with an operator that then changes nothing
  TransparentPaint,      ///< culled: a paint that paints nothing, same operators
  ZeroArea,              ///< culled: a fill of zero area
  ZeroWidth,             ///< culled: a stroke of zero width
  Hidden,                ///< culled: command `ref` overwrites every pixel it can change
  LayerNeverEnds,        ///< culled: a layer never ended never shows
  InsideNeverEndingLayer,  ///< culled: inside layer `ref`, which never ends
  InsideCulledLayer,     ///< culled: inside layer `ref`, which is culled
  LayerOpacityZero,      ///< culled: a layer of opacity 0
  LayerOutside,          ///< culled: a layer outside the canvas or its clip
  LayerEmpty,            ///< culled: a layer with nothing left to draw
  LayerNeedsMask,        ///< kept: it has a mask
  LayerNeedsOperator,    ///< kept: it is composited with an operator other than source-over
  LayerNeedsIsolation,   ///< kept: drawing inside it is not source-over (or reads the target)
  LayerNeedsClip,        ///< kept: its clip has antialiased edges, applied once to the whole layer
  LayerNeedsOverlap,     ///< kept: opacity < 1 over children that overlap
  LayerNeedsNested,      ///< kept: opacity < 1 over a layer of its own
  LayerNeedsShadows,     ///< kept: opacity < 1 over children with shadows
  LayerDropped,          ///< dropped: opacity 1, source-over, source-over inside
  LayerFolded,           ///< dropped: opacity `value` folded into its `count` children, which touch disjoint pixels
  EndOfDroppedLayer,     ///< the end of dropped layer `ref`
  LayerComposited,       ///< the end of a kept layer
};

/// What the planner decided for one command.
struct PlanDecision {
  enum class Action : std::uint8_t {
    Draw,        ///< drawn as recorded (or with the changes below)
    Cull,        ///< not drawn
    DropLayer,   ///< BeginLayer/EndLayer: no layer (its children draw straight onto the target)
  };
  Action action = Action::Draw;
  PlanReason reason = PlanReason::Drawn;
  int ref = -1;              ///< the command the reason refers to (Hidden: the cover; Inside...: the layer)
  float value = 0;           ///< LayerFolded: the opacity folded
  int count = 0;             ///< LayerFolded: how many children
  PixelBox bounds;           ///< device pixels the call can change (clipped to the canvas and its clip's box)
  float alpha_scale = 1;     ///< a folded group opacity, multiplied into the call's global alpha
  bool aliased = false;      ///< drawn without antialiasing work (the result is the same)
  bool front_to_back = false;  ///< a mesh drawn nearest triangle first (MeshOptions::front_to_back)
};

/// The plan of a scene: one decision per command and what it saves.
struct ScenePlan {
  std::vector<PlanDecision> decisions;
  int width = 0, height = 0;  ///< the scene's
  int tile_size = 64;
  int tiles_x = 0, tiles_y = 0;
  std::vector<std::uint8_t> touched_tiles;  ///< tiles_x * tiles_y, 1 where a kept call can change a pixel
  int culled = 0;                           ///< commands not drawn
  int layers_dropped = 0, layers_folded = 0;
  std::int64_t layer_pixels_saved = 0;      ///< layer pixels not allocated
  std::int64_t pixels_not_composited = 0;   ///< bounds area of the culled calls
  int aliased = 0;                          ///< calls drawn without antialiasing work
  int front_to_back = 0;                    ///< meshes drawn nearest triangle first
  int touched_tile_count() const;
};

/// The tiles `plan` touches, and those `previous` touched when it is given (a plan of a scene of the same size), as
/// rectangles of device pixels: runs of touched tiles in each tile row, merged with the run of the same extent
/// below. These are the only pixels a frame of the scene can change, so a program that redraws frames into one
/// image clears, redraws, encodes or uploads only them (Canvas::draw_frame).
std::vector<PixelBox> changed_regions(const ScenePlan& plan, const ScenePlan* previous = nullptr);

/// 2.5D ordering for objects of constant depth (window systems, cartoon cels, VLSI layers): the scene with its
/// calls in increasing z (Canvas::set_z), calls of equal z in the order they were recorded. A layer moves as one
/// block with the z of its BeginLayer, and the calls inside it are ordered the same way among themselves.
Scene order_by_depth(const Scene& scene);

/// Decides, for each command of `scene`, what it needs (see the top of this file).
ScenePlan plan_scene(const Scene& scene);

/// The decision for command `index` as one sentence: what was decided and why.
std::string describe_decision(const Scene& scene, const ScenePlan& plan, std::size_t index);

/// The plan as text, one line per command and a summary (`vraster explain`), or as JSON.
std::string explain_plan(const Scene& scene, const ScenePlan& plan);
std::string explain_plan_json(const Scene& scene, const ScenePlan& plan);

}  // namespace vraster
