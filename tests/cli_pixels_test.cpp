// The `vraster` command end to end: render, fill-rules, text and demo write the pixels they should. Expected images
// are written here by hand (pixel-aligned rectangles, whose every pixel is known) or are properties that hold for
// any correct output (ink inside the expected box, text read left to right, known colours at known points).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "support/cli_run.hpp"
#include "vraster/png.hpp"

using namespace vraster;
using namespace vraster::test;

TEST(CliRender, PixelAlignedRectanglesGiveTheHandMadeImageInEveryMode) {
  const std::string svg = write_file("rects.svg", kRects);
  const std::string out = work_dir() + "/rects.png";
  for (const char* aa : {"none", "analytic", "exact", "ssaa-4", "msaa-8"}) {
    const Image image = run_to_png("render '" + svg + "' --aa " + aa, out);
    expect_pixels(image, kRectsMap,
                  {{'.', {0, 0, 0, 0}}, {'R', {255, 0, 0, 255}}, {'B', {0, 0, 255, 255}}, {'G', {0, 255, 0, 255}}},
                  std::string("render --aa ") + aa);
  }
  const Image white = run_to_png("render '" + svg + "' --background white", out);
  expect_pixels(white, kRectsMap,
                {{'.', {255, 255, 255, 255}}, {'R', {255, 0, 0, 255}}, {'B', {0, 0, 255, 255}}, {'G', {0, 255, 0, 255}}},
                "render --background white");
}

// --threads N rasterizes large fills in bands on N threads: the image must be the same bytes as with one thread,
// through clips, group opacity, strokes and curves, in 8 and 16 bits.
TEST(CliRender, ThreadsGiveTheSameBytes) {
  const std::string svg = write_file("threads.svg", R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300">
  <clipPath id="c"><circle cx="200" cy="150" r="130"/></clipPath>
  <path d="M 10 10 L 390 40 L 60 290 L 300 20 L 380 280 Z" fill="#3070c0" fill-opacity="0.7" fill-rule="evenodd"/>
  <g clip-path="url(#c)" opacity="0.8">
    <path d="M 0 150 C 100 -50 300 350 400 150 S 200 0 0 150 Z" fill="#c03030"/>
    <rect x="50.3" y="60.7" width="300.2" height="180.9" fill="#30c070" fill-opacity="0.5"/>
  </g>
  <path d="M 20 280 Q 200 -100 380 280" fill="none" stroke="#202020" stroke-width="9.5"/>
</svg>)svg");
  // The PNG files themselves are compared (the encoder is deterministic), so 16-bit output is compared in full.
  auto render_bytes = [&](const std::string& args) {
    const std::string out = work_dir() + "/threads.png";
    std::filesystem::remove(out);
    std::string log;
    EXPECT_EQ(run_vraster(args + " -o '" + out + "'", log), 0) << args << "\n" << log;
    std::ifstream in(out, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* depth : {"8", "16"}) {
    for (const char* aa : {"analytic", "none", "msaa-8"}) {
      const std::string args = "render '" + svg + "' --depth " + depth + " --aa " + aa;
      const std::string one = render_bytes(args + " --threads 1");
      ASSERT_GT(one.size(), 100u) << args;
      EXPECT_TRUE(one == render_bytes(args + " --threads 3")) << args;
    }
    // --hairline draws with the core Renderer, whose fills wait in its queue with threads until svg::render flushes.
    const std::string args = "render '" + svg + "' --depth " + depth + " --hairline wu";
    const std::string one = render_bytes(args + " --threads 1");
    ASSERT_GT(one.size(), 100u) << args;
    EXPECT_TRUE(one == render_bytes(args + " --threads 3")) << args;
  }
}

TEST(CliRender, SixteenBitOutputHasFullRangeChannels) {
  const std::string svg = write_file("rects16.svg", kRects);
  const std::string out = work_dir() + "/rects16.png";
  std::filesystem::remove(out);
  std::string log;
  ASSERT_EQ(run_vraster("render '" + svg + "' --depth 16 -o '" + out + "'", log), 0) << log;
  const Image16 image = read_png16(out);
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 6);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) {
      const std::uint16_t* p = image.pixel(x, y);
      const char c = kRectsMap[y][x];
      const int r = c == 'R' ? 65535 : 0, g = c == 'G' ? 65535 : 0, b = c == 'B' ? 65535 : 0;
      const int a = c == '.' ? 0 : 65535;
      EXPECT_TRUE(p[0] == r && p[1] == g && p[2] == b && p[3] == a) << "pixel (" << x << ", " << y << ")";
    }
  }
}

TEST(CliRender, HalfCoveredPixelsAreHalfGreyAndTheCentreRuleDecidesAliased) {
  // A black bar from x = 0.5 to 3.5 on white: analytic coverage is 1/2 in the first and last column; sampled at
  // pixel centres (--aa none), the centre x = 0.5 lies on the bar's left edge (inside, top-left rule) and x = 3.5
  // on its right edge (outside).
  const std::string svg = write_file("half.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2">
  <rect x="0.5" y="0" width="3" height="2" fill="black"/>
</svg>
)");
  const std::string out = work_dir() + "/half.png";
  const Image analytic = run_to_png("render '" + svg + "' --background white --aa analytic", out);
  ASSERT_EQ(analytic.width, 4);
  for (int y = 0; y < 2; ++y) {
    for (int x : {0, 3}) {
      const int v = analytic.pixel(x, y)[0];
      EXPECT_TRUE(v == 127 || v == 128) << "half-covered pixel (" << x << ", " << y << ") is " << v;
    }
    EXPECT_EQ(analytic.pixel(1, y)[0], 0);
    EXPECT_EQ(analytic.pixel(2, y)[0], 0);
  }
  const Image aliased = run_to_png("render '" + svg + "' --background white --aa none", out);
  expect_pixels(aliased, {"###.", "###."}, {{'#', {0, 0, 0, 255}}, {'.', {255, 255, 255, 255}}}, "render --aa none");
}

namespace {

// Fill-rule sheet geometry (src/cli/fill_rules.cpp): panels of `panel` px in 3 columns and 2 rows, a 12 px margin
// around each, 22 px for the label under it; the panels in the order evenodd, nonzero, nonexterior, positive,
// negative, abs-geq-2.
struct SheetPanel {
  int x0, y0;
};
SheetPanel panel_at(int k, int panel) { return {12 + (k % 3) * (panel + 12), 12 + (k / 3) * (panel + 22 + 12)}; }

// Two squares, both with their left side running down (winding +1 inside each, as segments running downward count
// +1): winding 1 in the ring 0..8 \ 2..6 and 2 in the inner square.
const char* kNested = R"(<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8">
  <path d="M0 0V8H8V0Z M2 2V6H6V2Z" fill="black"/>
</svg>
)";

}  // namespace

TEST(CliFillRules, EachPanelFillsWhatItsRuleSays) {
  const std::string svg = write_file("nested.svg", kNested);
  const std::string out = work_dir() + "/nested_sheet.png";
  const int panel = 32;  // scale 4: the squares land on whole pixels
  const Image sheet = run_to_png("fill-rules '" + svg + "' --panel 32 --aa analytic", out);
  ASSERT_EQ(sheet.width, 3 * (panel + 12) + 12);
  ASSERT_EQ(sheet.height, 2 * (panel + 22 + 12) + 12);
  struct Want {
    const char* rule;
    bool ring, inner;
  };
  const Want wants[] = {{"evenodd", true, false}, {"nonzero", true, true}, {"nonexterior", true, true},
                        {"positive", true, true}, {"negative", false, false}, {"abs-geq-2", false, true}};
  for (int k = 0; k < 6; ++k) {
    const SheetPanel p = panel_at(k, panel);
    for (int y = 0; y < panel; ++y) {
      for (int x = 0; x < panel; ++x) {
        const bool inner = x >= 8 && x < 24 && y >= 8 && y < 24;
        const bool filled = inner ? wants[k].inner : wants[k].ring;
        const std::uint8_t* px = sheet.pixel(p.x0 + x, p.y0 + y);
        const int want = filled ? 0 : 255;
        ASSERT_TRUE(px[0] == want && px[1] == want && px[2] == want && px[3] == 255)
            << wants[k].rule << " panel, pixel (" << x << ", " << y << ") is " << describe(px);
      }
    }
    // The label under the panel has ink (the built-in bitmap font in the sheet's ink colour).
    int label_ink = 0;
    for (int y = p.y0 + panel + 1; y < p.y0 + panel + 22; ++y) {
      for (int x = p.x0; x < p.x0 + panel; ++x) label_ink += sheet.pixel(x, y)[0] < 128;
    }
    EXPECT_GT(label_ink, 10) << wants[k].rule << " label";
  }
}

TEST(CliFillRules, FxaaSmoothsTheAliasedSheet) {
  // A triangle with two slanted sides: aliased, its panels hold only black and white; FXAA blends the staircase
  // steps, so the fxaa sheet differs from the aliased one and has grey levels between them, on edges only.
  const std::string svg = write_file("triangle.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">
  <path d="M1 1L3 9L9 4Z" fill="black"/>
</svg>
)");
  const int panel = 60;
  const Image aliased = run_to_png("fill-rules '" + svg + "' --panel 60 --aa none", work_dir() + "/tri_none.png");
  const Image smooth = run_to_png("fill-rules '" + svg + "' --panel 60 --aa fxaa", work_dir() + "/tri_fxaa.png");
  ASSERT_EQ(aliased.width, smooth.width);
  ASSERT_EQ(aliased.height, smooth.height);
  for (int k = 0; k < 6; ++k) {
    const SheetPanel p = panel_at(k, panel);
    int aliased_grey = 0, smooth_grey = 0, changed = 0, changed_off_edge = 0;
    for (int y = 0; y < panel; ++y) {
      for (int x = 0; x < panel; ++x) {
        const int a = aliased.pixel(p.x0 + x, p.y0 + y)[0], s = smooth.pixel(p.x0 + x, p.y0 + y)[0];
        aliased_grey += a != 0 && a != 255;
        smooth_grey += s != 0 && s != 255;
        if (a == s) continue;
        ++changed;
        // A pixel FXAA may change has an aliased 4-neighbour of the other colour.
        bool edge = false;
        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < panel && ny < panel && aliased.pixel(p.x0 + nx, p.y0 + ny)[0] != a) {
            edge = true;
          }
        }
        changed_off_edge += !edge;
      }
    }
    const bool drawn = k != 4 && k != 5;  // winding 1 inside: negative and abs-geq-2 fill nothing
    EXPECT_EQ(aliased_grey, 0) << "panel " << k << ": the aliased sheet has grey levels";
    if (drawn) {
      EXPECT_GT(smooth_grey, 20) << "panel " << k << ": --aa fxaa left the edges aliased";
      EXPECT_GT(changed, 20) << "panel " << k;
    } else {
      EXPECT_EQ(changed, 0) << "panel " << k << ": an empty panel changed";
    }
    EXPECT_EQ(changed_off_edge, 0) << "panel " << k;
  }
}

#if VRASTER_CLI_HAS_TEXT
namespace {

struct Ink {
  long pixels = 0;
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;  // inclusive box of pixels with any ink
  double cx = 0;                                     // ink-weighted mean x
};

// Ink of black text on white: 255 - red channel.
Ink ink_of(const Image& image, int ya = 0, int yb = -1) {
  if (yb < 0) yb = image.height;
  Ink ink;
  double total = 0;
  for (int y = ya; y < yb; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const int v = 255 - image.pixel(x, y)[0];
      if (v == 0) continue;
      ++ink.pixels;
      total += v;
      ink.cx += v * (x + 0.5);
      ink.x0 = std::min(ink.x0, x), ink.y0 = std::min(ink.y0, y);
      ink.x1 = std::max(ink.x1, x), ink.y1 = std::max(ink.y1, y);
    }
  }
  if (total > 0) ink.cx /= total;
  return ink;
}

}  // namespace

TEST(CliText, CapitalISitsOnTheBaselineWithTheCapHeight) {
  // The default font, Noto Sans Regular (1000 units per em): hhea ascender 1069, descender -293, line gap 0; the
  // capital I is a plain stem from the baseline to the cap height, 714 units. At 100 px with a 10 px margin the
  // image is (advance + 20) x ceil(106.9 + 29.3 + 20) = 157 px high, the baseline at round(10 + 106.9) = 117: the
  // stem covers rows 117 - 71.4 = 45.6 to 117, so rows 46..116 are solid at its middle column and row 117 is blank.
  const Image image =
      run_to_png("text I --size 100 --margin 10 --background white --color black", work_dir() + "/text_I.png");
  ASSERT_EQ(image.height, 157);
  const Ink ink = ink_of(image);
  ASSERT_GT(ink.pixels, 0) << "blank text image";
  EXPECT_EQ(ink.y0, 45);
  EXPECT_EQ(ink.y1, 116);
  EXPECT_GE(ink.x0, 10);
  EXPECT_LE(ink.x1, image.width - 11);
  const int mid = static_cast<int>(ink.cx);
  for (int y = 46; y <= 116; ++y) EXPECT_EQ(image.pixel(mid, y)[0], 0) << "stem row " << y;
  // The stem is a solid bar: in its middle row every pixel is black or white but for one edge pixel each side.
  int partial = 0;
  for (int x = 0; x < image.width; ++x) {
    const int v = image.pixel(x, 80)[0];
    partial += v != 0 && v != 255;
  }
  EXPECT_LE(partial, 2);
}

TEST(CliText, TextReadsLeftToRightInsideItsMargin) {
  // "l." against ".l": the tall letter's ink (the top half of the line, where the full stop has none) lies left
  // of the image centre in the first and right of it in the second.
  for (const bool tall_first : {true, false}) {
    const std::string text = tall_first ? "l......" : "......l";
    const Image image = run_to_png("text '" + text + "' --size 40 --margin 8 --background white --color black",
                                   work_dir() + "/text_order.png");
    ASSERT_GT(image.width, 0);
    const Ink all = ink_of(image), top = ink_of(image, 0, image.height / 2);
    ASSERT_GT(all.pixels, 20) << text << ": blank";
    EXPECT_GE(all.x0, 7) << text;  // the margin, less the one pixel antialiasing may reach
    EXPECT_GE(all.y0, 7) << text;
    EXPECT_LE(all.x1, image.width - 8) << text;
    EXPECT_LE(all.y1, image.height - 8) << text;
    ASSERT_GT(top.pixels, 0) << text;
    if (tall_first) {
      EXPECT_LT(top.x1, image.width / 4) << text;
    } else {
      EXPECT_GT(top.x0, 3 * image.width / 4) << text;
    }
  }
}
#endif

TEST(CliDemo, KnownColoursAtKnownPoints) {
  // Points of the embedded scene (src/cli/demo.cpp) inside one shape each, away from every edge, and the colour the
  // scene gives them, worked out by hand from its SVG.
  const Image image = run_to_png("demo", work_dir() + "/demo.png");
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 620);  // the SVG scene (400 px) and the canvas panel under it
  struct Probe {
    const char* what;
    int x, y;
    double r, g, b;
  };
  const Probe probes[] = {
      {"backdrop #f4f1ea", 635, 5, 244, 241, 234},
      {"lower band #d9e4dd", 5, 350, 217, 228, 221},
      {"evenodd pentagram: hollow centre", 100, 107, 244, 241, 234},
      {"nonzero pentagram: filled centre #c0392b", 270, 107, 192, 57, 43},
      {"pentagram tip", 100, 35, 192, 57, 43},
      // #2e86c1 at opacity 0.85 over the backdrop: 0.85 * c + 0.15 * backdrop.
      {"translucent blue", 460, 160, 0.85 * 46 + 0.15 * 244, 0.85 * 134 + 0.15 * 241, 0.85 * 193 + 0.15 * 234},
      {"evenodd ring's hole shows the blue", 460, 80, 0.85 * 46 + 0.15 * 244, 0.85 * 134 + 0.15 * 241,
       0.85 * 193 + 0.15 * 234},
      {"yellow ring #f7dc6f", 460, 50, 247, 220, 111},
      // #e74c3c at opacity 0.5 over the backdrop.
      {"translucent red circle", 70, 200, 0.5 * 231 + 0.5 * 244, 0.5 * 76 + 0.5 * 241, 0.5 * 60 + 0.5 * 234},
      {"outer concentric ring #117a65", 300, 235, 17, 122, 101},
      {"gap between rings", 300, 245, 244, 241, 234},
      // The canvas panel (draw_canvas_panel): blue #2e86c1 squares under orange #f39c12 discs, one operator each.
      {"multiply: blue x orange", 128, 482, 46 * 243 / 255.0, 134 * 156 / 255.0, 193 * 18 / 255.0},
      {"difference: |blue - orange|", 272, 482, 197, 22, 175},
      {"destination-out: the square outside the disc", 400, 450, 46, 134, 193},
      // ... inside the disc the layer is empty, so the banner shows: its gradient from #2e4053 (0.5) to #512e5f (1)
      // at t = 416.5 / 640.
      {"destination-out: the banner through the hole", 416, 482, 46 + 35 * (416.5 / 640 - 0.5) / 0.5,
       64 - 18 * (416.5 / 640 - 0.5) / 0.5, 83 + 12 * (416.5 / 640 - 0.5) / 0.5},
  };
  for (const Probe& p : probes) {
    const std::uint8_t* px = image.pixel(p.x, p.y);
    EXPECT_NEAR(px[0], p.r, 1.5) << p.what << " at (" << p.x << ", " << p.y << "): " << describe(px);
    EXPECT_NEAR(px[1], p.g, 1.5) << p.what << " at (" << p.x << ", " << p.y << "): " << describe(px);
    EXPECT_NEAR(px[2], p.b, 1.5) << p.what << " at (" << p.x << ", " << p.y << "): " << describe(px);
    EXPECT_EQ(px[3], 255) << p.what;
  }
  // The 0.3 px hairlines at y = 385, 390, 395 thin out instead of vanishing: the rows they cross are darker than
  // the band by a fraction of the stroke colour (0.3 px of ink split over two rows: 10% to 20% of the way).
  for (int y : {384, 385}) {
    const double band = 217, ink = 27;  // red channel of #d9e4dd and #1b2631
    const double share = (band - image.pixel(100, y)[0]) / (band - ink);
    EXPECT_GT(share, 0.08) << "row " << y;
    EXPECT_LT(share, 0.25) << "row " << y;
  }
}
