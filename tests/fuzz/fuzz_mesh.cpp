// libFuzzer target: mesh files (.vmesh when the input starts with "vmesh", else OBJ) -> MeshRenderer on a small
// canvas, aliased and antialiased, z-buffer and painter's; OBJ models through both cameras. Parse errors are
// vraster::Error (fine); anything else (a crash, a sanitizer report, a stray exception) is a finding. The aliased
// draw of an opaque mesh with depth "none" must leave every pixel's alpha at 0 or 255.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "vraster/error.hpp"
#include "vraster/mesh.hpp"
#include "vraster/mesh_io.hpp"

namespace {

void draw_all(vraster::Mesh& mesh, int size) {
  using namespace vraster;
  if (mesh.triangles.size() > 4096) mesh.triangles.resize(4096);  // keep each run fast
  MeshRenderer renderer;
  Image image(size, size);
  for (int variant = 0; variant < 6; ++variant) {
    MeshOptions o;
    o.antialias = variant >= 3;
    o.depth = variant % 3 == 0 ? DepthMode::None : variant % 3 == 1 ? DepthMode::ZBuffer : DepthMode::Painter;
    o.shading = static_cast<Shading>(variant % 3);
    o.lighting.enabled = variant % 2 == 0;
    renderer.draw(image, mesh, o);
  }
  // Opaque, aliased, no depth: every pixel is either untouched or fully covered.
  for (MeshVertex& v : mesh.vertices) v.color.a = 1;
  Image check(size, size);
  MeshOptions o;
  o.depth = DepthMode::None;
  renderer.draw(check, mesh, o);
  for (std::size_t i = 3; i < check.data.size(); i += 4) {
    if (check.data[i] != 0 && check.data[i] != 255) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vraster;
  if (size > 3600) return 0;  // scripts/fuzz.sh's max_len for this target
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    if (text.substr(0, 5) == "vmesh") {
      MeshDocument doc = parse_vmesh(text, "fuzz.vmesh");
      draw_all(doc.mesh, 40);
    } else {
      const MeshModel model = parse_obj(text, "fuzz.obj");
      for (const bool perspective : {false, true}) {
        Camera camera;
        camera.perspective = perspective;
        Mesh mesh = project(model, camera, 40, 40, Color{0.8f, 0.5f, 0.3f, 1});
        draw_all(mesh, 40);
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
