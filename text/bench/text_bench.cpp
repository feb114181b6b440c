// Text benchmark: glyphs per second, vraster (outline -> coverage, uncached and cached) against FreeType's
// FT_Render_Glyph in the same run, at 12, 16, 32 and 64 px; and shaping + layout + rendering of a 10,000-character
// paragraph (also drawn by Blend2D when built with -DVRASTER_BENCH_BLEND2D_ROOT=PREFIX, from the same glyphs and
// positions). A program, not a test: build with -DVRASTER_BUILD_TEXT_BENCH=ON (or VRASTER_BUILD_BENCH) in Release.
//
//   text_bench [seconds-per-measurement]
#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#ifdef VRASTER_BENCH_WITH_BLEND2D
#include <blend2d/blend2d.h>
#endif

#include "font_impl.hpp"
#include "vraster/image.hpp"
#include "vraster_text/text.hpp"

using namespace vraster;
using namespace vraster::text;

namespace {

using Clock = std::chrono::steady_clock;

double g_seconds = 0.2;
constexpr int kRounds = 5;  // every measurement is repeated, interleaved with the others; the best round counts
std::uint64_t g_sink = 0;  // keeps results alive (printed at the end)

// Runs `body` (which handles `n` glyphs per call) until g_seconds have passed; returns glyphs per second.
template <class F>
double rate(int n, F&& body) {
  body();  // warm-up
  long calls = 0;
  const auto t0 = Clock::now();
  double elapsed = 0;
  do {
    body();
    ++calls;
    elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  } while (elapsed < g_seconds);
  return static_cast<double>(calls) * n / elapsed;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1) g_seconds = std::atof(argv[1]);
  const auto font = Font::load_default();
  std::vector<std::uint32_t> glyphs;
  for (char32_t c = 0x21; c < 0x7F; ++c) glyphs.push_back(font->glyph_index(c));  // printable ASCII, no space
  const int n = static_cast<int>(glyphs.size());

  FT_Library lib;
  FT_Face face;
  const auto data = Font::default_font_data();
  if (FT_Init_FreeType(&lib) || FT_New_Memory_Face(lib, data.data(), static_cast<FT_Long>(data.size()), 0, &face)) {
    std::fprintf(stderr, "FreeType failed\n");
    return 1;
  }

  if (argc > 2 && std::string(argv[2]) == "profile") {  // only vraster's uncached path, for a profiler
    GlyphRasterizer raster;
    const double size = argc > 3 ? std::atof(argv[3]) : 16.0;
    const double r = rate(n, [&] {
      for (auto g : glyphs) g_sink += raster.rasterize(*font, g, size, size, 0.25, 0, {}).coverage.size();
    });
    std::printf("%.0f glyphs/s\n", r);
    return 0;
  }
  std::printf("glyphs/s over %d ASCII glyphs of Noto Sans, unhinted; best of %d interleaved rounds of %.2f s\n", n,
              kRounds, g_seconds);
  std::printf("%5s %14s %14s %14s %14s %14s %14s %8s %10s\n", "size", "FT load+rend", "FT render", "vr uncached",
              "vr +FT load", "vr cached", "vr draw uncch", "vr/FTr", "vr+L/FT+L");
  GlyphRasterizer raster;
  GlyphRenderOptions options;
  for (double size : {12.0, 16.0, 32.0, 64.0}) {
    FT_Set_Char_Size(face, 0, static_cast<FT_F26Dot6>(size * 64), 72, 72);
    double ft_all = 0, ft_load = 0, vr = 0, vr_load = 0, cached = 0, uncached_draw = 0;
    Image image(256, 256);
    TextRenderer renderer;
    GlyphRenderOptions direct;
    direct.use_cache = false;
    for (int round = 0; round < kRounds; ++round) {
      // FreeType: load (scale the outline) + render to an 8-bit coverage bitmap.
      const double ft_all_r = rate(n, [&] {
        for (auto g : glyphs) {
          FT_Load_Glyph(face, g, FT_LOAD_NO_HINTING);
          FT_Render_Glyph(face->glyph, FT_RENDER_MODE_NORMAL);
          g_sink += face->glyph->bitmap.buffer ? face->glyph->bitmap.buffer[0] : 0;
        }
      });
      const double ft_load_r = rate(n, [&] {
        for (auto g : glyphs) {
          FT_Load_Glyph(face, g, FT_LOAD_NO_HINTING);
          g_sink += static_cast<std::uint64_t>(face->glyph->outline.n_points);
        }
      });
      // vraster, uncached: the decoded outline (font units) -> flatten -> rasterize -> 8-bit coverage mask.
      const double vr_r = rate(n, [&] {
        for (auto g : glyphs) {
          const GlyphMask m = raster.rasterize(*font, g, size, size, 0.25, 0, options);
          g_sink += m.coverage.size();
        }
      });
      // vraster, uncached, including FreeType's outline load and the decomposition into a Path every time.
      const double vr_load_r = rate(n, [&] {
        for (auto g : glyphs) {
          FT_Load_Glyph(face, g, FT_LOAD_NO_SCALE);
          Path p;
          decompose_outline(face->glyph->outline, 1, 1, p);
          g_sink += p.points().size();
          const GlyphMask m = raster.rasterize(*font, g, size, size, 0.25, 0, options);
          g_sink += m.coverage.size();
        }
      });
      // vraster, drawing onto an image: cached (mask lookup + blit) and uncached (outline filled onto the image).
      const double cached_r = rate(n, [&] {
        for (std::size_t i = 0; i < glyphs.size(); ++i) {
          renderer.draw_glyph(image, *font, glyphs[i], size, {20.0 + 0.25 * static_cast<double>(i % 4), 120}, Color{});
        }
      });
      const double uncached_draw_r = rate(n, [&] {
        for (std::size_t i = 0; i < glyphs.size(); ++i) {
          renderer.draw_glyph(image, *font, glyphs[i], size, {20.0, 120}, Color{}, {}, direct);
        }
      });
      ft_all = std::max(ft_all, ft_all_r), ft_load = std::max(ft_load, ft_load_r), vr = std::max(vr, vr_r);
      vr_load = std::max(vr_load, vr_load_r), cached = std::max(cached, cached_r);
      uncached_draw = std::max(uncached_draw, uncached_draw_r);
    }
    const double ft_render = 1.0 / (1.0 / ft_all - 1.0 / ft_load);  // render time alone
    std::printf("%5.0f %14.0f %14.0f %14.0f %14.0f %14.0f %14.0f %8.2f %10.2f\n", size, ft_all, ft_render, vr,
                vr_load, cached, uncached_draw, vr / ft_render, vr_load / ft_all);
  }

  // A 10,000-character paragraph: shaping + layout, then drawing (cold cache, warm cache).
  std::string text;
  const std::string sentence =
      "The quick brown fox jumps over the lazy dog; AVAWA Typography, kerning & 1234567890 office affluent. ";
  while (text.size() < 10000) text += sentence;
  text.resize(10000);
  FontList fonts(font);
  TextStyle style;
  style.size = 16;
  LayoutOptions lo;
  lo.max_width = 1200;
  TextLayout layout;
  const auto t0 = Clock::now();
  int reps = 0;
  do {
    layout = layout_text(text, fonts, style, lo, {10, 20});
    ++reps;
  } while (std::chrono::duration<double>(Clock::now() - t0).count() < g_seconds);
  const double layout_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / reps;
  Image page(1220, static_cast<int>(layout.logical.y1) + 20);
  TextRenderer cold;
  const auto t1 = Clock::now();
  cold.draw(page, layout, Color::rgb8(0, 0, 0));
  const double cold_ms = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
  reps = 0;
  const auto t2 = Clock::now();
  do {
    cold.draw(page, layout, Color::rgb8(0, 0, 0));
    ++reps;
  } while (std::chrono::duration<double>(Clock::now() - t2).count() < g_seconds);
  const double warm_ms = std::chrono::duration<double, std::milli>(Clock::now() - t2).count() / reps;
  GlyphRenderOptions direct;
  direct.use_cache = false;
  TextRenderer outlines;
  const auto t3 = Clock::now();
  outlines.draw(page, layout, Color::rgb8(0, 0, 0), {}, direct);
  const double outline_ms = std::chrono::duration<double, std::milli>(Clock::now() - t3).count();
  std::printf("\n10,000-character paragraph at 16 px, %zu lines, %zu glyphs:\n", layout.lines.size(),
              layout.glyphs.size());
  std::printf("  shaping + layout          %8.2f ms\n", layout_ms);
  std::printf("  render, cold glyph cache  %8.2f ms\n", cold_ms);
  std::printf("  render, warm glyph cache  %8.2f ms\n", warm_ms);
  std::printf("  render, from outlines     %8.2f ms\n", outline_ms);
  std::printf("  total (layout + cold)     %8.2f ms\n", layout_ms + cold_ms);
#ifdef VRASTER_BENCH_WITH_BLEND2D
  {
    // Blend2D draws the same glyphs at the same positions (one glyph run, absolute positions), from their outlines
    // every time (it keeps no glyph bitmaps), onto an image of the same size; timed as the warm-cache loop above.
    BLFontData font_data;
    BLFontFace face_b;
    BLFont font_b;
    if (font_data.create_from_data(data.data(), data.size()) != BL_SUCCESS || face_b.create_from_data(font_data, 0) != BL_SUCCESS ||
        font_b.create_from_face(face_b, static_cast<float>(style.size)) != BL_SUCCESS) {
      std::fprintf(stderr, "Blend2D cannot load the font\n");
      return 1;
    }
    std::vector<std::uint32_t> ids;
    std::vector<BLPoint> at;
    for (const PositionedGlyph& g : layout.glyphs) {
      ids.push_back(g.glyph);
      at.push_back(BLPoint(g.position.x, g.position.y));
    }
    BLGlyphRun run{};
    run.set_glyph_data(ids.data());
    run.set_placement_data(at.data());
    run.size = ids.size();
    run.placement_type = BL_GLYPH_PLACEMENT_TYPE_USER_UNITS;
    BLImage b_page(page.width, page.height, BL_FORMAT_PRGB32);
    BLContext ctx(b_page);
    ctx.fill_all(BLRgba32(0xFFFFFFFFu));
    ctx.set_fill_style(BLRgba32(0xFF000000u));
    ctx.fill_glyph_run(BLPoint(0, 0), font_b, run);  // warm-up
    int b_reps = 0;
    const auto t4 = Clock::now();
    do {
      ctx.fill_glyph_run(BLPoint(0, 0), font_b, run);
      ++b_reps;
    } while (std::chrono::duration<double>(Clock::now() - t4).count() < g_seconds);
    const double blend2d_ms = std::chrono::duration<double, std::milli>(Clock::now() - t4).count() / b_reps;
    ctx.end();
    std::printf("  Blend2D, same glyphs      %8.2f ms   (warm cache / Blend2D: %.2f)\n", blend2d_ms, warm_ms / blend2d_ms);
  }
#endif
  FT_Done_Face(face);
  FT_Done_FreeType(lib);
  std::printf("(checksum %llu)\n", static_cast<unsigned long long>(g_sink));
  return 0;
}
