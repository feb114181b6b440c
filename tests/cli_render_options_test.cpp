// `vraster render`'s options as users of rsvg-convert and resvg expect them: -z/--zoom, --dpi, --export-id, '-'
// for standard input and output, and batches into a directory on several threads. Expected images are drawn by
// hand (pixel-aligned shapes: every pixel is known) or are the same render made another way (a batch on four
// threads gives the images of one thread; text at 12pt and 192 dpi is text at 32px).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_run.hpp"
#include "vraster/png.hpp"

using namespace vraster;
using namespace vraster::test;

namespace {

const std::vector<std::pair<char, Rgba>> kLegend = {
    {'.', {0, 0, 0, 0}}, {'R', {255, 0, 0, 255}}, {'B', {0, 0, 255, 255}}, {'G', {0, 255, 0, 255}}};

/// `map` with each letter repeated `factor` times across and down.
std::vector<std::string> scaled(const std::vector<std::string>& map, int factor) {
  std::vector<std::string> out;
  for (const std::string& row : map) {
    std::string wide;
    for (const char c : row) wide.append(static_cast<std::size_t>(factor), c);
    for (int k = 0; k < factor; ++k) out.push_back(wide);
  }
  return out;
}

/// Runs a shell command line (for redirections); returns the exit status.
int run_shell(const std::string& command) {
  const int rc = std::system(command.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string cli() { return std::string("'") + VRASTER_CLI + "'"; }

/// The size of the image `args` renders (0 x 0 when it fails).
std::pair<int, int> rendered_size(const std::string& args, const std::string& out) {
  const Image image = run_to_png(args, out);
  return {image.width, image.height};
}

/// Whether two images have the same size and the same bytes.
bool same_pixels(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) return false;
  for (int y = 0; y < a.height; ++y) {
    if (!std::equal(a.pixel(0, y), a.pixel(0, y) + 4 * a.width, b.pixel(0, y))) return false;
  }
  return true;
}

}  // namespace

// --- -z / --zoom ---

TEST(CliZoom, ZoomTwoRepeatsEveryPixelOfTheHandMadeImageTwice) {
  const std::string svg = write_file("zoom.svg", kRects);
  const std::string out = work_dir() + "/zoom.png";
  expect_pixels(run_to_png("render '" + svg + "' -z 2", out), scaled(kRectsMap, 2), kLegend, "-z 2");
  expect_pixels(run_to_png("render '" + svg + "' --zoom 3", out), scaled(kRectsMap, 3), kLegend, "--zoom 3");
  EXPECT_EQ(rendered_size("render '" + svg + "' -z 0.5", out), std::make_pair(4, 3));
  EXPECT_EQ(rendered_size("render '" + svg + "' -z 0.3", out), std::make_pair(3, 2));  // 2.4 x 1.8 rounded up
}

TEST(CliZoom, WidthAndHeightAreMaximaOfTheZoomedSizeAsInRsvgConvert) {
  const std::string svg = write_file("zoom_cap.svg", kRects);  // 8 x 6
  const std::string out = work_dir() + "/zoom_cap.png";
  const std::string render = "render '" + svg + "' ";
  EXPECT_EQ(rendered_size(render + "-z 2 -w 100", out), std::make_pair(16, 12));        // fits: the zoom
  EXPECT_EQ(rendered_size(render + "-z 2 -w 16 -h 12", out), std::make_pair(16, 12));   // fits exactly
  EXPECT_EQ(rendered_size(render + "-z 2 -w 10", out), std::make_pair(10, 8));          // as -w 10 alone
  EXPECT_EQ(rendered_size(render + "-z 3 -h 12", out), std::make_pair(16, 12));         // as -h 12 alone
  EXPECT_EQ(rendered_size(render + "-z 4 -w 20 -h 20", out), std::make_pair(20, 20));   // as -w 20 -h 20
}

TEST(CliZoom, ZeroNegativeNanInfiniteAndNonNumericZoomsAreUsageErrors) {
  const std::string svg = write_file("zoom_bad.svg", kRects);
  const std::string out = work_dir() + "/zoom_bad.png";
  for (const char* z : {"0", "-1", "-0", "nan", "inf", "-inf", "1e999", "two", "''", "2x"}) {
    std::filesystem::remove(out);
    std::string log;
    EXPECT_EQ(run_vraster("render '" + svg + "' -o '" + out + "' -z " + z, log), 2) << z;
    EXPECT_NE(log.find("-z needs a finite number greater than 0"), std::string::npos) << z << ": " << log;
    EXPECT_FALSE(std::filesystem::exists(out)) << z;
  }
  std::string log;
  EXPECT_EQ(run_vraster("render '" + svg + "' -o '" + out + "' -z 1e6", log), 2);  // 8e6 px wide: out of range
  EXPECT_FALSE(std::filesystem::exists(out));
}

// --- --dpi ---

TEST(CliDpi, AnInchIsDpiPixels) {
  const std::string svg = write_file("dpi_inch.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="1in" height="0.5in">
  <rect width="100%" height="100%" fill="#ff0000"/></svg>)");
  const std::string out = work_dir() + "/dpi_inch.png";
  EXPECT_EQ(rendered_size("render '" + svg + "'", out), std::make_pair(96, 48));
  EXPECT_EQ(rendered_size("render '" + svg + "' --dpi 192", out), std::make_pair(192, 96));
  EXPECT_EQ(rendered_size("render '" + svg + "' --dpi 72 -z 2", out), std::make_pair(144, 72));
}

TEST(CliDpi, MillimetresPointsAndPicasInsideTheDocumentFollowTheDpi) {
  // At 254 dpi a millimetre is 10 px: a 10mm x 5mm rect is 100 x 50 pixels of a 2cm x 1cm (200 x 100) image.
  const std::string mm = write_file("dpi_mm.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="2cm" height="1cm">
  <rect width="10mm" height="5mm" fill="#ff0000"/></svg>)");
  // At 72 dpi a point is 1 px and a pica 12 px.
  const std::string pt = write_file("dpi_pt.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="1in" height="36pt">
  <rect x="12pt" y="1pc" width="1pc" height="6pt" fill="#ff0000"/></svg>)");
  struct Case {
    std::string args;
    int width, height, x0, y0, x1, y1;  // image size; the red rectangle
  };
  for (const Case& c : {Case{"'" + mm + "' --dpi 254", 200, 100, 0, 0, 100, 50},
                        Case{"'" + pt + "' --dpi 72", 72, 36, 12, 12, 24, 18},
                        Case{"'" + pt + "' --dpi 144", 144, 72, 24, 24, 48, 36}}) {
    const Image image = run_to_png("render " + c.args, work_dir() + "/dpi_units.png");
    ASSERT_EQ(image.width, c.width) << c.args;
    ASSERT_EQ(image.height, c.height) << c.args;
    int wrong = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const bool inside = x >= c.x0 && x < c.x1 && y >= c.y0 && y < c.y1;
        const std::uint8_t* p = image.pixel(x, y);
        const bool ok = inside ? p[0] == 255 && p[1] == 0 && p[2] == 0 && p[3] == 255 : p[3] == 0;
        if (!ok && ++wrong <= 4) ADD_FAILURE() << c.args << ": pixel (" << x << ", " << y << ") is " << describe(p);
      }
    }
    EXPECT_EQ(wrong, 0) << c.args;
  }
}

#if VRASTER_CLI_HAS_TEXT
TEST(CliDpi, TwelvePointTextAt192DpiIsThirtyTwoPixelText) {
  // 12pt = 12/72 in = 32 px at 192 dpi: the same glyphs as font-size 32px at the default 96 dpi.
  const auto doc = [](const char* size) {
    return std::string(R"(<svg xmlns="http://www.w3.org/2000/svg" width="120" height="48">)") +
           R"(<text x="4" y="36" font-size=")" + size + R"(" fill="#000">Hig</text></svg>)";
  };
  const std::string pt = write_file("dpi_text_pt.svg", doc("12pt"));
  const std::string px = write_file("dpi_text_px.svg", doc("32px"));
  const std::string fonts = " --no-system-fonts";
  const Image a = run_to_png("render '" + pt + "' --dpi 192" + fonts, work_dir() + "/dpi_text_pt.png");
  const Image b = run_to_png("render '" + px + "'" + fonts, work_dir() + "/dpi_text_px.png");
  const Image c = run_to_png("render '" + pt + "'" + fonts, work_dir() + "/dpi_text_96.png");  // 16px
  EXPECT_TRUE(same_pixels(a, b));
  EXPECT_FALSE(same_pixels(a, c));  // the dpi did change the text
}
#endif

TEST(CliDpi, OutOfRangeDpiIsAUsageError) {
  const std::string svg = write_file("dpi_bad.svg", kRects);
  for (const char* dpi : {"0", "-96", "9", "4001", "nan", "inf", "high"}) {
    std::string log;
    EXPECT_EQ(run_vraster("render '" + svg + "' -o '" + work_dir() + "/dpi_bad.png' --dpi " + dpi, log), 2) << dpi;
    EXPECT_NE(log.find("--dpi"), std::string::npos) << log;
  }
}

// --- --export-id ---

// A rect inside a translated group, over a green background that must not appear: its stroke bounding box is
// 8 x 5 (x 6..14, y 5..10 in the document), the 2-wide stroke ring around a 4 x 1 fill.
const char* kExport = R"SVG(<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="20" height="20">
  <defs><rect id="tile" width="3" height="2" fill="#ff0000"/></defs>
  <rect id="back" width="20" height="20" fill="#00ff00"/>
  <g id="outer" transform="translate(5 4)">
    <rect id="framed" x="1" y="2" width="6" height="3" fill="#ff0000" stroke="#0000ff" stroke-width="2"/>
  </g>
  <g id="pair" transform="translate(10 10)">
    <rect width="2" height="2" fill="#ff0000"/>
    <rect x="4" y="3" width="2" height="1" fill="#0000ff"/>
  </g>
  <use xlink:href="#tile" x="15" y="15"/>
  <rect id="hidden" width="5" height="5" display="none"/>
</svg>
)SVG";

TEST(CliExportId, TheElementAloneInItsStrokeBoundingBox) {
  const std::string svg = write_file("export.svg", kExport);
  const std::string out = work_dir() + "/export.png";
  const std::vector<std::string> framed = {
      "BBBBBBBB",  //
      "BBBBBBBB",  //
      "BBRRRRBB",  //
      "BBBBBBBB",  //
      "BBBBBBBB",  //
  };
  expect_pixels(run_to_png("render '" + svg + "' --export-id framed", out), framed, kLegend, "--export-id framed");
  expect_pixels(run_to_png("render '" + svg + "' --export-id '#framed' -z 2", out), scaled(framed, 2), kLegend,
                "--export-id #framed -z 2");
  EXPECT_EQ(rendered_size("render '" + svg + "' --export-id framed -w 16", out), std::make_pair(16, 10));
}

TEST(CliExportId, AGroupIsTheUnionOfItsChildrenAndAUsedCopyIsFound) {
  const std::string svg = write_file("export_group.svg", kExport);
  const std::string out = work_dir() + "/export_group.png";
  expect_pixels(run_to_png("render '" + svg + "' --export-id pair", out),
                {"RR....", "RR....", "......", "....BB"}, kLegend, "--export-id pair");
  // The only drawn copy of the rect in <defs> is the one <use> makes.
  expect_pixels(run_to_png("render '" + svg + "' --export-id tile", out), {"RRR", "RRR"}, kLegend, "--export-id tile");
}

TEST(CliExportId, AnIdThatIsNotDrawnIsAnErrorWithoutOutput) {
  const std::string svg = write_file("export_missing.svg", kExport);
  const std::string out = work_dir() + "/export_missing.png";
  for (const char* id : {"nothing", "hidden"}) {
    std::filesystem::remove(out);
    std::string log;
    EXPECT_EQ(run_vraster("render '" + svg + "' --export-id " + id + " -o '" + out + "'", log), 2) << id;
    EXPECT_NE(log.find(std::string("no drawn element has the id '") + id + "'"), std::string::npos) << log;
    EXPECT_FALSE(std::filesystem::exists(out)) << id;
  }
}

// --- '-': standard input and standard output ---

TEST(CliStdio, StandardInputToStandardOutputGivesTheHandMadeImage) {
  const std::string svg = write_file("stdio.svg", kRects);
  const std::string out = work_dir() + "/stdio.png";
  std::filesystem::remove(out);
  ASSERT_EQ(run_shell(cli() + " render - -o - < '" + svg + "' > '" + out + "'"), 0);
  expect_pixels(read_png(out), kRectsMap, kLegend, "render - -o -");
  ASSERT_EQ(run_shell(cli() + " render '" + svg + "' -z 2 -o - > '" + out + "'"), 0);
  expect_pixels(read_png(out), scaled(kRectsMap, 2), kLegend, "render IN -z 2 -o -");
}

TEST(CliStdio, ImagesOfStandardInputComeFromTheCurrentDirectory) {
  const std::string dir = work_dir() + "/stdin_images";
  std::filesystem::create_directories(dir + "/sub");
  Image green(2, 2);
  green.clear(Color{0, 1, 0, 1});
  write_png(dir + "/sub/green.png", green);
  const std::string svg = write_file("stdin_images/doc.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2">
  <image href="sub/green.png" width="2" height="2"/></svg>)");
  const std::string out = dir + "/out.png";
  std::filesystem::remove(out);
  ASSERT_EQ(run_shell("cd '" + dir + "' && " + cli() + " render - -o out.png < doc.svg"), 0);
  expect_pixels(read_png(out), {"GG..", "GG.."}, kLegend, "<image> of standard input");
}

TEST(CliStdio, AFailureWritesNothingOnStandardOutput) {
  const std::string svg = write_file("stdio_broken.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"4\" height=\"4\">\n<rect\n");
  const std::string out = work_dir() + "/stdio_broken.png";
  const std::string err = work_dir() + "/stdio_broken.txt";
  ASSERT_EQ(run_shell(cli() + " render - -o - < '" + svg + "' > '" + out + "' 2> '" + err + "'"), 2);
  EXPECT_EQ(std::filesystem::file_size(out), 0u);
  std::ifstream in(err);
  const std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(message.find("<stdin>:"), std::string::npos) << message;  // FILE:LINE:COLUMN with the input's name
}

// --- batches: several inputs into DIR/ on -j threads ---

namespace {

/// Writes the batch inputs: kRects first, then documents that differ (colours, shapes, a gradient, a clip,
/// text when it is built) so that a mix-up between files or threads shows.
std::vector<std::string> write_batch_inputs(const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> names;
  auto add = [&](const std::string& name, const std::string& text) {
    write_file(dir.substr(work_dir().size() + 1) + "/" + name, text);
    names.push_back(name);
  };
  add("rects.svg", kRects);
  for (int k = 0; k < 9; ++k) {
    const std::string c = std::to_string(k * 25);
    const std::string n = std::to_string(k);
    std::string doc = R"SVG(<svg xmlns="http://www.w3.org/2000/svg" width="40" height="30"><defs>)SVG";
    doc += R"SVG(<linearGradient id="g"><stop offset="0" stop-color="rgb()SVG" + std::to_string(k * 25) +
           R"SVG(,0,200)"/><stop offset="1" stop-color="#ff0"/></linearGradient>)SVG";
    doc += R"SVG(<clipPath id="c"><circle cx="20" cy="15" r=")SVG" + std::to_string(6 + k) + R"SVG("/></clipPath></defs>)SVG";
    doc += R"SVG(<rect width="40" height="30" fill="url(#g)" clip-path="url(#c)"/>)SVG";
    doc += R"SVG(<path d="M2 2L)SVG" + std::to_string(10 + 3 * k) + R"SVG( 28" stroke="#000" stroke-width="1.5"/>)SVG";
#if VRASTER_CLI_HAS_TEXT
    doc += R"SVG(<text x="2" y="12" font-size="10">)SVG" + n + "</text>";
#endif
    add("doc" + n + ".svg", doc + "</svg>");
  }
  return names;
}

}  // namespace

TEST(CliBatch, EachInputBecomesDirNamePngAndFourThreadsGiveTheImagesOfOne) {
  const std::string in = work_dir() + "/batch/in";
  std::filesystem::remove_all(work_dir() + "/batch");
  const std::vector<std::string> names = write_batch_inputs(in);
  write_file("batch/in/broken.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"4\" height=\"4\">\n<rect\n");
  std::string inputs;
  for (const std::string& n : names) inputs += " '" + in + "/" + n + "'";
  inputs += " '" + in + "/broken.svg'";
  for (const char* jobs : {"1", "4", "0"}) {
    const std::string out = work_dir() + "/batch/j" + jobs + "/";  // a new directory, named with a trailing '/'
    std::string log;
    // The broken file fails (status 2) with its name in the message; every other file is still written.
    EXPECT_EQ(run_vraster("render" + inputs + " -o '" + out + "' --no-system-fonts -j " + jobs, log), 2) << log;
    EXPECT_NE(log.find("broken.svg:"), std::string::npos) << log;
    EXPECT_FALSE(std::filesystem::exists(out + "broken.png"));
    for (const auto& entry : std::filesystem::directory_iterator(out)) {
      EXPECT_EQ(entry.path().extension(), ".png") << entry.path();  // no temporary left behind
    }
  }
  expect_pixels(read_png(work_dir() + "/batch/j4/rects.png"), kRectsMap, kLegend, "batch rects.png");
  for (const std::string& n : names) {
    const std::string png = n.substr(0, n.size() - 4) + ".png";
    const Image one = read_png(work_dir() + "/batch/j1/" + png);
    EXPECT_TRUE(same_pixels(one, read_png(work_dir() + "/batch/j4/" + png))) << png << ": -j 4 differs from -j 1";
    EXPECT_TRUE(same_pixels(one, read_png(work_dir() + "/batch/j0/" + png))) << png << ": -j 0 differs from -j 1";
    // A single run of the same file gives the same image as its batch.
    std::string log;
    const std::string single = work_dir() + "/batch/single.png";
    ASSERT_EQ(run_vraster("render '" + in + "/" + n + "' -o '" + single + "' --no-system-fonts", log), 0) << log;
    EXPECT_TRUE(same_pixels(one, read_png(single))) << png << ": the batch differs from a single run";
  }
}

// More files written at once than the fixed slots that name partial files for removal on a signal (64): writers
// wait for a slot instead of going without one, and every file is still written whole.
TEST(CliBatch, MoreWorkersThanCleanupSlotsWriteEveryFile) {
  const std::string dir = work_dir() + "/many";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/in");
  std::string inputs;
  for (int k = 0; k < 100; ++k) {
    const std::string name = "many/in/r" + std::to_string(k) + ".svg";
    const std::string path = write_file(name, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"300\" height=\"300\"><rect x=\"" +
                         std::to_string(k) + "\" width=\"50\" height=\"50\"/></svg>");
    inputs += " '" + path + "'";
  }
  std::string log;
  ASSERT_EQ(run_vraster("render" + inputs + " -o '" + dir + "/out/' --no-system-fonts -j 100", log), 0) << log;
  int pngs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/out")) {
    EXPECT_EQ(entry.path().extension(), ".png") << entry.path();  // no temporary left behind
    ++pngs;
  }
  EXPECT_EQ(pngs, 100);
  const Image last = read_png(dir + "/out/r99.png");
  EXPECT_EQ(last.pixel(120, 10)[3], 255);  // the rect of the last file, at x 99 to 149
  EXPECT_EQ(last.pixel(150, 10)[3], 0);
}

TEST(CliBatch, CollidingOutputNamesAreRefusedBeforeAnythingIsRendered) {
  const std::string dir = work_dir() + "/collide";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/a");
  std::filesystem::create_directories(dir + "/b");
  std::filesystem::create_directories(dir + "/out");
  write_file("collide/a/x.svg", kRects);
  write_file("collide/b/x.svg", kRects);
  write_file("collide/first.svg", kRects);
  std::string log;
  EXPECT_EQ(run_vraster("render '" + dir + "/first.svg' '" + dir + "/a/x.svg' '" + dir + "/b/x.svg' -o '" + dir +
                            "/out' -j 2",
                        log),
            2);
  EXPECT_NE(log.find("would both write"), std::string::npos) << log;
  EXPECT_TRUE(std::filesystem::is_empty(dir + "/out"));  // not even first.png
}

TEST(CliBatch, SeveralInputsNeedADirectoryAndStandardInputHasNoName) {
  const std::string svg = write_file("batch_usage.svg", kRects);
  std::string log;
  EXPECT_EQ(run_vraster("render '" + svg + "' '" + svg + "' -o '" + work_dir() + "/batch_usage.png'", log), 2);
  EXPECT_NE(log.find("several inputs need -o DIR/"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(work_dir() + "/batch_usage.png"));
  EXPECT_EQ(run_vraster("render - '" + svg + "' -o '" + work_dir() + "/batch_usage_dir/'", log), 2);
  EXPECT_NE(log.find("standard input"), std::string::npos) << log;
}

// --- documents of many shapes: drawn straight onto the image (no recording), with the recorded render's pixels ---

TEST(CliLargeDocuments, ManyShapesDrawnDirectlyMatchTheRecordedAndPlannedRender) {
  // 51,000 shapes, just over the 50,000 nodes above which one frame is drawn directly (sanitizer builds take half a
  // minute for it): translucent fills, strokes, a group with opacity, a clip path, a gradient. --bench 1 records,
  // plans and replays the same document.
  std::string body =
      "<defs><clipPath id='c'><circle cx='100' cy='100' r='80'/></clipPath>"
      "<linearGradient id='g'><stop offset='0' stop-color='red'/><stop offset='1' stop-color='blue'/></linearGradient>"
      "<rect id='dot' width='3' height='2' fill='url(#g)' stroke='black' stroke-width='0.3'/></defs>"
      "<g opacity='0.6' clip-path='url(#c)'>";
  std::ostringstream shapes;
  for (int i = 0; i < 51000; ++i) {
    const int x = (i * 37) % 197, y = (i * 53) % 193;
    if (i % 3 == 0) {
      shapes << "<use href='#dot' x='" << x << "' y='" << y << "'/>";
    } else {
      shapes << "<rect x='" << x << ".5' y='" << y << "' width='2' height='3' fill='#" << 100 + i % 800
             << "' fill-opacity='0.5'/>";
    }
  }
  body += shapes.str();
  body += "</g>";
  const std::string svg = write_file("many_shapes.svg",
                                     "<svg xmlns='http://www.w3.org/2000/svg' width='200' height='200'>" + body + "</svg>");
  const Image direct = run_to_png("render '" + svg + "'", work_dir() + "/many_direct.png");
  const Image recorded = run_to_png("render '" + svg + "' --bench 1", work_dir() + "/many_recorded.png");
  ASSERT_EQ(direct.width, 200);
  ASSERT_EQ(recorded.width, 200);
  int max_diff = 0, painted = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) {
      for (int c = 0; c < 4; ++c) max_diff = std::max(max_diff, std::abs(direct.pixel(x, y)[c] - recorded.pixel(x, y)[c]));
      painted += direct.pixel(x, y)[3] > 0;
    }
  }
  EXPECT_LE(max_diff, 2);  // a folded layer rounds once less (SvgPlan.PlannedNaiveAndDirectRendersAgree)
  EXPECT_GT(painted, 15000);  // the clipped disc of r = 80 is covered
}
