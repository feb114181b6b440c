// Shaped lines against what HarfBuzz's own hb-view draws (cairo) for the same font, size and text.
//
// hb-view (HarfBuzz 6.0 with cairo 1.16 on Debian 12) puts the pen at (margin, margin + ascender), positions
// glyphs in 1/64 px and cairo then draws each glyph at a whole-pixel position with its own rasterizer. We lay out
// the same text with vraster, draw it at the same origin with whole-pixel glyph positions (subpixel_phases = 1), and
// compare ink masks (ink = 1 - grey level):
//  - ink centroids within 0.1 px and total ink within 1% (a wrong advance, offset or glyph moves or changes ink
//    by far more: one glyph off by one pixel on a 20-glyph line moves the centroid by ~0.05 px in x; a wrong glyph
//    changes the ink total by several percent);
//  - mean |difference| over the ink box below 0.012 (measured 0.0007-0.0022: antialiasing differences only) and
//    fewer than 2% of the box's pixels differ by more than 25%. The slack covers one case: a glyph whose exact
//    position lies within 1/128 px of a half pixel is rounded one way by us (exact doubles) and the other way by
//    hb-view (1/64 px first), moving that glyph by one pixel (measured: 1.2% of pixels for "latin16").
// A diff image (hb-view | vraster | 4 x difference, red: less ink than hb-view, blue: more) is written to the test
// output folder for every case.
#include <gtest/gtest.h>

#include <cmath>

#include "text_support.hpp"
#include "vraster/png.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;
using namespace vraster::text::testing;

namespace {

void compare_with_hb_view(const std::string& name, const std::string& font_path, const std::string& text,
                          const std::string& lang, double size) {
  require_program("hb-view", "libharfbuzz-bin");
  const std::string ref_file = out_dir() + "/hbview_" + name + ".png";
  int status = 0;
  const std::string log = run_command("LANG=C.UTF-8 hb-view --font-size=" + std::to_string(static_cast<int>(size)) +
                                          " --margin=16 --language=" + lang + " --output-format=png -o '" + ref_file +
                                          "' '" + font_path + "' '" + text + "' 2>&1",
                                      status);
  ASSERT_EQ(status, 0) << "hb-view did not run: " << log;
  const Image ref = read_png(ref_file);

  const auto font = Font::load_file(font_path);
  TextStyle style;
  style.size = size;
  style.language = lang;
  const TextLayout layout = layout_text(text, FontList(font), style);
  GlyphRenderOptions options;
  options.subpixel_phases = 1;  // cairo 1.16 (Debian 12) draws every glyph at a whole-pixel position
  Image ours(ref.width, ref.height);
  ours.clear(Color::rgb8(255, 255, 255));
  const Point origin{16.0, 16.0 - font->metrics(size).ascender};  // hb-view: margin, margin + ascender
  TextRenderer().draw(ours, layout, Color::rgb8(0, 0, 0), Affine::translate(origin.x, origin.y), options);
  const auto a = ink_of(ref, true), b = ink_of(ours, true);
  const InkStats sa = ink_stats(a, ref.width, ref.height), sb = ink_stats(b, ref.width, ref.height);
  ASSERT_GT(sa.total, 0);
  EXPECT_NEAR(sb.cx, sa.cx, 0.1);
  EXPECT_NEAR(sb.cy, sa.cy, 0.1);
  EXPECT_NEAR(sb.total / sa.total, 1.0, 0.01);
  const int x0 = std::min(sa.x0, sb.x0), y0 = std::min(sa.y0, sb.y0);
  const int x1 = std::max(sa.x1, sb.x1), y1 = std::max(sa.y1, sb.y1);
  double sum = 0;
  long big = 0, count = 0;
  Image diff(3 * ref.width, ref.height);
  diff.clear(Color::rgb8(255, 255, 255));
  for (int y = 0; y < ref.height; ++y) {
    for (int x = 0; x < ref.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * ref.width + x;
      const double d = b[i] - a[i];
      auto put = [&](int px, double v, int channel_keep) {
        auto* p = diff.pixel(px, y);
        const auto g = static_cast<std::uint8_t>(std::lround(255 * (1 - std::clamp(v, 0.0, 1.0))));
        p[0] = p[1] = p[2] = g;
        if (channel_keep >= 0) p[channel_keep] = 255;
      };
      put(x, a[i], -1);
      put(ref.width + x, b[i], -1);
      put(2 * ref.width + x, std::min(1.0, 4 * std::abs(d)), d < 0 ? 0 : 2);
      if (x < x0 || x > x1 || y < y0 || y > y1) continue;
      sum += std::abs(d);
      big += std::abs(d) > 0.25;
      ++count;
    }
  }
  write_png(out_dir() + "/hbview_" + name + "_diff.png", diff);
  const double mean = sum / static_cast<double>(count);
  const double big_share = static_cast<double>(big) / static_cast<double>(count);
  std::printf("[hb-view] %s: centroid (%+.3f, %+.3f) px, ink ratio %.4f, mean |diff| %.4f, pixels > 25%%: %.3f%%\n",
              name.c_str(), sb.cx - sa.cx, sb.cy - sa.cy, sb.total / sa.total, mean, 100 * big_share);
  EXPECT_LT(mean, 0.012);
  EXPECT_LT(big_share, 0.02);
}

}  // namespace

TEST(HbView, LatinKerningAndLigaturesMatch) {
  compare_with_hb_view("latin", system_font(kNotoSerif), "AVAWA office fluffy Tofu", "en", 48);
}

TEST(HbView, LatinDefaultFontSmallSizeMatches) {
  compare_with_hb_view("latin16", repo_font("NotoSans-Regular.ttf"), "Kerning: AVAWA, Typography, 1/2", "en", 16);
}

TEST(HbView, ArabicMatches) {
  compare_with_hb_view("arabic", system_font(kAmiri),
                       "\xd9\x85\xd8\xb1\xd8\xad\xd8\xa8\xd8\xa7 \xd8\xa8\xd8\xa7\xd9\x84\xd8\xb9\xd8\xa7\xd9\x84\xd9\x85",
                       "ar", 48);
}

TEST(HbView, DevanagariMatches) {
  compare_with_hb_view("devanagari", system_font(kNotoSansDevanagari),
                       "\xe0\xa4\xa8\xe0\xa4\xae\xe0\xa4\xb8\xe0\xa5\x8d\xe0\xa4\xa4\xe0\xa5\x87 "
                       "\xe0\xa4\x95\xe0\xa4\xbf\xe0\xa4\xb0\xe0\xa5\x8d\xe0\xa4\xa4\xe0\xa4\xbf",
                       "hi", 48);
}
