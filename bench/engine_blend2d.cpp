// Blend2D: PRGB32 image, synchronous context (thread_count 0: one thread, the same as the other engines), paths
// built in device space before timing; per frame: fill_all white (copy), then fill_path per item (source-over).
// Built only when -DVRASTER_BENCH_BLEND2D_ROOT=PREFIX names an install prefix of Blend2D (not a Debian package:
// build it outside this repository; nothing of it is kept here).
#include <blend2d/blend2d.h>

#include <stdexcept>
#include <vector>

#include "engines.hpp"

namespace bench {
namespace {

using vraster::Point;
using vraster::Verb;

struct Item {
  BLPath path;
  BLFillRule rule = BL_FILL_RULE_NON_ZERO;
  BLRgba32 color;
};

class Blend2DEngine final : public Engine {
 public:
  ~Blend2DEngine() override { ctx_.end(); }
  const char* name() const override { return "blend2d"; }
  std::string version() const override {
    return "Blend2D " + std::to_string(BL_VERSION >> 16) + "." + std::to_string((BL_VERSION >> 8) & 0xFF) + "." +
           std::to_string(BL_VERSION & 0xFF) + " (synchronous context, JIT pipelines as built by default)";
  }

  void prepare(const vraster::svg::Document& doc) override {
    ctx_.end();
    items_.clear();
    width_ = doc.width;
    height_ = doc.height;
    if (image_.create(width_, height_, BL_FORMAT_PRGB32) != BL_SUCCESS) throw std::runtime_error("BLImage::create failed");
    BLContextCreateInfo info{};
    info.thread_count = 0;  // synchronous, single-threaded
    info.flags = 0;         // no BL_CONTEXT_CREATE_FLAG_DISABLE_JIT: the JIT pipelines, Blend2D's default
    if (ctx_.begin(image_, info) != BL_SUCCESS) throw std::runtime_error("BLContext::begin failed");
    ctx_.set_flatten_tolerance(tolerance_);  // (its own default is 0.2 px)
    for (const vraster::svg::DrawItem& item : doc.items) {
      if (!item.is_fill()) continue;  // the fill benchmark compares fills only
      Item it;
      const auto pts = item.path.points();
      const vraster::Affine& m = item.transform;
      std::size_t i = 0;
      for (const Verb v : item.path.verbs()) {
        switch (v) {
          case Verb::Move: {
            const Point p = m.apply(pts[i++]);
            it.path.move_to(p.x, p.y);
            break;
          }
          case Verb::Line: {
            const Point p = m.apply(pts[i++]);
            it.path.line_to(p.x, p.y);
            break;
          }
          case Verb::Quad: {
            const Point q = m.apply(pts[i]), p = m.apply(pts[i + 1]);
            i += 2;
            it.path.quad_to(q.x, q.y, p.x, p.y);
            break;
          }
          case Verb::Cubic: {
            const Point c1 = m.apply(pts[i]), c2 = m.apply(pts[i + 1]), p = m.apply(pts[i + 2]);
            i += 3;
            it.path.cubic_to(c1.x, c1.y, c2.x, c2.y, p.x, p.y);
            break;
          }
          case Verb::Close:
            it.path.close();
            break;
        }
      }
      it.rule = item.rule == vraster::FillRule::EvenOdd ? BL_FILL_RULE_EVEN_ODD : BL_FILL_RULE_NON_ZERO;
      auto channel = [](float v) { return static_cast<std::uint32_t>(v * 255.f + 0.5f); };
      it.color = BLRgba32(channel(item.color.r), channel(item.color.g), channel(item.color.b), channel(item.color.a));
      items_.push_back(std::move(it));
    }
  }

  bool frame() override {
    ctx_.set_comp_op(BL_COMP_OP_SRC_COPY);
    ctx_.fill_all(BLRgba32(0xFFFFFFFFu));
    ctx_.set_comp_op(BL_COMP_OP_SRC_OVER);
    for (const Item& it : items_) {
      if (it.color.a() == 0) continue;  // vraster skips invisible fills too
      ctx_.set_fill_rule(it.rule);
      ctx_.fill_path(it.path, it.color);
    }
    if (ctx_.flush(BL_CONTEXT_FLUSH_SYNC) != BL_SUCCESS) {
      error_ = "BLContext::flush failed";
      return false;
    }
    return true;
  }

  vraster::Image image() const override {
    vraster::Image out(width_, height_);
    BLImageData data{};
    if (image_.get_data(&data) != BL_SUCCESS) return out;
    for (int y = 0; y < height_; ++y) {
      const auto* row = static_cast<const std::uint32_t*>(
          static_cast<const void*>(static_cast<const unsigned char*>(data.pixel_data) + y * data.stride));
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
  int width_ = 0, height_ = 0;
  BLImage image_;
  BLContext ctx_;
  std::vector<Item> items_;
  std::string error_;
};

}  // namespace

std::unique_ptr<Engine> make_blend2d_engine() { return std::make_unique<Blend2DEngine>(); }

}  // namespace bench
