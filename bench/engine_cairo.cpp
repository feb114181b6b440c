// Cairo: ARGB32 image surface, default antialiasing, paths built in device space before timing
// (cairo_copy_path once per item; cairo_append_path + cairo_fill per frame).
#include <cairo.h>

#include <stdexcept>
#include <vector>

#include "engines.hpp"

namespace bench {
namespace {

using vraster::Point;
using vraster::Verb;

struct Item {
  cairo_path_t* path = nullptr;
  cairo_fill_rule_t rule = CAIRO_FILL_RULE_WINDING;
  double r = 0, g = 0, b = 0, a = 1;
};

class CairoEngine final : public Engine {
 public:
  ~CairoEngine() override { release(); }
  const char* name() const override { return "cairo"; }
  std::string version() const override { return std::string("Cairo ") + cairo_version_string(); }

  void prepare(const vraster::svg::Document& doc) override {
    release();
    width_ = doc.width;
    height_ = doc.height;
    surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width_, height_);
    cr_ = cairo_create(surface_);
    if (cairo_status(cr_) != CAIRO_STATUS_SUCCESS) throw std::runtime_error("cairo_create failed");
    cairo_set_tolerance(cr_, tolerance_);
    for (const vraster::svg::DrawItem& item : doc.items) {
      if (!item.is_fill()) continue;  // the fill benchmark compares fills only
      cairo_new_path(cr_);
      const auto verbs = item.path.verbs();
      const auto pts = item.path.points();
      const vraster::Affine& m = item.transform;
      std::size_t i = 0;
      Point cur{};
      for (const Verb v : verbs) {
        switch (v) {
          case Verb::Move:
            cur = m.apply(pts[i++]);
            cairo_move_to(cr_, cur.x, cur.y);
            break;
          case Verb::Line:
            cur = m.apply(pts[i++]);
            cairo_line_to(cr_, cur.x, cur.y);
            break;
          case Verb::Quad: {
            const Point q = m.apply(pts[i]), p2 = m.apply(pts[i + 1]);
            i += 2;
            const Point c1 = cur + (2.0 / 3.0) * (q - cur), c2 = p2 + (2.0 / 3.0) * (q - p2);
            cairo_curve_to(cr_, c1.x, c1.y, c2.x, c2.y, p2.x, p2.y);
            cur = p2;
            break;
          }
          case Verb::Cubic: {
            const Point c1 = m.apply(pts[i]), c2 = m.apply(pts[i + 1]), p3 = m.apply(pts[i + 2]);
            i += 3;
            cairo_curve_to(cr_, c1.x, c1.y, c2.x, c2.y, p3.x, p3.y);
            cur = p3;
            break;
          }
          case Verb::Close:
            cairo_close_path(cr_);
            break;
        }
      }
      Item it;
      it.path = cairo_copy_path(cr_);
      if (it.path->status != CAIRO_STATUS_SUCCESS) throw std::runtime_error("cairo_copy_path failed");
      it.rule = item.rule == vraster::FillRule::EvenOdd ? CAIRO_FILL_RULE_EVEN_ODD : CAIRO_FILL_RULE_WINDING;
      it.r = item.color.r;
      it.g = item.color.g;
      it.b = item.color.b;
      it.a = item.color.a;
      items_.push_back(it);
    }
    cairo_new_path(cr_);
  }

  bool frame() override {
    cairo_set_operator(cr_, CAIRO_OPERATOR_SOURCE);
    cairo_set_source_rgb(cr_, 1, 1, 1);
    cairo_paint(cr_);
    cairo_set_operator(cr_, CAIRO_OPERATOR_OVER);
    for (const Item& it : items_) {
      if (!(it.a > 0)) continue;  // vraster skips invisible fills too
      cairo_new_path(cr_);
      cairo_append_path(cr_, it.path);
      cairo_set_fill_rule(cr_, it.rule);
      cairo_set_source_rgba(cr_, it.r, it.g, it.b, it.a);
      cairo_fill(cr_);
    }
    cairo_surface_flush(surface_);
    if (cairo_status(cr_) != CAIRO_STATUS_SUCCESS) {
      error_ = cairo_status_to_string(cairo_status(cr_));
      return false;
    }
    return true;
  }

  vraster::Image image() const override {
    vraster::Image out(width_, height_);
    cairo_surface_flush(surface_);
    const unsigned char* data = cairo_image_surface_get_data(surface_);
    const int stride = cairo_image_surface_get_stride(surface_);
    for (int y = 0; y < height_; ++y) {
      const auto* row = reinterpret_cast<const std::uint32_t*>(static_cast<const void*>(data + y * stride));
      for (int x = 0; x < width_; ++x) {
        const std::uint32_t p = row[x];  // premultiplied ARGB in a native-endian uint32
        std::uint8_t* o = out.pixel(x, y);
        o[0] = static_cast<std::uint8_t>(p >> 16);
        o[1] = static_cast<std::uint8_t>(p >> 8);
        o[2] = static_cast<std::uint8_t>(p);
        o[3] = static_cast<std::uint8_t>(p >> 24);
      }
    }
    return out;
  }

  std::string error() const override { return error_; }

 private:
  void release() {
    for (Item& it : items_) cairo_path_destroy(it.path);
    items_.clear();
    if (cr_) cairo_destroy(cr_);
    if (surface_) cairo_surface_destroy(surface_);
    cr_ = nullptr;
    surface_ = nullptr;
  }

  int width_ = 0, height_ = 0;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  std::vector<Item> items_;
  std::string error_;
};

}  // namespace

std::unique_ptr<Engine> make_cairo_engine() { return std::make_unique<CairoEngine>(); }

}  // namespace bench
