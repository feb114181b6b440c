// <image> in the resolved tree (svg_subset/README.md): placement under preserveAspectRatio, data: URLs of every
// format, the folder rule for files, SVG documents as images, and hostile input. Checked without pixels.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <functional>
#include <string>

#include "support/encode_images.hpp"
#include "svg_subset/svg.hpp"
#include "svg_subset/tree.hpp"

namespace vraster::svg {
namespace {

namespace fs = std::filesystem;
using test::Bytes;

Tree tree(const std::string& body, const ParseOptions& options = {}) {
  return parse_svg_tree("<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
                        "width=\"100\" height=\"100\">" + body + "</svg>", "test.svg", options);
}

/// The ImageNode of the first element (a group holding it), or a failure.
const ImageNode& image_of(const Tree& t) {
  static const ImageNode none;
  if (t.root.children.empty()) {
    ADD_FAILURE() << "no node in the tree";
    return none;
  }
  const Group* g = std::get_if<Group>(&t.root.children[0].value);
  if (!g || g->children.empty() || !std::get_if<ImageNode>(&g->children[0].value)) {
    ADD_FAILURE() << "the first node is not a group holding an image";
    return none;
  }
  return std::get<ImageNode>(g->children[0].value);
}

void expect_rect(const Rect& r, double x0, double y0, double x1, double y1) {
  EXPECT_NEAR(r.x0, x0, 1e-9);
  EXPECT_NEAR(r.y0, y0, 1e-9);
  EXPECT_NEAR(r.x1, x1, 1e-9);
  EXPECT_NEAR(r.y1, y1, 1e-9);
}

bool has_warning(const Tree& t, const std::string& part) {
  for (const std::string& w : t.warnings) {
    if (w.find(part) != std::string::npos) return true;
  }
  return false;
}

/// A 2 x 1 PNG: an opaque red pixel, then a half-transparent green one.
Bytes two_pixel_png() {
  Image image(2, 1);
  image.clear(Color::rgb8(255, 0, 0));
  std::uint8_t* p = image.pixel(1, 0);
  p[0] = 0, p[1] = 128, p[2] = 0, p[3] = 128;
  return test::png_bytes(image);
}

std::string image_element(const std::string& href, const std::string& aspect = "",
                          const std::string& size = "width='100' height='100'") {
  return "<image x='0' y='0' " + size + " " + (aspect.empty() ? "" : "preserveAspectRatio='" + aspect + "' ") +
         "xlink:href='" + href + "'/>";
}

TEST(SvgImage, DataUrlPngDecodedToItsPixels) {
  const Tree t = tree(image_element(test::data_url("image/png", two_pixel_png())));
  const ImageNode& im = image_of(t);
  ASSERT_TRUE(im.image);
  ASSERT_EQ(im.image->width, 2);
  ASSERT_EQ(im.image->height, 1);
  const std::uint8_t* red = im.image->pixel(0, 0);
  const std::uint8_t* green = im.image->pixel(1, 0);
  EXPECT_EQ(red[0], 255);
  EXPECT_EQ(red[3], 255);
  EXPECT_EQ(green[0], 0);
  EXPECT_NEAR(green[1], 128, 1);  // premultiplied: 128 of 128
  EXPECT_EQ(green[3], 128);
  EXPECT_TRUE(im.smooth);
  EXPECT_EQ(im.href.substr(0, 5), "data:");
  EXPECT_LT(im.href.size(), 40u);  // the tree keeps the head of a data: URL only
  for (const std::string& w : t.warnings) ADD_FAILURE() << "unexpected warning " << w;
}

TEST(SvgImage, DestinationForEveryAlignMeetSliceAndNone) {
  const std::string url = test::data_url("image/png", two_pixel_png());  // 2:1
  struct Case {
    const char* aspect;
    double x0, y0, x1, y1;
  } cases[] = {
      {"", 0, 25, 100, 75},  // xMidYMid meet
      {"xMinYMin meet", 0, 0, 100, 50},
      {"xMaxYMax meet", 0, 50, 100, 100},
      {"xMidYMid slice", -50, 0, 150, 100},
      {"xMinYMin slice", 0, 0, 200, 100},
      {"xMaxYMax slice", -100, 0, 100, 100},
      {"none", 0, 0, 100, 100},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.aspect);
    const Tree t = tree(image_element(url, c.aspect));
    const ImageNode& im = image_of(t);
    expect_rect(im.dest, c.x0, c.y0, c.x1, c.y1);
    expect_rect(im.view, 0, 0, 100, 100);
    expect_rect(im.clip, 0, 0, 100, 100);
  }
}

TEST(SvgImage, AutoSizesTakeTheIntrinsicSizeOrItsAspectRatio) {
  const std::string url = test::data_url("image/png", two_pixel_png());
  expect_rect(image_of(tree(image_element(url, "", ""))).view, 0, 0, 2, 1);
  expect_rect(image_of(tree(image_element(url, "", "width='auto' height='auto'"))).view, 0, 0, 2, 1);
  expect_rect(image_of(tree(image_element(url, "", "width='50'"))).view, 0, 0, 50, 25);
  expect_rect(image_of(tree(image_element(url, "", "height='50'"))).view, 0, 0, 100, 50);
  EXPECT_TRUE(tree(image_element(url, "", "width='0' height='10'")).root.children.empty());
}

TEST(SvgImage, JpegGifAndWebpDataUrls) {
  const GifColorType palette[4] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}, {0, 0, 0}};
  struct Case {
    std::string url;
    int r, g, b;
  } cases[] = {
      {test::data_url("image/jpeg", test::jpeg_bytes(4, 4, 250, 10, 10)), 250, 10, 10},
      {"data:;base64," + test::base64(test::jpeg_bytes(4, 4, 10, 250, 10)), 10, 250, 10},  // no MIME type
      {test::data_url("image/gif", test::gif_bytes(1, 1, {2}, palette, -1)), 255, 0, 0},
      {test::data_url("image/png", test::webp_bytes(1, 1, {0, 0, 255, 255})), 0, 0, 255},  // a wrong MIME type
  };
  for (const Case& c : cases) {
    const Tree t = tree(image_element(c.url));
    const ImageNode& im = image_of(t);
    ASSERT_TRUE(im.image);
    const std::uint8_t* p = im.image->pixel(0, 0);
    EXPECT_NEAR(p[0], c.r, 4);
    EXPECT_NEAR(p[1], c.g, 4);
    EXPECT_NEAR(p[2], c.b, 4);
    EXPECT_EQ(p[3], 255);
  }
}

TEST(SvgImage, PercentEncodedDataUrlAndImageRendering) {
  const Tree t = tree("<g image-rendering='pixelated'>" +
                      image_element("data:image/svg+xml,%3Csvg xmlns=%22http://www.w3.org/2000/svg%22 width=%2210%22 "
                                    "height=%2210%22%3E%3Crect width=%2210%22 height=%2210%22/%3E%3C/svg%3E") +
                      image_element(test::data_url("image/png", two_pixel_png())) + "</g>");
  const Group& g = std::get<Group>(t.root.children.at(0).value);
  ASSERT_EQ(g.children.size(), 2u);
  ASSERT_TRUE(std::get_if<Group>(&g.children[0].value));  // the SVG image: a group
  const Group& element = std::get<Group>(g.children[1].value);
  EXPECT_FALSE(std::get<ImageNode>(element.children.at(0).value).smooth);
  EXPECT_TRUE(image_of(tree("<g image-rendering='optimizeQuality'/>" +
                            image_element(test::data_url("image/png", two_pixel_png())))).smooth);
}

TEST(SvgImage, CorruptDataWarnsAndGivesANullImage) {
  Bytes png = two_pixel_png();
  png.resize(png.size() - 20);  // the image data cut short
  for (const std::string& url : {test::data_url("image/png", png), std::string("data:image/png;base64,@@@@"),
                                 std::string("data:image/png;base64,iVBORw0KGgo="), std::string("data:text/plain,hello")}) {
    SCOPED_TRACE(url);
    const Tree t = tree(image_element(url));
    EXPECT_FALSE(image_of(t).image);
    EXPECT_TRUE(has_warning(t, "not drawn")) << (t.warnings.empty() ? "no warning" : t.warnings[0]);
  }
}

TEST(SvgImage, HugeDeclaredImageSizeIsRefused) {
  Image one(1, 1);
  one.clear(Color::rgb8(1, 2, 3));
  const Tree t = tree(image_element(test::data_url("image/png", test::png_with_size(test::png_bytes(one), 30000, 30000))));
  EXPECT_FALSE(image_of(t).image);
  EXPECT_TRUE(has_warning(t, "not drawn"));
}

TEST(SvgImage, SvgImageBecomesAPlacedClippedGroup) {
  const std::string inner =
      "<svg xmlns='http://www.w3.org/2000/svg' width='20' height='10'><rect width='20' height='10'/></svg>";
  const Tree t = tree("<image x='0' y='0' width='100' height='100' href='" +
                      test::data_url("image/svg+xml", Bytes(inner.begin(), inner.end())) + "'/>");
  const Group& element = std::get<Group>(t.root.children.at(0).value);
  const Group& clipped = std::get<Group>(element.children.at(0).value);
  ASSERT_TRUE(clipped.clip);  // to the viewport and the document's own canvas: (0, 25) - (100, 75)
  const Path& clip_rect = std::get<PathNode>(clipped.clip->content->children.at(0).value).path;
  expect_rect(clip_rect.bounds(), 0, 25, 100, 75);
  const Group& content = std::get<Group>(clipped.children.at(0).value);
  EXPECT_NEAR(content.transform.a, 5, 1e-9);  // 20 x 10 meets 100 x 100: scale 5, centred
  EXPECT_NEAR(content.transform.d, 5, 1e-9);
  EXPECT_NEAR(content.transform.e, 0, 1e-9);
  EXPECT_NEAR(content.transform.f, 25, 1e-9);
  ASSERT_EQ(content.children.size(), 1u);
  EXPECT_TRUE(std::get_if<PathNode>(&content.children[0].value));
}

TEST(SvgImage, NestedSvgImagesStopAtTheDepthLimit) {
  // Each level is an SVG whose only content is an image of the level inside it: 8 levels, far beyond 4.
  std::string doc = "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><rect width='10' height='10'/></svg>";
  for (int level = 0; level < 8; ++level) {
    doc = "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><image width='10' height='10' href='" +
          test::data_url("image/svg+xml", Bytes(doc.begin(), doc.end())) + "'/></svg>";
  }
  const Tree t = parse_svg_tree(doc);
  EXPECT_TRUE(has_warning(t, "nested more than 4 levels")) << (t.warnings.empty() ? "no warning" : t.warnings[0]);
  // No rectangle anywhere: the innermost documents were refused.
  std::function<int(const Group&)> paths = [&](const Group& g) {
    int n = 0;
    for (const Node& c : g.children) {
      if (const Group* sub = std::get_if<Group>(&c.value)) n += paths(*sub);
      if (std::get_if<PathNode>(&c.value)) ++n;
    }
    return n;
  };
  EXPECT_EQ(paths(t.root), 0);
}

// Files: a fresh folder per test with a document folder inside it.
class SvgImageFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() / ("vraster_svgimg_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "doc" / "sub");
    test::write_bytes((root_ / "outside.png").string(), two_pixel_png());
    test::write_bytes((root_ / "doc" / "sub" / "inside.png").string(), two_pixel_png());
    options_.base_dir = (root_ / "doc").string();
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
  ParseOptions options_;
};

TEST_F(SvgImageFiles, RelativeFilesInsideTheFolderAreRead) {
  EXPECT_TRUE(image_of(tree(image_element("sub/inside.png"), options_)).image);
  EXPECT_TRUE(image_of(tree(image_element("sub/../sub/inside.png"), options_)).image);
  EXPECT_TRUE(image_of(tree(image_element("sub/inside%2Epng"), options_)).image);  // percent-encoded
  // Without a folder (a document held in memory), no file is read.
  const Tree t = tree(image_element("sub/inside.png"));
  EXPECT_FALSE(image_of(t).image);
  EXPECT_TRUE(has_warning(t, "external files are not read"));
}

TEST_F(SvgImageFiles, PathsLeavingTheFolderAreRefused) {
  fs::create_symlink(root_ / "outside.png", root_ / "doc" / "link.png");
  for (const std::string& href : {std::string("../outside.png"), std::string("sub/../../outside.png"), (root_ / "outside.png").string(),
                                 std::string("file://") + (root_ / "outside.png").string(), std::string("link.png"),
                                 std::string("http://example.invalid/a.png")}) {
    SCOPED_TRACE(href);
    const Tree t = tree(image_element(href), options_);
    EXPECT_FALSE(image_of(t).image);
    EXPECT_EQ(t.warnings.size(), 1u);
  }
  EXPECT_TRUE(has_warning(tree(image_element("../outside.png"), options_), "outside the document's folder"));
  // Inside, but not a regular file: a folder, a FIFO (reading it would block), a missing file.
  ASSERT_EQ(::mkfifo((root_ / "doc" / "fifo.png").c_str(), 0600), 0);
  for (const char* href : {"sub", "fifo.png", "missing.png"}) {
    const Tree t = tree(image_element(href), options_);
    EXPECT_FALSE(image_of(t).image);
    EXPECT_TRUE(has_warning(t, "not a regular file")) << href;
  }
  // A wider allowed folder lets it in.
  ParseOptions wider = options_;
  wider.allowed_dir = root_.string();
  EXPECT_TRUE(image_of(tree(image_element("../outside.png"), wider)).image);
}

TEST_F(SvgImageFiles, AnSvgImageReadsNoFilesItselfSoSelfReferenceEnds) {
  const std::string self = "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'>"
                           "<image width='10' height='10' href='self.svg'/><rect width='1' height='1'/></svg>";
  test::write_bytes((root_ / "doc" / "self.svg").string(), Bytes(self.begin(), self.end()));
  const Document doc = load_svg((root_ / "doc" / "self.svg").string());
  EXPECT_EQ(doc.items.size(), 2u);  // its own rect, and the rect of the one copy of itself it shows
  bool refused = false;
  for (const std::string& w : doc.warnings) refused |= w.find("external files are not read") != std::string::npos;
  EXPECT_TRUE(refused);
}

}  // namespace
}  // namespace vraster::svg
