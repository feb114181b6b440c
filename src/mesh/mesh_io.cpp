// Mesh input: OBJ and .vmesh text, and the camera projection of 3D models.
//
//   text -> lines -> statements (tokens with their columns) -> model or mesh, checked against the caps as it grows
//   model -> centre and scale to the unit sphere -> yaw, pitch -> orthographic or perspective device positions
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "vraster/error.hpp"
#include "vraster/mesh_io.hpp"

namespace vraster {

namespace {

// One line of text split into tokens, each with its 1-based column, for messages "NAME:LINE:COLUMN: ...".
class Statement {
 public:
  Statement(const std::string& name, std::string_view line, int number) : name_(name), number_(number) {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i >= line.size()) break;
      // A comment: '#' opening the line, or '#' standing alone ("# ..."); "#rrggbb" is a colour.
      const bool alone = i + 1 >= line.size() || line[i + 1] == ' ' || line[i + 1] == '\t' || line[i + 1] == '\r';
      if (line[i] == '#' && (tokens_.empty() || alone)) break;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      tokens_.push_back(line.substr(start, i - start));
      columns_.push_back(static_cast<int>(start) + 1);
    }
  }
  std::size_t size() const { return tokens_.size(); }
  std::string_view operator[](std::size_t i) const { return tokens_[i]; }

  [[noreturn]] void fail(std::size_t token, const std::string& message) const {
    // A missing value is reported just after the last one.
    const int column = token < columns_.size() ? columns_[token]
                       : columns_.empty()      ? 1
                                               : columns_.back() + static_cast<int>(tokens_.back().size());
    throw Error(name_ + ":" + std::to_string(number_) + ":" + std::to_string(column) + ": " + message);
  }
  double number(std::size_t i) const {
    if (i >= size()) fail(i, "expected a number after '" + std::string(tokens_.empty() ? "" : tokens_[0]) + "'");
    std::string_view t = tokens_[i];
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) fail(i, "'" + std::string(tokens_[i]) + "' is not a number");
    if (!std::isfinite(v)) fail(i, "'" + std::string(tokens_[i]) + "' is not finite");
    return v;
  }
  long long integer(std::size_t i) const {
    if (i >= size()) fail(i, "expected an integer");
    long long v = 0;
    const auto [end, ec] = std::from_chars(tokens_[i].data(), tokens_[i].data() + tokens_[i].size(), v);
    if (ec != std::errc() || end != tokens_[i].data() + tokens_[i].size()) {
      fail(i, "'" + std::string(tokens_[i]) + "' is not an integer");
    }
    return v;
  }
  void expect_count(std::size_t lo, std::size_t hi) const {
    if (size() < lo) fail(size(), "'" + std::string(tokens_[0]) + "' needs " + std::to_string(lo - 1) + " values");
    if (size() > hi) fail(hi, "too many values for '" + std::string(tokens_[0]) + "'");
  }

 private:
  const std::string& name_;
  int number_;
  std::vector<std::string_view> tokens_;
  std::vector<int> columns_;
};

template <class F>
void for_each_statement(std::string_view text, const std::string& name, F&& f) {
  if (text.size() > kMaxMeshFileBytes) {
    throw Error(name + ": larger than " + std::to_string(kMaxMeshFileBytes >> 20) + " MiB");
  }
  int number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    ++number;
    const Statement s(name, text.substr(pos, end - pos), number);
    if (s.size() > 0) f(s);
    pos = end + 1;
  }
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// #rgb, #rrggbb or #rrggbbaa.
Color parse_hex_color(const Statement& s, std::size_t i) {
  if (i >= s.size()) s.fail(i, "expected a colour (#rrggbb)");
  const std::string_view t = s[i];
  const std::string bad = std::string(t) + " is not a colour (#rgb, #rrggbb or #rrggbbaa)";
  const bool ok_length = t.size() == 4 || t.size() == 7 || t.size() == 9;
  if (!ok_length || t[0] != '#') s.fail(i, bad);
  int v[8] = {0, 0, 0, 0, 0, 0, 15, 15};
  for (std::size_t k = 1; k < t.size(); ++k) {
    const int d = hex_digit(t[k]);
    if (d < 0) s.fail(i, bad);
    v[k - 1] = d;
  }
  if (t.size() == 4) return Color::rgb8(v[0] * 17, v[1] * 17, v[2] * 17);
  return Color::rgb8(v[0] * 16 + v[1], v[2] * 16 + v[3], v[4] * 16 + v[5], v[6] * 16 + v[7]);
}

Vec3 to_vec(double x, double y, double z) {
  return Vec3{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

}  // namespace

std::string read_mesh_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(path + ": cannot read the file");
  if (static_cast<std::uint64_t>(size) > kMaxMeshFileBytes) {
    throw Error(path + ": larger than " + std::to_string(kMaxMeshFileBytes >> 20) + " MiB");
  }
  in.seekg(0);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), size)) throw Error(path + ": cannot read the file");
  return text;
}

MeshModel parse_obj(std::string_view text, const std::string& name) {
  MeshModel model;
  std::vector<Vec3> positions, normals;
  std::vector<Color> colors;
  bool any_color = false;
  std::map<std::pair<std::uint32_t, std::int64_t>, std::uint32_t> corner_vertex;  // (position, normal) -> vertex
  bool any_normal = false;
  std::vector<std::uint32_t> corners;
  for_each_statement(text, name, [&](const Statement& s) {
    const std::string_view kind = s[0];
    if (kind == "v") {
      s.expect_count(4, 7);
      if (s.size() != 4 && s.size() != 5 && s.size() != 7) s.fail(4, "'v' takes x y z [w] or x y z r g b");
      if (positions.size() >= kMaxMeshVertices) s.fail(0, "more than " + std::to_string(kMaxMeshVertices) + " vertices");
      positions.push_back(to_vec(s.number(1), s.number(2), s.number(3)));
      if (s.size() == 5) s.number(4);  // the weight of rational curves: checked, not used
      Color c{0.8f, 0.8f, 0.8f, 1};
      if (s.size() == 7) {
        const double r = s.number(4), g = s.number(5), b = s.number(6);
        c = Color{static_cast<float>(std::clamp(r, 0.0, 1.0)), static_cast<float>(std::clamp(g, 0.0, 1.0)),
                  static_cast<float>(std::clamp(b, 0.0, 1.0)), 1};
        any_color = true;
      }
      colors.push_back(c);
    } else if (kind == "vn") {
      s.expect_count(4, 4);
      if (normals.size() >= kMaxMeshVertices) s.fail(0, "more than " + std::to_string(kMaxMeshVertices) + " normals");
      normals.push_back(to_vec(s.number(1), s.number(2), s.number(3)));
    } else if (kind == "f") {
      if (s.size() < 4) s.fail(s.size(), "a face needs at least 3 corners");
      corners.clear();
      for (std::size_t i = 1; i < s.size(); ++i) {
        const std::string_view t = s[i];
        const std::size_t slash = t.find('/');
        auto index = [&](std::string_view part, std::size_t count, const char* what) -> std::int64_t {
          long long v = 0;
          const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
          if (ec != std::errc() || end != part.data() + part.size()) {
            s.fail(i, "'" + std::string(t) + "' is not a face corner (v, v/t, v//n or v/t/n)");
          }
          const long long n = static_cast<long long>(count);
          const long long resolved = v < 0 ? n + v : v - 1;  // negative: relative to the end
          if (v == 0 || resolved < 0 || resolved >= n) {
            s.fail(i, std::string(what) + " index " + std::to_string(v) + " out of range (" + std::to_string(n) +
                          " defined so far)");
          }
          return resolved;
        };
        const std::int64_t p = index(t.substr(0, slash), positions.size(), "vertex");
        std::int64_t n = -1;
        if (slash != std::string_view::npos) {
          const std::size_t slash2 = t.find('/', slash + 1);
          if (slash2 != std::string_view::npos && slash2 + 1 < t.size()) {
            n = index(t.substr(slash2 + 1), normals.size(), "normal");
            any_normal = true;
          }
        }
        const auto key = std::make_pair(static_cast<std::uint32_t>(p), n);
        auto it = corner_vertex.find(key);
        if (it == corner_vertex.end()) {
          if (model.positions.size() >= kMaxMeshVertices) {
            s.fail(i, "more than " + std::to_string(kMaxMeshVertices) + " vertices");
          }
          it = corner_vertex.emplace(key, static_cast<std::uint32_t>(model.positions.size())).first;
          model.positions.push_back(positions[static_cast<std::size_t>(p)]);
          model.colors.push_back(colors[static_cast<std::size_t>(p)]);
          model.normals.push_back(n >= 0 ? normals[static_cast<std::size_t>(n)] : Vec3{0, 0, 0});
        }
        corners.push_back(it->second);
      }
      for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        if (model.triangles.size() >= kMaxMeshTriangles) {
          s.fail(0, "more than " + std::to_string(kMaxMeshTriangles) + " triangles");
        }
        model.triangles.push_back({corners[0], corners[i], corners[i + 1]});
      }
    }
    // vt, o, g, s, usemtl, mtllib, l, p and the rest: not needed for shading.
  });
  if (model.triangles.empty()) throw Error(name + ": no faces");
  // Corners without a normal get one computed on projection; a model mixing both computes them all.
  bool all_normals = any_normal;
  for (const Vec3& n : model.normals) all_normals = all_normals && (n.x != 0 || n.y != 0 || n.z != 0);
  if (!all_normals) model.normals.clear();
  if (!any_color) model.colors.clear();
  return model;
}

Mesh project(const MeshModel& model, const Camera& camera, int width, int height, Color color) {
  if (!(std::isfinite(camera.yaw) && std::isfinite(camera.pitch) && camera.margin >= 0 && camera.margin < 0.5)) {
    throw Error("camera: yaw and pitch must be finite and the margin in [0, 0.5)");
  }
  if (camera.perspective && !(camera.distance > 1 && camera.distance <= 1000)) {
    throw Error("camera: the perspective distance must be more than 1 and at most 1000 bounding radii");
  }
  Mesh mesh;
  if (model.positions.empty()) return mesh;
  Vec3 lo = model.positions[0], hi = lo;
  for (const Vec3& p : model.positions) {
    lo = Vec3{std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = Vec3{std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double cx = (double(lo.x) + hi.x) / 2, cy = (double(lo.y) + hi.y) / 2, cz = (double(lo.z) + hi.z) / 2;
  double radius = 0;
  for (const Vec3& p : model.positions) {
    radius = std::max(radius, std::hypot(p.x - cx, p.y - cy, p.z - cz));
  }
  if (!(radius > 0) || !std::isfinite(radius)) radius = 1;

  // Normals: the model's, or area-weighted sums of the face normals (faces counterclockwise seen from outside).
  std::vector<Vec3> normals = model.normals;
  if (normals.size() != model.positions.size()) {
    normals.assign(model.positions.size(), Vec3{});
    for (const auto& t : model.triangles) {
      const Vec3 a = model.positions[t[0]], b = model.positions[t[1]], c = model.positions[t[2]];
      const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
      const Vec3 n = to_vec(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx);
      for (const std::uint32_t k : t) normals[k] = Vec3{normals[k].x + n.x, normals[k].y + n.y, normals[k].z + n.z};
    }
  }
  const double cyaw = std::cos(camera.yaw), syaw = std::sin(camera.yaw);
  const double cpitch = std::cos(camera.pitch), spitch = std::sin(camera.pitch);
  auto rotate = [&](double x, double y, double z) {  // yaw about y, then pitch about x (top towards the viewer)
    const double x1 = cyaw * x + syaw * z, z1 = -syaw * x + cyaw * z;
    return std::array<double, 3>{x1, cpitch * y - spitch * z1, spitch * y + cpitch * z1};
  };
  const double half = std::min(width, height) / 2.0 * (1 - 2 * camera.margin);
  const double d = camera.distance;
  const double focal = half * std::sqrt(d * d - 1);  // the unit sphere's silhouette just fills `half`
  mesh.vertices.resize(model.positions.size());
  for (std::size_t i = 0; i < model.positions.size(); ++i) {
    const Vec3 p = model.positions[i];
    const auto e = rotate((p.x - cx) / radius, (p.y - cy) / radius, (p.z - cz) / radius);  // eye space, y up, +z to us
    MeshVertex& v = mesh.vertices[i];
    if (camera.perspective) {
      const double view = d - e[2];  // distance along the view axis, > 0 for points inside the sphere
      v.position = Point{width / 2.0 + focal * e[0] / view, height / 2.0 - focal * e[1] / view};
      v.w = view;
      v.depth = 1 - (d - 1) / view;  // a + b / w: linear on screen, increasing with distance
      v.eye = to_vec(e[0], -e[1], view);
    } else {
      v.position = Point{width / 2.0 + half * e[0], height / 2.0 - half * e[1]};
      v.depth = -e[2];
      v.eye = to_vec(e[0], -e[1], d - e[2]);
    }
    const auto n = rotate(normals[i].x, normals[i].y, normals[i].z);
    v.normal = to_vec(n[0], -n[1], -n[2]);  // lighting space: y down, z away from the viewer
    v.color = model.colors.size() == model.positions.size() ? model.colors[i] : color;
  }
  mesh.triangles = model.triangles;
  return mesh;
}

namespace {

// Quads of a grid of (nu + 1) rows of nv vertices, closed around each row, into triangles, each turned so that it runs
// counterclockwise around the outward normal.
void add_grid(MeshModel& m, int nu, int nv) {
  auto index = [&](int i, int j) { return static_cast<std::uint32_t>(i * nv + j % nv); };
  auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vec3 p = m.positions[a], q = m.positions[b], r = m.positions[c];
    const double ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z, vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const Vec3 n = m.normals[a];
    if (nx * n.x + ny * n.y + nz * n.z < 0) std::swap(b, c);
    if (nx * nx + ny * ny + nz * nz > 0) m.triangles.push_back({a, b, c});  // the poles' zero-area halves: none
  };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const std::uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      add(a, b, c);
      add(a, c, d);
    }
  }
}

}  // namespace

MeshModel make_sphere(int rings, int segments) {
  if (rings < 2 || segments < 3 || rings > 2048 || segments > 2048) throw Error("sphere: rings or segments out of range");
  MeshModel m;
  for (int i = 0; i <= rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      const Vec3 p = to_vec(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(p);
      m.normals.push_back(p);
    }
  }
  add_grid(m, rings, segments);
  return m;
}

MeshModel make_torus(double major, double minor, int around, int tube) {
  if (!(minor > 0 && minor < major) || around < 3 || tube < 3 || around > 2048 || tube > 2048) {
    throw Error("torus: radii or counts out of range");
  }
  MeshModel m;
  for (int i = 0; i <= around; ++i) {
    const double u = 2 * M_PI * i / around;
    for (int j = 0; j < tube; ++j) {
      const double v = 2 * M_PI * j / tube;
      const double ring = major + minor * std::cos(v);
      m.positions.push_back(to_vec(ring * std::cos(u), minor * std::sin(v), ring * std::sin(u)));
      m.normals.push_back(to_vec(std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u)));
    }
  }
  add_grid(m, around, tube);
  return m;
}

MeshDocument parse_vmesh(std::string_view text, const std::string& name) {
  MeshDocument doc;
  bool header = false;
  for_each_statement(text, name, [&](const Statement& s) {
    const std::string_view kind = s[0];
    if (!header) {
      if (kind != "vmesh" || s.size() != 2 || s[1] != "1") s.fail(0, "a mesh file starts with 'vmesh 1'");
      header = true;
      return;
    }
    if (kind == "size") {
      s.expect_count(3, 3);
      const long long w = s.integer(1), h = s.integer(2);
      if (w < 1 || w > 8192) s.fail(1, "width must be from 1 to 8192");
      if (h < 1 || h > 8192) s.fail(2, "height must be from 1 to 8192");
      doc.width = static_cast<int>(w), doc.height = static_cast<int>(h);
    } else if (kind == "background") {
      s.expect_count(2, 2);
      doc.background = s[1] == "transparent" ? Color::transparent() : parse_hex_color(s, 1);
    } else if (kind == "light") {
      s.expect_count(2, 2);
      if (s[1] != "on" && s[1] != "off") s.fail(1, "'light' is 'on' or 'off'");
      doc.lit = s[1] == "on";
    } else if (kind == "v") {
      if (s.size() != 5 && s.size() != 8) s.fail(std::min<std::size_t>(s.size(), 5), "'v' takes x y z #colour [nx ny nz]");
      if (doc.mesh.vertices.size() >= kMaxMeshVertices) {
        s.fail(0, "more than " + std::to_string(kMaxMeshVertices) + " vertices");
      }
      MeshVertex v;
      v.position = Point{s.number(1), s.number(2)};
      v.depth = s.number(3);
      v.color = parse_hex_color(s, 4);
      if (s.size() == 8) v.normal = to_vec(s.number(5), s.number(6), s.number(7));
      doc.mesh.vertices.push_back(v);
    } else if (kind == "t") {
      s.expect_count(4, 4);
      if (doc.mesh.triangles.size() >= kMaxMeshTriangles) {
        s.fail(0, "more than " + std::to_string(kMaxMeshTriangles) + " triangles");
      }
      std::array<std::uint32_t, 3> t{};
      for (std::size_t i = 0; i < 3; ++i) {
        const long long k = s.integer(i + 1);
        if (k < 0 || k >= static_cast<long long>(doc.mesh.vertices.size())) {
          s.fail(i + 1, "vertex " + std::to_string(k) + " is not defined (" +
                            std::to_string(doc.mesh.vertices.size()) + " so far, counted from 0)");
        }
        t[i] = static_cast<std::uint32_t>(k);
      }
      doc.mesh.triangles.push_back(t);
    } else {
      s.fail(0, "unknown statement '" + std::string(kind) + "' (size, background, light, v, t)");
    }
  });
  if (!header) throw Error(name + ":1:1: empty file (a mesh file starts with 'vmesh 1')");
  return doc;
}

}  // namespace vraster
