// vraster mesh / shading / depth: triangle meshes from files, and two sheets built in code.
//
//   mesh:    read a .vmesh (device-space mesh) or an OBJ (3D model -> camera) -> MeshRenderer -> PNG
//   shading: a lit sphere and torus, each under flat, Gouraud and Phong shading, side by side
//   depth:   interpenetrating triangles and three cyclically overlapping bars, painter's order beside the z-buffer
#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <string>

#include "cli/bitmap_font.hpp"
#include "cli/cli.hpp"
#include "vraster/error.hpp"
#include "vraster/mesh.hpp"
#include "vraster/mesh_io.hpp"
#include "vraster/png.hpp"

namespace vraster::cli {
namespace {

constexpr Color kInk = {0.12f, 0.16f, 0.22f, 1.f};

double number_arg(std::string_view flag, std::string_view text, double lo, double hi) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !(v >= lo && v <= hi)) {
    throw UsageError{std::string(flag) + ": '" + std::string(text) + "' is not a number from " + std::to_string(lo) +
                     " to " + std::to_string(hi)};
  }
  return v;
}

// A colour written #rgb, #rrggbb, #rrggbbaa or "transparent" (the .vmesh syntax, parsed by the same reader).
Color color_arg(std::string_view flag, std::string_view text) {
  try {
    return parse_vmesh("vmesh 1\nbackground " + std::string(text) + "\n", std::string(flag)).background;
  } catch (const Error&) {
    throw UsageError{std::string(flag) + ": '" + std::string(text) + "' is not a colour (#rrggbb or transparent)"};
  }
}

bool ends_with_obj(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".obj";
}

void paste(Image& sheet, const Image& panel, int ox, int oy) {
  for (int y = 0; y < panel.height; ++y) {
    std::copy(panel.pixel(0, y), panel.pixel(0, y) + panel.width * 4, sheet.pixel(ox, oy + y));
  }
}

// A sheet of columns x rows panels with a label under each column.
struct Sheet {
  int panel, columns, rows;
  static constexpr int kMargin = 12, kLabel = 22;
  Image image;
  Sheet(int panel_size, int c, int r)
      : panel(panel_size), columns(c), rows(r),
        image(c * (panel_size + kMargin) + kMargin, r * (panel_size + kMargin) + kMargin + kLabel) {
    image.clear(Color{1, 1, 1, 1});
  }
  void put(const Image& p, int column, int row) {
    paste(image, p, kMargin + column * (panel + kMargin), kMargin + row * (panel + kMargin));
  }
  void label(int column, std::string_view text) {
    const int x = kMargin + column * (panel + kMargin) + (panel - label_width(text, 2)) / 2;
    draw_label(image, x, kMargin + rows * (panel + kMargin), text, kInk, 2);
  }
};

}  // namespace

int run_mesh(int argc, char** argv) {
  std::string input, output;
  MeshOptions options;
  Camera camera;
  int width = 512, height = 512, bits = 8;
  bool background_set = false;
  Color background{1, 1, 1, 1};
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw UsageError{std::string(arg) + " needs a value"};
      return argv[++i];
    };
    if (arg == "-o" || arg == "--output") {
      output = value();
    } else if (arg == "--shading") {
      const auto v = value();
      if (!parse_shading(v, options.shading)) throw UsageError{"--shading: flat, gouraud or phong, not '" + std::string(v) + "'"};
    } else if (arg == "--depth") {
      const auto v = value();
      if (!parse_depth_mode(v, options.depth)) throw UsageError{"--depth: zbuffer, painter or none, not '" + std::string(v) + "'"};
    } else if (arg == "--aa") {
      options.antialias = true;
    } else if (arg == "--cull") {
      options.cull_back_faces = true;
    } else if (arg == "--camera") {
      const auto v = value();
      if (v != "ortho" && v != "perspective") throw UsageError{"--camera: ortho or perspective"};
      camera.perspective = v == "perspective";
    } else if (arg == "--yaw") {
      camera.yaw = number_arg(arg, value(), -360, 360) * M_PI / 180;
    } else if (arg == "--pitch") {
      camera.pitch = number_arg(arg, value(), -360, 360) * M_PI / 180;
    } else if (arg == "--distance") {
      camera.distance = number_arg(arg, value(), 1.01, 1000);
    } else if (arg == "--width") {
      width = static_cast<int>(number_arg(arg, value(), 1, 8192));
    } else if (arg == "--height") {
      height = static_cast<int>(number_arg(arg, value(), 1, 8192));
    } else if (arg == "--bits") {
      bits = static_cast<int>(number_arg(arg, value(), 8, 16));
      if (bits != 8 && bits != 16) throw UsageError{"--bits must be 8 or 16"};
    } else if (arg == "--background") {
      background = color_arg(arg, value());
      background_set = true;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError{"mesh: unknown option '" + std::string(arg) + "'"};
    } else if (input.empty()) {
      input = arg;
    } else {
      throw UsageError{"mesh: more than one input file given"};
    }
  }
  if (input.empty()) throw UsageError{"mesh: no input file"};
  if (output.empty()) throw UsageError{"mesh: no output file (-o OUT.png)"};

  const std::string text = read_mesh_file(input);
  Mesh mesh;
  if (ends_with_obj(input)) {
    mesh = project(parse_obj(text, input), camera, width, height, Color{0.85f, 0.55f, 0.3f, 1});
    options.lighting.enabled = true;
    options.lighting.perspective_view = camera.perspective;
  } else {
    MeshDocument doc = parse_vmesh(text, input);
    width = doc.width, height = doc.height;
    if (!background_set) background = doc.background;
    options.lighting.enabled = doc.lit;
    mesh = std::move(doc.mesh);
  }
  MeshRenderer renderer;
  if (bits == 16) {
    Image16 image(width, height);
    image.clear(background);
    renderer.draw(image, mesh, options);
    write_png(output, image);
  } else {
    Image image(width, height);
    image.clear(background);
    renderer.draw(image, mesh, options);
    write_png(output, image);
  }
  const MeshStats& s = renderer.stats();
  std::cout << "vraster mesh: wrote " << output << " (" << width << "x" << height << ", " << s.triangles_drawn
            << " triangles drawn, " << s.triangles_skipped << " skipped)\n";
  return 0;
}

namespace {

int panel_arg(int argc, char** argv, std::string& output, bool& aa, const char* command) {
  int panel = 220;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) throw UsageError{std::string(arg) + " needs a value"};
      return argv[++i];
    };
    if (arg == "-o" || arg == "--output") {
      output = value();
    } else if (arg == "--panel") {
      panel = static_cast<int>(number_arg(arg, value(), 32, 2048));
    } else if (arg == "--aa") {
      aa = true;
    } else {
      throw UsageError{std::string(command) + ": unknown argument '" + std::string(arg) + "'"};
    }
  }
  if (output.empty()) throw UsageError{std::string(command) + ": no output file (-o SHEET.png)"};
  return panel;
}

}  // namespace

int run_shading(int argc, char** argv) {
  std::string output;
  bool aa = false;
  const int panel = panel_arg(argc, argv, output, aa, "shading");
  const MeshModel models[2] = {make_sphere(10, 16), make_torus(1, 0.42, 28, 12)};
  const Color colors[2] = {Color{0.9f, 0.45f, 0.2f, 1}, Color{0.2f, 0.6f, 0.7f, 1}};
  const Shading modes[3] = {Shading::Flat, Shading::Gouraud, Shading::Phong};
  Sheet sheet(panel, 3, 2);
  MeshRenderer renderer;
  for (int row = 0; row < 2; ++row) {
    Camera camera;
    camera.yaw = 0.5, camera.pitch = row == 0 ? 0.3 : 0.75;
    const Mesh mesh = project(models[row], camera, panel, panel, colors[row]);
    for (int column = 0; column < 3; ++column) {
      Image image(panel, panel);
      image.clear(Color{0.95f, 0.95f, 0.95f, 1});
      MeshOptions o;
      o.shading = modes[column];
      o.lighting.enabled = true;
      o.antialias = aa;
      renderer.draw(image, mesh, o);
      sheet.put(image, column, row);
    }
  }
  sheet.label(0, "flat");
  sheet.label(1, "gouraud");
  sheet.label(2, "phong");
  write_png(output, sheet.image);
  std::cout << "vraster shading: wrote " << output << "\n";
  return 0;
}

int run_depth(int argc, char** argv) {
  std::string output;
  bool aa = false;
  const int panel = panel_arg(argc, argv, output, aa, "depth");
  const double s = panel;
  auto vertex = [&](double x, double y, double z, Color c) {
    MeshVertex v;
    v.position = Point{x * s, y * s};
    v.depth = z;
    v.color = c;
    return v;
  };
  const Color red{0.86f, 0.2f, 0.2f, 1}, green{0.2f, 0.7f, 0.3f, 1}, blue{0.2f, 0.35f, 0.85f, 1};
  Mesh scenes[2];
  // Two triangles passing through each other: each is in front on one side of the line where they cross.
  scenes[0].vertices = {vertex(0.06, 0.12, 0.1, red),  vertex(0.94, 0.22, 0.9, red),  vertex(0.45, 0.92, 0.5, red),
                        vertex(0.94, 0.08, 0.12, blue), vertex(0.06, 0.3, 0.88, blue), vertex(0.55, 0.95, 0.48, blue)};
  scenes[0].triangles = {{0, 1, 2}, {3, 4, 5}};
  // Three bars, each over the next at one end and under the previous at the other: no order of whole bars works.
  const Color bar_colors[3] = {red, green, blue};
  for (int k = 0; k < 3; ++k) {
    const double a0 = 2 * M_PI * k / 3 - M_PI / 2, a1 = a0 + 2 * M_PI / 3;
    const double cx = 0.5, cy = 0.55, r = 0.38;
    // From just before corner k to past corner k + 1, near at the start and far at the end.
    const double px = cx + r * std::cos(a0), py = cy + r * std::sin(a0);
    const double qx = cx + r * std::cos(a1), qy = cy + r * std::sin(a1);
    const double dx = qx - px, dy = qy - py, len = std::hypot(dx, dy);
    const double ux = dx / len, uy = dy / len, nx = -uy * 0.06, ny = ux * 0.06;
    const double sx = px - ux * 0.1, sy = py - uy * 0.1, ex = qx + ux * 0.1, ey = qy + uy * 0.1;
    const auto base = static_cast<std::uint32_t>(scenes[1].vertices.size());
    scenes[1].vertices.push_back(vertex(sx + nx, sy + ny, 0.2, bar_colors[k]));
    scenes[1].vertices.push_back(vertex(sx - nx, sy - ny, 0.2, bar_colors[k]));
    scenes[1].vertices.push_back(vertex(ex - nx, ey - ny, 0.8, bar_colors[k]));
    scenes[1].vertices.push_back(vertex(ex + nx, ey + ny, 0.8, bar_colors[k]));
    scenes[1].triangles.push_back({base, base + 1, base + 2});
    scenes[1].triangles.push_back({base, base + 2, base + 3});
  }
  Sheet sheet(panel, 2, 2);
  MeshRenderer renderer;
  for (int row = 0; row < 2; ++row) {
    for (int column = 0; column < 2; ++column) {
      Image image(panel, panel);
      image.clear(Color{0.97f, 0.97f, 0.97f, 1});
      MeshOptions o;
      o.shading = Shading::Flat;
      o.depth = column == 0 ? DepthMode::Painter : DepthMode::ZBuffer;
      o.antialias = aa;
      renderer.draw(image, scenes[row], o);
      sheet.put(image, column, row);
    }
  }
  sheet.label(0, "painter");
  sheet.label(1, "z-buffer");
  write_png(output, sheet.image);
  std::cout << "vraster depth: wrote " << output << "\n";
  return 0;
}

}  // namespace vraster::cli
