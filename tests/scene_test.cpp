// Recorded scenes and the planner (include/vraster/scene.hpp).
//
// Properties: replaying a recording draws exactly what drawing directly draws; a planned replay draws the same
// picture as the naive one (within one level per channel, from rounding in a different order) on random scenes
// built to meet every rule; and hand-made scenes get the decisions they should, for the reason they should.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>

#include "vraster/canvas.hpp"
#include "vraster/error.hpp"
#include "vraster/mesh.hpp"
#include "vraster/scene.hpp"

using namespace vraster;

namespace {

using Draw = std::function<void(Canvas&)>;
using Action = PlanDecision::Action;

Scene record(int w, int h, const Draw& draw) {
  Scene scene;
  scene.width = w;
  scene.height = h;
  Canvas recorder(scene);
  draw(recorder);
  return scene;
}

Image direct(int w, int h, const Draw& draw) {
  Image image(w, h);
  image.clear(Color::transparent());
  Canvas canvas(image);
  draw(canvas);
  return image;
}

Image replayed(const Scene& scene, const ScenePlan* plan) {
  Image image(scene.width, scene.height);
  image.clear(Color::transparent());
  Canvas canvas(image);
  canvas.draw_scene(scene, plan);
  return image;
}

int max_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) worst = std::max(worst, std::abs(a.data[i] - b.data[i]));
  return worst;
}

/// A random scene that exercises every kind of call and every planner rule: opaque covers drawn late, layers
/// of opacity 1, groups with disjoint children, clips (rectangles and circles), shadows, images, masks.
void random_scene(Canvas& c, unsigned seed) {
  std::mt19937 rng(seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  auto colour = [&](bool opaque) {
    return Color{static_cast<float>(uni(0, 1)), static_cast<float>(uni(0, 1)), static_cast<float>(uni(0, 1)),
                 opaque ? 1.f : static_cast<float>(uni(0.2, 1))};
  };
  auto shape = [&] {
    c.begin_path();
    switch (pick(3)) {
      case 0: c.rect(uni(-10, 60), uni(-10, 60), uni(1, 40), uni(1, 40)); break;
      case 1: c.rect(pick(60), pick(60), 1 + pick(30), 1 + pick(30)); break;  // whole pixels
      default: c.arc(uni(0, 64), uni(0, 64), uni(2, 20), 0, 6.283185307179586); break;
    }
  };
  Image tile(4, 3);
  tile.clear(colour(false));
  const int calls = 8 + pick(20);
  int depth = 0, layers = 0;
  for (int k = 0; k < calls; ++k) {
    switch (pick(13)) {
      case 0:
      case 1:
        c.set_fill_color(colour(pick(2) == 0));
        shape();
        c.fill();
        break;
      case 2:
        c.set_stroke_color(colour(pick(2) == 0));
        c.set_line_width(uni(0.5, 6));
        shape();
        c.stroke();
        break;
      case 3:  // an opaque cover, pixel-aligned or not
        c.set_fill_color(colour(true));
        if (pick(2)) c.fill_rect(pick(20), pick(20), 20 + pick(44), 20 + pick(44));
        else c.fill_rect(uni(0, 20), uni(0, 20), uni(20, 60), uni(20, 60));
        break;
      case 4:
        if (depth < 3) {
          c.save();
          ++depth;
          shape();
          c.clip(pick(2) ? FillRule::NonZero : FillRule::EvenOdd);
        }
        break;
      case 5:
        if (depth > 0) {
          c.restore();
          --depth;
        }
        break;
      case 6: {
        if (layers >= 2) break;
        LayerOptions options;
        options.opacity = pick(2) ? 1.f : static_cast<float>(uni(0.2, 0.9));
        if (pick(4) == 0) options.op = CompositeOp::Multiply;
        c.begin_layer(options);
        ++layers;
        const int children = 1 + pick(4);
        const bool disjoint = pick(2) == 0;
        for (int i = 0; i < children; ++i) {
          c.set_fill_color(colour(pick(2) == 0));
          if (disjoint) c.fill_rect(2 + i * 16, 2 + pick(40), 12, 10);
          else {
            shape();
            c.fill();
          }
        }
        if (pick(2)) {
          c.end_layer();
          --layers;
        }
        break;
      }
      case 7:
        if (layers > 0) {
          c.end_layer();
          --layers;
        }
        break;
      case 8:
        c.set_global_alpha(pick(3) == 0 ? 0 : uni(0.3, 1));
        break;
      case 9: {
        static const CompositeOp ops[] = {CompositeOp::SourceOver, CompositeOp::SourceOver, CompositeOp::Copy,
                                          CompositeOp::DestinationOut, CompositeOp::Screen, CompositeOp::SourceAtop};
        c.set_composite(ops[pick(6)]);
        break;
      }
      case 10:
        c.draw_image(tile, uni(-5, 50), uni(-5, 50), uni(3, 30), uni(3, 30));
        break;
      case 11:
        if (pick(2)) {
          c.set_shadow(Shadow{colour(false), uni(-4, 4), uni(-4, 4), uni(0, 3)});
        } else {
          c.set_shadow(Shadow{});
          c.clear_rect(uni(0, 50), uni(0, 50), uni(2, 20), uni(2, 20));
        }
        break;
      case 12: {  // a small mesh, opaque or not, with or without depth
        Mesh mesh;
        const bool opaque = pick(2) == 0;
        for (int v = 0; v < 6; ++v) {
          MeshVertex vertex;
          vertex.position = {uni(-5, 69), uni(-5, 69)};
          vertex.depth = uni(0, 1);
          vertex.color = colour(opaque);
          mesh.vertices.push_back(vertex);
        }
        mesh.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 2, 4}};
        MeshOptions options;
        options.shading = pick(2) ? Shading::Gouraud : Shading::Flat;
        options.depth = pick(2) ? DepthMode::ZBuffer : DepthMode::None;
        options.antialias = pick(3) == 0;
        c.draw_mesh(mesh, options);
        break;
      }
    }
  }
}

}  // namespace

TEST(Scene, ReplayingARecordingDrawsExactlyWhatDrawingDirectlyDraws) {
  for (unsigned seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Draw draw = [seed](Canvas& c) { random_scene(c, seed); };
    const Scene scene = record(64, 64, draw);
    EXPECT_EQ(max_difference(direct(64, 64, draw), replayed(scene, nullptr)), 0);
  }
}

// A replayed fill copies only the state it draws with (not the paints or the line style: its paint is the
// command's own). Each state a fill uses, set apart from the others between strokes that set the stroke's state,
// must replay as drawn: a gradient paint under a transform (the paint is mapped by it), an image pattern (with its
// own nearest filter, and under a scale), global alpha, an operator, a shadow, the aliased mode and a coarse
// tolerance on a curve. (The image smoothing and filter of the state are draw_image's, the z order's, the recorded
// fill rule the command's own: a fill does not draw with them.)
TEST(Scene, ReplayedFillsDrawWithEveryStateTheyWereRecordedWith) {
  auto tile = std::make_shared<Image>(4, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      std::uint8_t* p = tile->pixel(x, y);
      p[0] = static_cast<std::uint8_t>(60 * x);
      p[1] = static_cast<std::uint8_t>(60 * y);
      p[2] = 90;
      p[3] = 255;
    }
  }
  const std::vector<std::function<void(Canvas&)>> states = {
      [](Canvas& c) {
        Paint g = Paint::linear({0, 0}, {20, 0});
        g.add_stop(0, Color{1, 0, 0, 1});
        g.add_stop(1, Color{0, 0, 1, 1});
        c.set_fill_paint(g);
        c.translate(7.5, 3.25);
        c.rotate(0.4);
      },
      [&](Canvas& c) {
        Paint pattern = Paint::pattern(tile);
        pattern.set_transform(Affine::scale(3.7, 2.3));
        pattern.set_filter(ImageFilter::Nearest);
        c.set_fill_paint(pattern);
      },
      [&](Canvas& c) {
        Paint pattern = Paint::pattern(tile);
        pattern.set_transform(Affine::scale(3.7, 2.3));
        c.set_fill_paint(pattern);
        c.scale(1.3, 0.8);
      },
      [](Canvas& c) { c.set_global_alpha(0.45); },
      [](Canvas& c) { c.set_composite(CompositeOp::Xor); },
      [](Canvas& c) { c.set_shadow(Shadow{Color{0, 0, 0, 0.6f}, 3, 2, 1.5}); },
      [](Canvas& c) { c.set_anti_alias(AntiAlias::None); },
      [](Canvas& c) { c.set_tolerance(3); },
  };
  for (std::size_t k = 0; k < states.size(); ++k) {
    SCOPED_TRACE("state " + std::to_string(k));
    const Draw draw = [&](Canvas& c) {
      c.set_fill_color(Color{0.2f, 0.6f, 0.3f, 1});
      c.fill_rect(4, 4, 40, 30);
      c.save();
      states[k](c);
      c.begin_path();
      c.arc(30, 30, 18, 0, 6.283185307179586);
      c.fill();
      c.restore();
      // A stroke with its own paint and line style between the fills (what a fill's replay leaves as it is).
      c.set_stroke_color(Color{0.9f, 0.1f, 0.5f, 0.8f});
      c.set_line_width(3);
      const double dashes[] = {4, 2};
      c.set_line_dash(dashes);
      c.stroke_rect(10, 12, 30, 25);
      c.fill_rect(40, 40, 15, 15);
    };
    const Image want = direct(64, 64, draw);
    EXPECT_EQ(max_difference(want, replayed(record(64, 64, draw), nullptr)), 0);
    // (the state makes a difference: the same picture without it differs)
    const Draw plain = [&](Canvas& c) {
      c.set_fill_color(Color{0.2f, 0.6f, 0.3f, 1});
      c.fill_rect(4, 4, 40, 30);
      c.begin_path();
      c.arc(30, 30, 18, 0, 6.283185307179586);
      c.fill();
    };
    Image state_only(64, 64), plain_only(64, 64);
    state_only.clear(Color::transparent());
    plain_only.clear(Color::transparent());
    {
      Canvas c(state_only);
      c.set_fill_color(Color{0.2f, 0.6f, 0.3f, 1});
      c.fill_rect(4, 4, 40, 30);
      states[k](c);
      c.begin_path();
      c.arc(30, 30, 18, 0, 6.283185307179586);
      c.fill();
    }
    {
      Canvas c(plain_only);
      plain(c);
    }
    EXPECT_GT(max_difference(state_only, plain_only), 0);
  }
}

TEST(Scene, APlannedRenderDrawsTheNaivePicture) {
  int culled = 0, dropped = 0, folded = 0;
  for (unsigned seed = 1; seed <= 1000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = record(64, 64, [seed](Canvas& c) { random_scene(c, seed); });
    const ScenePlan plan = plan_scene(scene);
    ASSERT_EQ(plan.decisions.size(), scene.commands.size());
    // A folded opacity is applied to the exact colour, where the naive render first rounds the layer to 8 bits
    // and then applies its opacity (quantised on its own path): those two roundings can add up to two levels.
    EXPECT_LE(max_difference(replayed(scene, nullptr), replayed(scene, &plan)), plan.layers_folded > 0 ? 2 : 1)
        << explain_plan(scene, plan);
    culled += plan.culled;
    dropped += plan.layers_dropped;
    folded += plan.layers_folded;
  }
  // The scenes meet every rule often enough for the comparison to mean something.
  EXPECT_GT(culled, 100);
  EXPECT_GT(dropped, 20);
  EXPECT_GT(folded, 10);
}

TEST(ScenePlanner, CallsUnderALaterOpaqueRectangleAreCulled) {
  const Scene scene = record(100, 80, [](Canvas& c) {
    c.set_fill_color({1, 0, 0, 1});
    c.begin_path();
    c.arc(30, 30, 20, 0, 6.3);
    c.fill();                        // #0: hidden by #2
    c.fill_rect(90, 10, 30, 30);     // #1: reaches past the cover: kept
    c.set_fill_color({0, 0, 1, 1});
    c.fill_rect(0, 0, 80, 80);       // #2: the cover (opaque, whole pixels)
  });
  const ScenePlan plan = plan_scene(scene);
  EXPECT_EQ(plan.decisions[0].action, Action::Cull);
  EXPECT_EQ(plan.decisions[0].reason, PlanReason::Hidden);
  EXPECT_EQ(plan.decisions[0].ref, 2);
  EXPECT_EQ(describe_decision(scene, plan, 0), "hidden under #2, which overwrites every pixel it can change");
  EXPECT_EQ(plan.decisions[1].action, Action::Draw);
  EXPECT_EQ(plan.decisions[2].action, Action::Draw);
  EXPECT_TRUE(plan.decisions[2].aliased);
  EXPECT_EQ(plan.culled, 1);
}

TEST(ScenePlanner, TranslucentOrClippedCoversHideNothing) {
  const Scene scene = record(64, 64, [](Canvas& c) {
    c.fill_rect(10, 10, 10, 10);  // #0
    c.set_fill_color({0, 0, 1, 0.5f});
    c.fill_rect(0, 0, 64, 64);    // #1: translucent
    c.save();
    c.begin_path();
    c.arc(32, 32, 30, 0, 6.3);
    c.clip();                     // an antialiased clip: its edge pixels blend
    c.set_fill_color({0, 0, 1, 1});
    c.fill_rect(0, 0, 64, 64);    // #2
    c.restore();
    c.set_fill_color({0, 1, 0, 1});
    c.fill_rect(0.5, 0.5, 40, 40);  // #3: not whole pixels: covers only [1, 40)
  });
  const ScenePlan plan = plan_scene(scene);
  EXPECT_EQ(plan.decisions[0].action, Action::Cull) << "hidden by #3, whose interior [1,40) contains [9,21)";
  EXPECT_EQ(plan.decisions[0].ref, 3);
  EXPECT_EQ(plan.decisions[1].action, Action::Draw);  // reaches pixel row 0, which #3 only half covers
  EXPECT_EQ(plan.decisions[2].action, Action::Draw);
}

TEST(ScenePlanner, InvisibleEmptyAndOutsideCallsAreCulled) {
  const Scene scene = record(50, 50, [](Canvas& c) {
    c.fill_rect(60, 60, 10, 10);  // #0 outside the canvas
    c.save();
    c.begin_path();
    c.rect(0, 0, 10, 10);
    c.clip();
    c.fill_rect(20, 20, 10, 10);  // #1 outside the clip
    c.restore();
    c.set_fill_color({1, 0, 0, 0});
    c.fill_rect(5, 5, 10, 10);    // #2 transparent paint
    c.set_fill_color({1, 0, 0, 1});
    c.set_global_alpha(0);
    c.fill_rect(5, 5, 10, 10);    // #3 alpha 0
    c.set_composite(CompositeOp::Copy);
    c.fill_rect(5, 5, 10, 10);    // #4 copy with alpha 0 clears the clip region: kept
    c.set_global_alpha(1);
    c.set_composite(CompositeOp::SourceOver);
    c.begin_path();
    c.move_to(1, 1);
    c.line_to(40, 1);
    c.line_to(20, 1);
    c.fill();                     // #5 zero area
  });
  const ScenePlan plan = plan_scene(scene);
  ASSERT_EQ(plan.decisions.size(), 6u);
  EXPECT_EQ(plan.decisions[0].reason, PlanReason::OutsideCanvas);
  EXPECT_EQ(plan.decisions[1].reason, PlanReason::OutsideClip);
  EXPECT_EQ(describe_decision(scene, plan, 2), "transparent paint with source-over: changes nothing");
  EXPECT_EQ(plan.decisions[3].reason, PlanReason::GlobalAlphaZero);
  EXPECT_EQ(plan.decisions[4].action, Action::Draw);
  EXPECT_EQ(plan.decisions[5].reason, PlanReason::ZeroArea);
  EXPECT_EQ(plan.culled, 5);
}

TEST(ScenePlanner, LayersAreDroppedOrFoldedOnlyWhenThePictureStaysTheSame) {
  const Draw draw = [](Canvas& c) {
    c.begin_layer(1.f);  // #0: opacity 1, source-over inside: dropped
    c.set_fill_color({1, 0, 0, 0.5f});
    c.fill_rect(2, 2, 20, 20);
    c.fill_rect(10, 10, 20, 20);
    c.end_layer();       // #3
    c.begin_layer(0.5f);  // #4: disjoint children: folded
    c.set_fill_color({0, 1, 0, 1});
    c.fill_rect(40, 2, 10, 10);
    c.fill_rect(40, 20, 10, 10);
    c.end_layer();        // #7
    c.begin_layer(0.5f);  // #8: overlapping children: kept
    c.fill_rect(2, 40, 20, 20);
    c.fill_rect(10, 45, 20, 20);
    c.end_layer();        // #11
    c.begin_layer(1.f);   // #12: multiply inside: kept
    c.set_composite(CompositeOp::Multiply);
    c.fill_rect(40, 40, 20, 20);
    c.end_layer();        // #14
  };
  const Scene scene = record(64, 64, draw);
  const ScenePlan plan = plan_scene(scene);
  EXPECT_EQ(plan.decisions[0].action, Action::DropLayer);
  EXPECT_EQ(plan.decisions[3].action, Action::DropLayer);
  EXPECT_EQ(plan.decisions[4].action, Action::DropLayer);
  EXPECT_FLOAT_EQ(plan.decisions[5].alpha_scale, 0.5f);
  EXPECT_EQ(plan.decisions[8].action, Action::Draw);
  EXPECT_EQ(plan.decisions[8].reason, PlanReason::LayerNeedsOverlap);
  EXPECT_EQ(describe_decision(scene, plan, 4),
            "layer folded: opacity 0.5 goes into each of 2 children, which touch disjoint pixels");
  EXPECT_EQ(plan.decisions[12].action, Action::Draw);
  EXPECT_EQ(plan.decisions[12].reason, PlanReason::LayerNeedsIsolation);
  EXPECT_EQ(plan.layers_dropped, 1);
  EXPECT_EQ(plan.layers_folded, 1);
  EXPECT_LE(max_difference(direct(64, 64, draw), replayed(scene, &plan)), 1);
}

TEST(ScenePlanner, APostFilterStopsOcclusion) {
  const Scene scene = record(32, 32, [](Canvas& c) {
    c.set_anti_alias(AntiAlias::None);
    c.begin_path();
    c.move_to(2, 2);
    c.line_to(30, 5);
    c.line_to(6, 30);
    c.fill();                 // #0
    c.apply_fxaa();           // #1 reads the neighbours of every pixel
    c.fill_rect(0, 0, 32, 32);  // #2
  });
  const ScenePlan plan = plan_scene(scene);
  EXPECT_EQ(plan.decisions[0].action, Action::Draw);
}

TEST(ScenePlanner, ExplainNamesEveryCommandAndSummarises) {
  const Scene scene = record(128, 128, [](Canvas& c) {
    c.fill_rect(10, 10, 5, 5);
    c.fill_rect(0, 0, 128, 128);
  });
  const ScenePlan plan = plan_scene(scene);
  const std::string text = explain_plan(scene, plan);
  EXPECT_NE(text.find("#0     fill   cull"), std::string::npos) << text;
  EXPECT_NE(text.find("#1     fill   draw"), std::string::npos) << text;
  EXPECT_NE(text.find("summary: 2 commands, 1 culled"), std::string::npos) << text;
  EXPECT_NE(text.find("tiles touched: 4 of 4"), std::string::npos) << text;
  const std::string json = explain_plan_json(scene, plan);
  EXPECT_NE(json.find("\"action\":\"cull\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"ref\":1"), std::string::npos) << json;
  EXPECT_NE(json.find("\"culled\":1"), std::string::npos) << json;
}

TEST(ScenePlanner, TilesCountOnlyWhatKeptCallsTouch) {
  const Scene scene = record(256, 256, [](Canvas& c) { c.fill_rect(70, 70, 40, 40); });
  const ScenePlan plan = plan_scene(scene);
  EXPECT_EQ(plan.tiles_x * plan.tiles_y, 16);
  EXPECT_EQ(plan.touched_tile_count(), 1);  // [69, 111) with its antialiasing margin stays in tile (1, 1)
}

TEST(Scene, RecordingCanvasDrawsNothingAndReadsTransparentPixels) {
  Scene scene;
  scene.width = 8;
  scene.height = 8;
  Canvas recorder(scene);
  recorder.fill_rect(0, 0, 8, 8);
  const Image px = recorder.get_pixels(0, 0, 2, 2);
  for (const auto v : px.data) EXPECT_EQ(v, 0);
  EXPECT_EQ(scene.commands.size(), 1u);
  Scene bad;
  EXPECT_THROW({ Canvas c(bad); }, Error);  // a 0 x 0 scene
}

TEST(ScenePlanner, AFloodFillReadsWhatCameBefore) {
  const Draw draw = [](Canvas& c) {
    c.set_anti_alias(AntiAlias::None);
    c.fill_rect(10, 0, 2, 32);                                      // #0: a wall the fill stops at
    c.flood_fill(2, 2, Color{1, 0, 0, 1});                           // #1: fills left of the wall only
    c.set_fill_color({0, 0, 1, 1});
    c.fill_rect(8, 0, 8, 32);                                       // #2: covers the wall afterwards
  };
  const Scene scene = record(32, 32, draw);
  const ScenePlan plan = plan_scene(scene);
  EXPECT_EQ(plan.decisions[0].action, Action::Draw);  // hidden by #2, but #1 reads it
  const Image planned = replayed(scene, &plan);
  EXPECT_EQ(max_difference(direct(32, 32, draw), planned), 0);
  EXPECT_EQ(planned.pixel(2, 2)[0], 255);
  EXPECT_EQ(planned.pixel(20, 2)[3], 0);  // right of the wall: not filled
}

TEST(CanvasFloodFill, EqualsTheLibraryFillOnTheTarget) {
  Image a(24, 24), b(24, 24);
  for (Image* img : {&a, &b}) {
    img->clear(Color::transparent());
    Canvas c(*img);
    c.set_anti_alias(AntiAlias::None);
    c.begin_path();
    c.arc(12, 12, 8, 0, 6.283185307179586);
    c.set_line_width(1.5);
    c.stroke();
  }
  SeedFillOptions options;
  options.connectivity = Connectivity::Eight;
  options.tolerance = 0.1;
  const std::int64_t expected = flood_fill(a, 12, 12, Color{0, 1, 0, 1}, options);
  Canvas c(b);
  c.translate(100, 100);  // device pixels: the transform does not apply
  EXPECT_EQ(c.flood_fill(12, 12, Color{0, 1, 0, 1}, options), expected);
  EXPECT_GT(expected, 100);
  EXPECT_EQ(max_difference(a, b), 0);
  EXPECT_EQ(c.flood_fill(12, 12, Color{NAN, 1, 0, 1}, options), 0);
  options.tolerance = 2;
  EXPECT_THROW(c.flood_fill(12, 12, Color{0, 0, 0, 1}, options), Error);
}

TEST(SceneDepth, CallsAreDrawnInIncreasingZAndLayersMoveAsOneBlock) {
  auto rect = [](Canvas& c, Color colour, double x) {
    c.set_fill_color(colour);
    c.fill_rect(x, 0, 20, 20);
  };
  const Color red{1, 0, 0, 1}, green{0, 1, 0, 1}, blue{0, 0, 1, 1};
  const Scene scene = record(40, 20, [&](Canvas& c) {
    c.set_z(2);
    rect(c, red, 0);     // nearest: on top
    c.set_z(0);
    rect(c, green, 10);  // farthest
    c.set_z(1);
    c.begin_layer(1.f);  // the layer moves with z 1; inside, its own order
    c.set_z(5);
    rect(c, blue, 5);
    c.set_z(-5);
    rect(c, green, 15);
    c.end_layer();
  });
  const Scene ordered = order_by_depth(scene);
  ASSERT_EQ(ordered.commands.size(), scene.commands.size());
  const Image expected = direct(40, 20, [&](Canvas& c) {
    rect(c, green, 10);
    c.begin_layer(1.f);
    rect(c, green, 15);
    rect(c, blue, 5);
    c.end_layer();
    rect(c, red, 0);
  });
  const ScenePlan plan = plan_scene(ordered);
  EXPECT_EQ(max_difference(expected, replayed(ordered, &plan)), 0);
  EXPECT_EQ(replayed(ordered, nullptr).pixel(7, 5)[0], 255);    // red over blue
  EXPECT_EQ(replayed(ordered, nullptr).pixel(22, 5)[2], 255);   // blue over the inner green
  Scene equal = record(40, 20, [&](Canvas& c) {  // equal depths keep their order
    rect(c, red, 0);
    rect(c, green, 10);
  });
  EXPECT_EQ(max_difference(replayed(order_by_depth(equal), nullptr), replayed(equal, nullptr)), 0);
}

namespace {

/// A soup of opaque triangles over each other (every triangle overlaps many), with exact depth ties: triangles
/// repeated with another colour at the same depths, and triangles in one plane.
Mesh overlapping_soup(unsigned seed, int triangles, double size) {
  std::mt19937 rng(seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  Mesh mesh;
  for (int t = 0; t < triangles; ++t) {
    const double cx = uni(0, size), cy = uni(0, size), r = uni(size / 8, size / 3);
    // Surfaces of real meshes: each triangle near one depth, a third of them in the plane z = 0.5 (ties).
    const bool in_plane = rng() % 3 == 0;
    const double base = uni(0, 1);
    const bool tie = t > 0 && rng() % 4 == 0;  // the previous triangle again, another colour, the same depths
    for (int k = 0; k < 3; ++k) {
      MeshVertex v;
      if (tie) {
        v = mesh.vertices[mesh.vertices.size() - 3];
      } else {
        v.position = {cx + r * std::cos(uni(0, 6.3)), cy + r * std::sin(uni(0, 6.3))};
        // In the plane: depths within 1e-8 of 0.5, which all round to the same float depth, but give the
        // triangles different nearest vertices (so the nearest-first order is not the given one among them).
        v.depth = in_plane ? 0.5 + uni(-1e-8, 1e-8) : base + uni(-0.05, 0.05);
        v.normal = {static_cast<float>(uni(-1, 1)), static_cast<float>(uni(-1, 1)), -1};
      }
      v.color = {static_cast<float>(uni(0, 1)), static_cast<float>(uni(0, 1)), static_cast<float>(uni(0, 1)), 1};
      mesh.vertices.push_back(v);
    }
    const auto i = static_cast<std::uint32_t>(3 * t);
    mesh.triangles.push_back({i, i + 1, i + 2});
  }
  return mesh;
}

}  // namespace

TEST(SceneMesh, FrontToBackDrawsExactlyTheGivenOrdersPictureAndShadesLess) {
  std::int64_t shaded_naive = 0, shaded_planned = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Mesh mesh = overlapping_soup(seed, 60, 48);
    for (const Shading shading : {Shading::Flat, Shading::Gouraud, Shading::Phong}) {
      MeshOptions options;
      options.shading = shading;
      options.lighting.enabled = true;
      // Half the runs start from a depth buffer something else wrote, which keeps its pixels on ties.
      DepthBuffer given(48, 48), ordered(48, 48);
      if (seed % 2 == 0) {
        for (int y = 0; y < 48; ++y) {
          for (int x = 0; x < 48; ++x) given.row(y)[x] = ordered.row(y)[x] = (x + y) % 3 == 0 ? 0.5f : DepthBuffer::kFar;
        }
      }
      Image a(48, 48), b(48, 48);
      a.clear(Color::transparent());
      b.clear(Color::transparent());
      MeshRenderer renderer;
      renderer.draw(a, mesh, options, &given);
      const MeshStats naive = renderer.stats();
      options.front_to_back = true;
      renderer.draw(b, mesh, options, &ordered);
      const MeshStats planned = renderer.stats();
      EXPECT_TRUE(planned.drew_front_to_back);
      EXPECT_EQ(a.data, b.data);
      for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 48; ++x) ASSERT_EQ(given.at(x, y), ordered.at(x, y)) << x << "," << y;
      }
      EXPECT_EQ(naive.fragments, planned.fragments);
      shaded_naive += naive.fragments_shaded;
      shaded_planned += planned.fragments_shaded;
    }
  }
  // Nearest first is a heuristic for triangles that span depths (a single mesh may shade a little more), but
  // over many it shades clearly less.
  EXPECT_LT(shaded_planned * 10, shaded_naive * 9) << shaded_planned << " of " << shaded_naive;
}

TEST(SceneMesh, FrontToBackIsIgnoredWhereTheOrderMatters) {
  Mesh mesh = overlapping_soup(7, 30, 40);
  MeshOptions options;
  options.front_to_back = true;
  MeshRenderer renderer;
  Image image(40, 40);
  mesh.vertices[4].color.a = 0.5f;  // one translucent vertex: blending order matters
  renderer.draw(image, mesh, options);
  EXPECT_FALSE(renderer.stats().drew_front_to_back);
  mesh.vertices[4].color.a = 1;
  options.write_depth = false;
  renderer.draw(image, mesh, options);
  EXPECT_FALSE(renderer.stats().drew_front_to_back);
  options.write_depth = true;
  options.depth = DepthMode::Painter;
  renderer.draw(image, mesh, options);
  EXPECT_FALSE(renderer.stats().drew_front_to_back);
  options.depth = DepthMode::ZBuffer;
  renderer.draw(image, mesh, options);
  EXPECT_TRUE(renderer.stats().drew_front_to_back);
}

TEST(SceneMesh, TheCanvasDrawsAMeshAsTheSameRectangleFilled) {
  // Two aliased triangles making the rectangle [8, 40) x [4, 28) after the transform: the same pixels as
  // fill_rect, under a rectangular clip, with an operator (through a layer) and with global alpha.
  Mesh mesh;
  for (const Point p : {Point{4, 2}, Point{20, 2}, Point{20, 14}, Point{4, 14}}) {
    MeshVertex v;
    v.position = p;
    v.color = {0.2f, 0.6f, 1, 1};
    mesh.vertices.push_back(v);
  }
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  MeshOptions options;
  options.shading = Shading::Flat;
  for (const CompositeOp op : {CompositeOp::SourceOver, CompositeOp::Xor, CompositeOp::Copy}) {
    for (const float alpha : {1.f, 0.5f}) {
      SCOPED_TRACE(std::string(to_string(op)) + " alpha " + std::to_string(alpha));
      auto scene = [&](Canvas& c, bool as_mesh) {
        c.set_fill_color({1, 0, 0, 0.75f});
        c.fill_rect(0, 0, 48, 32);
        c.rect(12, 0, 40, 20);
        c.clip();
        c.set_composite(op);
        c.set_global_alpha(alpha);
        c.scale(2, 2);
        if (as_mesh) {
          c.draw_mesh(mesh, options);
        } else {
          c.set_fill_color({0.2f, 0.6f, 1, 1});
          c.fill_rect(4, 2, 16, 12);
        }
      };
      const Image expected = direct(48, 32, [&](Canvas& c) { scene(c, false); });
      const Image drawn = direct(48, 32, [&](Canvas& c) { scene(c, true); });
      EXPECT_LE(max_difference(expected, drawn), 1);
      // Recorded and replayed, planned or not: the same.
      const Scene recorded = record(48, 32, [&](Canvas& c) { scene(c, true); });
      EXPECT_EQ(max_difference(drawn, replayed(recorded, nullptr)), 0);
      const ScenePlan plan = plan_scene(recorded);
      EXPECT_EQ(max_difference(drawn, replayed(recorded, &plan)), 0);
    }
  }
}

TEST(SceneMesh, ThePlannerDrawsOpaqueDepthMeshesFrontToBackAndKeepsGroupsOverMeshes) {
  const Mesh soup = overlapping_soup(3, 40, 64);
  Mesh translucent = soup;
  for (MeshVertex& v : translucent.vertices) v.color.a = 0.6f;
  const Scene scene = record(64, 64, [&](Canvas& c) {
    MeshOptions options;
    options.shading = Shading::Phong;
    options.lighting.enabled = true;
    c.draw_mesh(soup, options);          // #0: front to back
    c.draw_mesh(translucent, options);   // #1: blending order matters
    options.antialias = true;
    c.draw_mesh(soup, options);          // #2: the antialiased accumulation keeps its order
    options.antialias = false;
    c.begin_layer(0.5f);                 // #3: a group opacity over a mesh's overlapping triangles
    c.draw_mesh(soup, options);          // #4: inside a kept layer of opacity 0.5
    c.end_layer();                       // #5
    c.translate(500, 0);
    c.draw_mesh(soup, options);          // #6: outside
    c.draw_mesh(Mesh{}, options);        // #7: nothing
  });
  const ScenePlan plan = plan_scene(scene);
  ASSERT_EQ(plan.decisions.size(), 8u);
  EXPECT_TRUE(plan.decisions[0].front_to_back);
  EXPECT_FALSE(plan.decisions[1].front_to_back);
  EXPECT_FALSE(plan.decisions[2].front_to_back);
  EXPECT_EQ(plan.decisions[3].action, Action::Draw);
  EXPECT_EQ(plan.decisions[3].reason, PlanReason::LayerNeedsOverlap);
  EXPECT_TRUE(plan.decisions[4].front_to_back);
  EXPECT_EQ(plan.decisions[6].reason, PlanReason::OutsideCanvas);
  EXPECT_EQ(plan.decisions[7].reason, PlanReason::ZeroArea);
  EXPECT_EQ(plan.front_to_back, 2);
  EXPECT_EQ(max_difference(replayed(scene, nullptr), replayed(scene, &plan)), 0);
  const std::string text = explain_plan(scene, plan);
  EXPECT_NE(text.find("nearest triangles first"), std::string::npos) << text;
  EXPECT_NE(text.find("2 meshes front to back"), std::string::npos) << text;
}

TEST(SceneFrames, RedrawingOnlyTheChangedTilesGivesTheFullRedraw) {
  // A sequence of frames into one image, each cleared only where it or the frame before touches: every frame is
  // what a full clear and redraw gives, and the pixels that changed between frames lie inside the regions returned.
  const Color background{0.9f, 0.9f, 0.8f, 1};
  Image frames(200, 150);
  ScenePlan previous;
  int partial_frames = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("frame " + std::to_string(seed));
    const Scene scene = record(200, 150, [seed](Canvas& c) {
      // A small scene somewhere in the big canvas (most tiles stay untouched), sometimes with a post-filter.
      c.translate(static_cast<double>(seed * 37 % 140), static_cast<double>(seed * 53 % 90));
      random_scene(c, seed);
    });
    const ScenePlan plan = plan_scene(scene);
    const Image before = frames;
    const std::vector<PixelBox> regions =
        Canvas(frames).draw_frame(scene, plan, seed == 1 ? nullptr : &previous, background);
    Image full(200, 150);
    full.clear(background);
    {
      Canvas canvas(full);
      canvas.draw_scene(scene, &plan);
    }
    ASSERT_EQ(max_difference(frames, full), 0);
    std::int64_t area = 0;
    for (const PixelBox& r : regions) {
      EXPECT_TRUE(r.x0 >= 0 && r.y0 >= 0 && r.x1 <= 200 && r.y1 <= 150 && !r.empty());
      area += r.area();
    }
    for (int y = 0; y < 150; ++y) {
      for (int x = 0; x < 200; ++x) {
        if (std::equal(before.pixel(x, y), before.pixel(x, y) + 4, frames.pixel(x, y))) continue;
        const bool inside = std::any_of(regions.begin(), regions.end(), [&](const PixelBox& r) {
          return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
        });
        ASSERT_TRUE(inside || seed == 1) << "pixel " << x << "," << y << " changed outside the regions";
      }
    }
    // The regions are disjoint tiles: their area is that of the tiles either frame touches.
    std::int64_t tiles_area = 0;
    for (int ty = 0; ty < plan.tiles_y; ++ty) {
      for (int tx = 0; tx < plan.tiles_x; ++tx) {
        const std::size_t i = static_cast<std::size_t>(ty) * plan.tiles_x + tx;
        if (seed > 1 && !plan.touched_tiles[i] && !previous.touched_tiles[i]) continue;
        tiles_area += std::int64_t{std::min(64, 200 - 64 * tx)} * std::min(64, 150 - 64 * ty);
      }
    }
    EXPECT_EQ(area, tiles_area);
    if (area < 200 * 150) ++partial_frames;
    previous = plan;
  }
  // Scenes whose operators change only what they draw leave most tiles alone.
  EXPECT_GT(partial_frames, 10);
}

TEST(SceneFrames, ChangedRegionsMergeTouchedTilesAndRejectOtherSizes) {
  ScenePlan plan;
  plan.width = 150, plan.height = 100, plan.tile_size = 64, plan.tiles_x = 3, plan.tiles_y = 2;
  // touched:  X X .      regions: [0,128)x[0,64) and [0,150)x[64,100)
  //           X X X      (cut to the canvas along the right and bottom edges)
  plan.touched_tiles = {1, 1, 0, 1, 1, 1};
  const std::vector<PixelBox> regions = changed_regions(plan);
  ASSERT_EQ(regions.size(), 2u);  // the runs [0,128) and [0,150) differ, so they do not merge
  EXPECT_EQ(regions[0].x0, 0);
  EXPECT_EQ(regions[0].x1, 128);
  EXPECT_EQ(regions[0].y1, 64);
  EXPECT_EQ(regions[1].x1, 150);
  EXPECT_EQ(regions[1].y0, 64);
  EXPECT_EQ(regions[1].y1, 100);
  ScenePlan other = plan;
  other.touched_tiles = {0, 0, 1, 0, 0, 0};
  const std::vector<PixelBox> both = changed_regions(plan, &other);
  ASSERT_EQ(both.size(), 1u);  // every tile of one frame or the other: the whole canvas
  EXPECT_EQ(both[0].x1, 150);
  EXPECT_EQ(both[0].y1, 100);
  ScenePlan smaller = plan;
  smaller.width = 100;
  EXPECT_THROW(changed_regions(plan, &smaller), Error);
  Image image(150, 99);
  Scene scene;
  scene.width = 150, scene.height = 100;
  EXPECT_THROW(Canvas(image).draw_frame(scene, plan, nullptr, Color::transparent()), Error);
  Image right(150, 100);
  Canvas inside_a_layer(right);
  inside_a_layer.begin_layer(0.5f);
  EXPECT_THROW(inside_a_layer.draw_frame(scene, plan, nullptr, Color::transparent()), Error);
}
