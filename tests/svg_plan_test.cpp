// The plan never changes the picture: SVG documents that meet every planner rule (hidden shapes under a
// background, group opacity over disjoint and overlapping children, clips, masks, patterns, gradients, blend
// modes) drawn through a planned scene, a naive scene and straight onto the canvas.
#include <gtest/gtest.h>

#include <string>

#include "svg_subset/draw.hpp"
#include "svg_subset/scene.hpp"
#include "vraster/canvas.hpp"
#include "vraster/scene.hpp"

using namespace vraster;

namespace {

int max_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) worst = std::max(worst, std::abs(a.data[i] - b.data[i]));
  return worst;
}

Image from_scene(const Scene& scene, const ScenePlan* plan) {
  Image image(scene.width, scene.height);
  image.clear(Color::transparent());
  Canvas canvas(image);
  canvas.draw_scene(scene, plan);
  return image;
}

const char* const kDocuments[] = {
    // a shape under a later background, a translucent cover, an outside shape
    R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="80" height="60"><circle cx="30" cy="30" r="20" fill="red"/>
       <rect width="80" height="60" fill="#eee"/><rect x="100" width="10" height="10"/>
       <rect x="5" y="5" width="50" height="30" fill="blue" fill-opacity="0.5"/></svg>)svg",
    // group opacity over disjoint children (folded) and over overlapping ones (kept), nested groups
    R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="80" height="60"><g opacity="0.6"><rect x="2" y="2" width="20" height="20" fill="red"/>
       <circle cx="50" cy="15" r="10" fill="green"/></g><g opacity="0.5"><rect x="2" y="30" width="30" height="20" fill="blue"/>
       <rect x="20" y="35" width="30" height="20" fill="orange"/><g opacity="0.7"><circle cx="65" cy="45" r="10"/></g></g></svg>)svg",
    // clip paths, a mask, a pattern, gradients, a blend mode
    R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="80" height="60"><defs>
       <clipPath id="c"><circle cx="20" cy="20" r="15"/><rect x="30" y="5" width="10" height="30"/></clipPath>
       <mask id="m"><rect width="80" height="60" fill="white"/><circle cx="60" cy="40" r="8" fill="black"/></mask>
       <pattern id="p" width="8" height="8" patternUnits="userSpaceOnUse"><rect width="4" height="4" fill="purple"/></pattern>
       <linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1" stop-color="blue"/></linearGradient></defs>
       <rect width="80" height="60" fill="url(#p)"/><rect width="60" height="40" fill="url(#g)" clip-path="url(#c)"/>
       <g mask="url(#m)"><rect x="40" y="20" width="40" height="40" fill="url(#g)"/></g>
       <circle cx="40" cy="30" r="15" fill="yellow" style="mix-blend-mode:multiply"/></svg>)svg",
};

}  // namespace

TEST(SvgPlan, PlannedNaiveAndDirectRendersAgree) {
  for (const char* text : kDocuments) {
    SCOPED_TRACE(text);
    const svg::Tree tree = svg::parse_svg_tree(text);
    const auto [w, h] = svg::tree_output_size(tree);
    Image direct(w, h);
    direct.clear(Color::transparent());
    svg::render_tree(tree, direct);
    const Scene scene = svg::record_tree(tree, w, h);
    const ScenePlan plan = plan_scene(scene);
    EXPECT_EQ(max_difference(direct, from_scene(scene, nullptr)), 0);
    EXPECT_LE(max_difference(direct, from_scene(scene, &plan)), plan.layers_folded > 0 ? 2 : 1)
        << explain_plan(scene, plan);
  }
}

TEST(SvgPlan, TheDocumentsMeetThePlannerRules) {
  int culled = 0, folded = 0, kept_layers = 0;
  for (const char* text : kDocuments) {
    const svg::Tree tree = svg::parse_svg_tree(text);
    const auto [w, h] = svg::tree_output_size(tree);
    const Scene scene = svg::record_tree(tree, w, h);
    const ScenePlan plan = plan_scene(scene);
    culled += plan.culled;
    folded += plan.layers_folded;
    for (const PlanDecision& d : plan.decisions) {
      kept_layers += d.reason == PlanReason::LayerNeedsOverlap || d.reason == PlanReason::LayerNeedsMask;
    }
  }
  EXPECT_GE(culled, 2);
  EXPECT_GE(folded, 1);
  EXPECT_GE(kept_layers, 2);
}
