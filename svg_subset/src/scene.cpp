// svg_subset: recording a document's drawing into a scene.
#include "svg_subset/scene.hpp"

namespace vraster::svg {

Scene record_tree(const Tree& tree, int width, int height, const DrawSettings& settings, DrawStats* stats) {
  Scene scene;
  scene.width = width;
  scene.height = height;
  Canvas recorder(scene);
  if (tree.width > 0 && tree.height > 0) recorder.scale(width / tree.width, height / tree.height);
  const DrawStats drawn = draw_tree(tree, recorder, settings);
  if (stats) *stats = drawn;
  return scene;
}

}  // namespace vraster::svg
