// FreeType's smooth ("gray") rasterizer: one FT_Outline per item in device space (26.6 fixed point, y flipped
// to FreeType's y-up convention), built before timing; FT_Outline_Render in direct mode with a span callback
// that composites the colour source-over with vraster's 8-bit math.
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "engines.hpp"

namespace bench {
namespace {

using vraster::Point;
using vraster::Verb;

struct Item {
  std::vector<FT_Vector> points;
  std::vector<char> tags;
  std::vector<short> contours;
  int flags = FT_OUTLINE_NONE;
  std::uint32_t color = 0;  // premultiplied RGBA, R in the low byte
  bool too_big = false;     // more points or contours than FT_Outline's short counts hold
};

struct SpanTarget {
  std::uint32_t* pixels;
  int width, height;
  std::uint32_t color;
};

void gray_spans(int y, int count, const FT_Span* spans, void* user) {
  const auto* t = static_cast<const SpanTarget*>(user);
  const int row = t->height - 1 - y;  // FreeType row y (y up) is device row H - 1 - y
  if (row < 0 || row >= t->height) return;
  std::uint32_t* line = t->pixels + static_cast<std::size_t>(row) * t->width;
  const std::uint32_t color = t->color;
  const bool opaque = (color >> 24) == 255;
  for (int k = 0; k < count; ++k) {
    const std::uint32_t cov = spans[k].coverage;
    if (cov == 0) continue;
    std::uint32_t* px = line + spans[k].x;
    const int n = spans[k].len;
    if (cov == 255 && opaque) {
      std::fill(px, px + n, color);
      continue;
    }
    const std::uint32_t src = cov == 255 ? color : scale8(color, cov);
    const std::uint32_t inv = 255u - (src >> 24);
    for (int i = 0; i < n; ++i) px[i] = src + scale8(px[i], inv);
  }
}

FT_Pos to26(double v) { return static_cast<FT_Pos>(std::lround(v * 64.0)); }

class FreeTypeEngine final : public Engine {
 public:
  FreeTypeEngine() {
    if (FT_Init_FreeType(&library_) != 0) throw std::runtime_error("FT_Init_FreeType failed");
  }
  ~FreeTypeEngine() override { FT_Done_FreeType(library_); }
  const char* name() const override { return "freetype"; }
  std::string version() const override {
    FT_Int major = 0, minor = 0, patch = 0;
    FT_Library_Version(library_, &major, &minor, &patch);
    return "FreeType " + std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
  }

  void prepare(const vraster::svg::Document& doc) override {
    width_ = doc.width;
    height_ = doc.height;
    pixels_.assign(static_cast<std::size_t>(width_) * height_, 0xFFFFFFFFu);
    items_.clear();
    items_.reserve(doc.items.size());
    const double h = height_;
    for (const vraster::svg::DrawItem& fill : doc.items) {
      if (!fill.is_fill()) continue;  // the fill benchmark compares fills only
      Item it;
      const auto verbs = fill.path.verbs();
      const auto pts = fill.path.points();
      const vraster::Affine& m = fill.transform;
      std::size_t contour_begin = 0;
      auto add = [&](Point p, char tag) {
        const Point d = m.apply(p);
        it.points.push_back(FT_Vector{to26(d.x), to26(h - d.y)});
        it.tags.push_back(tag);
      };
      auto end_contour = [&] {
        if (it.points.size() - contour_begin >= 2) {
          it.contours.push_back(static_cast<short>(it.points.size() - 1));
        } else {
          it.points.resize(contour_begin);  // a lone move: nothing to fill
          it.tags.resize(contour_begin);
        }
        contour_begin = it.points.size();
      };
      std::size_t i = 0;
      for (const Verb v : verbs) {
        switch (v) {
          case Verb::Move:
            end_contour();
            add(pts[i++], FT_CURVE_TAG_ON);
            break;
          case Verb::Line:
            add(pts[i++], FT_CURVE_TAG_ON);
            break;
          case Verb::Quad:
            add(pts[i], FT_CURVE_TAG_CONIC);
            add(pts[i + 1], FT_CURVE_TAG_ON);
            i += 2;
            break;
          case Verb::Cubic:
            add(pts[i], FT_CURVE_TAG_CUBIC);
            add(pts[i + 1], FT_CURVE_TAG_CUBIC);
            add(pts[i + 2], FT_CURVE_TAG_ON);
            i += 3;
            break;
          case Verb::Close:
            end_contour();  // FreeType closes every contour implicitly
            break;
        }
      }
      end_contour();
      it.too_big = it.points.size() > 32767 || it.contours.size() > 32767;
      if (fill.rule == vraster::FillRule::EvenOdd) it.flags |= FT_OUTLINE_EVEN_ODD_FILL;
      const float a = std::clamp(fill.color.a, 0.f, 1.f);
      auto ch = [&](float c) { return static_cast<std::uint32_t>(std::lround(std::clamp(c, 0.f, 1.f) * a * 255.0)); };
      it.color = ch(fill.color.r) | ch(fill.color.g) << 8 | ch(fill.color.b) << 16 |
                 static_cast<std::uint32_t>(std::lround(a * 255.0)) << 24;
      items_.push_back(std::move(it));
    }
  }

  bool frame() override {
    std::fill(pixels_.begin(), pixels_.end(), 0xFFFFFFFFu);
    SpanTarget target{pixels_.data(), width_, height_, 0};
    FT_Raster_Params params{};
    params.flags = FT_RASTER_FLAG_AA | FT_RASTER_FLAG_DIRECT | FT_RASTER_FLAG_CLIP;
    params.gray_spans = gray_spans;
    params.user = &target;
    params.clip_box = FT_BBox{0, 0, width_, height_};
    for (Item& it : items_) {
      if ((it.color >> 24) == 0 || it.contours.empty()) continue;
      if (it.too_big) {
        error_ = "path too large for FT_Outline";
        return false;
      }
      FT_Outline outline{};
      outline.n_contours = static_cast<short>(it.contours.size());
      outline.n_points = static_cast<short>(it.points.size());
      outline.points = it.points.data();
      outline.tags = it.tags.data();
      outline.contours = it.contours.data();
      outline.flags = it.flags;
      target.color = it.color;
      params.source = &outline;
      const FT_Error err = FT_Outline_Render(library_, &outline, &params);
      if (err != 0) {
        const char* s = FT_Error_String(err);
        char buf[96];
        std::snprintf(buf, sizeof buf, "FT_Outline_Render error 0x%02X%s%s", static_cast<unsigned>(err),
                      s ? ": " : "", s ? s : "");
        error_ = buf;
        return false;
      }
    }
    return true;
  }

  vraster::Image image() const override {
    vraster::Image out(width_, height_);
    for (std::size_t i = 0; i < pixels_.size(); ++i) {
      const std::uint32_t p = pixels_[i];
      out.data[4 * i + 0] = static_cast<std::uint8_t>(p);
      out.data[4 * i + 1] = static_cast<std::uint8_t>(p >> 8);
      out.data[4 * i + 2] = static_cast<std::uint8_t>(p >> 16);
      out.data[4 * i + 3] = static_cast<std::uint8_t>(p >> 24);
    }
    return out;
  }

  std::string error() const override { return error_; }

 private:
  FT_Library library_ = nullptr;
  int width_ = 0, height_ = 0;
  std::vector<std::uint32_t> pixels_;
  std::vector<Item> items_;
  std::string error_;
};

}  // namespace

std::unique_ptr<Engine> make_freetype_engine() { return std::make_unique<FreeTypeEngine>(); }

}  // namespace bench
