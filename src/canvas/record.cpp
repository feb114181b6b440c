// Scenes on the canvas: recording draw calls (Canvas(Scene&)) and replaying them (Canvas::draw_scene).
//
// Recording keeps clips as geometry: each clip() links a SceneClip node to the ones in force, and save/restore
// carry that link in the state, so every command knows its clip chain without a stack of its own. Replaying
// turns chains back into clips: the clips a command needs that are not in force yet are pushed one per save(),
// and the ones it does not need are popped with restore(), so consecutive commands under the same clips share
// one clip mask.
#include <algorithm>
#include <string>

#include "canvas/canvas_impl.hpp"
#include "vraster/error.hpp"

namespace vraster {

SceneCommand& Canvas::Impl::record(SceneCommand::Kind kind) {
  SceneCommand c;
  c.kind = kind;
  c.state = state;  // the SceneState part
  c.clip = state.recorded_clip;
  recording->commands.push_back(std::move(c));
  return recording->commands.back();
}

namespace {

/// The clip chain from `node` back to `base` (exclusive), outermost first.
std::vector<const SceneClip*> chain_above(const SceneClip* node, const SceneClip* base) {
  std::vector<const SceneClip*> out;
  for (; node && node != base; node = node->parent.get()) out.push_back(node);
  std::reverse(out.begin(), out.end());
  return out;
}

/// Starts loading the parts of `c` a replayed fill or stroke reads first (its kind and path, its state's scalars,
/// paints and shadow, its clip).
void prefetch_command(const SceneCommand& c) {
  __builtin_prefetch(&c.kind);
  __builtin_prefetch(&c.path);
  __builtin_prefetch(&c.state.transform);
  __builtin_prefetch(&c.state.fill_paint);
  __builtin_prefetch(&c.state.global_alpha);
  __builtin_prefetch(&c.state.shadow);
  __builtin_prefetch(&c.clip);
}

}  // namespace

void Canvas::draw_scene(const Scene& scene, const ScenePlan* plan) {
  Impl& s = *impl_;
  if (s.recording) {  // recording a replay: the commands are appended as they are
    for (const SceneCommand& c : scene.commands) s.recording->commands.push_back(c);
    return;
  }
  if (plan && plan->decisions.size() != scene.commands.size()) {
    throw Error("draw_scene: the plan was made for another scene");
  }
  // One level per layer being replayed (and one for the scene itself): the clip nodes pushed since it started,
  // each with its own save(), above the chain in force when it started.
  struct Level {
    const SceneClip* base = nullptr;
    std::vector<const SceneClip*> applied;
    bool layer = false;  // a real layer (end_layer() pops it) rather than a dropped one
  };
  std::vector<Level> levels(1);
  save();
  auto pop_clips = [&](Level& level) {
    for (std::size_t i = 0; i < level.applied.size(); ++i) restore();
    level.applied.clear();
  };
  auto use_clip = [&](const SceneClip* chain) {
    Level& level = levels.back();
    const std::vector<const SceneClip*> wanted = chain_above(chain, level.base);
    std::size_t same = 0;
    while (same < wanted.size() && same < level.applied.size() && wanted[same] == level.applied[same]) ++same;
    while (level.applied.size() > same) {
      restore();
      level.applied.pop_back();
    }
    for (std::size_t i = same; i < wanted.size(); ++i) {
      const SceneClip& clip = *wanted[i];
      save();
      s.state.aa = clip.aa;
      s.state.tolerance = clip.tolerance;
      s.clip_path(clip.path, clip.to_device, clip.rule);
      level.applied.push_back(&clip);
    }
  };
  // Everything but the clip. A fill takes its paint from the command (fill_path's argument), so for it the state's
  // paints and line style stay as they are: copying two paints and a dash list per call was a tenth of a frame of
  // tiny fills (docs/performance.md). A field added to SceneState is copied here too.
  auto use_state = [&](const SceneState& r, const PlanDecision* d, bool paints = true) {
    SceneState& st = s.state;
    if (paints) {
      st = r;
    } else {
      st.transform = r.transform;
      st.global_alpha = r.global_alpha;
      st.op = r.op;
      st.rule = r.rule;
      st.aa = r.aa;
      st.tolerance = r.tolerance;
      st.smoothing = r.smoothing;
      st.filter = r.filter;
      st.shadow = r.shadow;
      st.z = r.z;
    }
    if (d) st.global_alpha *= d->alpha_scale;
    if (d && d->aliased) st.aa = AntiAlias::None;
  };

  const std::size_t count = scene.commands.size();
  for (std::size_t i = 0; i < count; ++i) {
    const SceneCommand& c = scene.commands[i];
    // A command is some 800 bytes and a scene of many small fills is megabytes of them, read once: the loads of the
    // next ones are started now (what a fill reads of the command two ahead, the points of the one ahead), or each
    // call began with a wait for memory (two-thirds of this loop's time, a tenth of the frame of 20 000 tiny fills).
    if (i + 2 < count) prefetch_command(scene.commands[i + 2]);
    if (i + 1 < count) {
      const Path& next = scene.commands[i + 1].path;
      __builtin_prefetch(next.points().data());
      __builtin_prefetch(next.verbs().data());
    }
    const PlanDecision* d = plan ? &plan->decisions[i] : nullptr;
    if (d && d->action == PlanDecision::Action::Cull) continue;  // a culled layer has every command inside culled
    switch (c.kind) {
      case SceneCommand::Kind::BeginLayer: {
        use_clip(c.clip.get());
        const bool dropped = d && d->action == PlanDecision::Action::DropLayer;
        if (!dropped) {
          use_state(c.state, d);
          begin_layer(c.layer);
        }
        levels.push_back(Level{c.clip.get(), {}, !dropped});
        break;
      }
      case SceneCommand::Kind::EndLayer: {
        if (levels.size() < 2) break;  // unbalanced: the recording canvas ignored it too
        Level& level = levels.back();
        pop_clips(level);
        const bool layer = level.layer;
        levels.pop_back();
        if (layer) end_layer();
        break;
      }
      case SceneCommand::Kind::Fill:
        use_clip(c.clip.get());
        use_state(c.state, d, /*paints=*/false);
        s.fill_path(c.path, c.to_device, c.rule, c.state.fill_paint);
        break;
      case SceneCommand::Kind::Stroke:
        use_clip(c.clip.get());
        use_state(c.state, d);
        s.stroke_user_path(c.path, c.to_device);
        break;
      case SceneCommand::Kind::DrawImage:
        use_clip(c.clip.get());
        use_state(c.state, d);
        if (c.image) s.draw_image(*c.image, c.src, c.dst);
        break;
      case SceneCommand::Kind::FillMask: {
        if (!c.image) break;
        use_clip(c.clip.get());
        use_state(c.state, d);
        std::vector<std::uint8_t> coverage(static_cast<std::size_t>(c.image->width) * c.image->height);
        for (std::size_t k = 0; k < coverage.size(); ++k) coverage[k] = c.image->data[k * 4 + 3];
        fill_mask(coverage.data(), c.image->width, c.image->height, c.image->width, c.x, c.y);
        break;
      }
      case SceneCommand::Kind::PutPixels:
        if (c.image) put_pixels(*c.image, c.x, c.y);
        break;
      case SceneCommand::Kind::Fxaa:
        apply_fxaa();
        break;
      case SceneCommand::Kind::Mesh: {
        if (!c.mesh) break;
        use_clip(c.clip.get());
        use_state(c.state, d);
        MeshOptions options = c.mesh_options;
        if (d && d->front_to_back) options.front_to_back = true;
        s.draw_mesh(*c.mesh, c.to_device, options);
        break;
      }
      case SceneCommand::Kind::FloodFill:
        flood_fill(c.x, c.y, c.state.fill_paint.color(), c.seed);
        break;
    }
  }
  // A layer the scene never ended never shows (as on the canvas it was recorded from): it is discarded.
  while (levels.size() > 1) {
    pop_clips(levels.back());
    const bool layer = levels.back().layer;
    levels.pop_back();
    if (layer) s.end_layer(/*composite=*/false);
  }
  pop_clips(levels.back());
  restore();
}

namespace {

/// Sets every pixel of `box` to `fill` (four channels).
template <class T>
void fill_box(BasicImage<T>& image, const PixelBox& box, const T* fill) {
  const bool uniform = fill[0] == fill[1] && fill[1] == fill[2] && fill[2] == fill[3];
  for (int y = box.y0; y < box.y1; ++y) {
    T* px = image.pixel(box.x0, y);
    const std::size_t n = static_cast<std::size_t>(box.x1 - box.x0) * 4;
    if (uniform) {
      std::fill_n(px, n, fill[0]);  // transparent, opaque white, ...: one store pattern
    } else {
      for (std::size_t i = 0; i < n; i += 4) std::copy(fill, fill + 4, px + i);
    }
  }
}

template <class T>
void clear_regions(BasicImage<T>& image, const std::vector<PixelBox>& regions, Color background) {
  BasicImage<T> one(1, 1);
  one.clear(background);
  for (const PixelBox& r : regions) fill_box(image, r, one.data.data());
}

}  // namespace

std::vector<PixelBox> Canvas::draw_frame(const Scene& scene, const ScenePlan& plan, const ScenePlan* previous,
                                         Color background) {
  Impl& s = *impl_;
  if (s.recording) throw Error("draw_frame: the canvas is recording");
  if (!s.layers.empty()) throw Error("draw_frame: a layer is open");
  if (scene.width != s.width || scene.height != s.height || plan.width != s.width || plan.height != s.height) {
    throw Error("draw_frame: the canvas is " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                ", the scene " + std::to_string(scene.width) + "x" + std::to_string(scene.height) + ", the plan " +
                std::to_string(plan.width) + "x" + std::to_string(plan.height));
  }
  std::vector<PixelBox> regions;
  if (previous == nullptr) {
    regions.push_back(PixelBox{0, 0, s.width, s.height});
  } else {
    regions = changed_regions(plan, previous);
  }
  if (s.is16()) {
    clear_regions(*s.image16, regions, background);
  } else {
    clear_regions(*s.image8, regions, background);
  }
  draw_scene(scene, &plan);
  return regions;
}

}  // namespace vraster
