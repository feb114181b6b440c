// Seed fill: hand-made regions (the seeds' 4- and 8-connected examples), a plain BFS reference on random images,
// tolerance, 16-bit images, and a 4096 x 4096 spiral maze (no recursion, so no stack overflow).
#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <string>
#include <vector>

#include "vraster/error.hpp"
#include "vraster/seed_fill.hpp"

namespace vraster {
namespace {

const Color kWhite{1, 1, 1, 1}, kBlack{0, 0, 0, 1}, kRed{1, 0, 0, 1};

// A picture from rows of characters: '#' black, '.' white, 'r' red.
Image picture(const std::vector<std::string>& rows) {
  Image img(static_cast<int>(rows[0].size()), static_cast<int>(rows.size()));
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const char c = rows[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)];
      premultiply_to(c == '#' ? kBlack : c == 'r' ? kRed : kWhite, img.pixel(x, y));
    }
  }
  return img;
}

// The image back as characters ('r' for red, '#' black, '.' white, '?' anything else).
std::vector<std::string> characters(const Image& img) {
  std::vector<std::string> rows;
  for (int y = 0; y < img.height; ++y) {
    std::string row;
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.pixel(x, y);
      row += p[0] == 255 && p[1] == 0 ? 'r' : p[0] == 0 && p[1] == 0 ? '#' : p[0] == 255 && p[1] == 255 ? '.' : '?';
    }
    rows.push_back(row);
  }
  return rows;
}

// Interior-defined, as the seeds' Flood_Fill_4 example: white pixels linked only diagonally are a separate 4-connected
// region but the same 8-connected one.
TEST(SeedFill, InteriorFourConnectedStopsAtDiagonals) {
  Image img = picture({"..#####",
                       "..#####",
                       "##.####",
                       "###..##",
                       "###..##"});
  EXPECT_EQ(flood_fill(img, 0, 0, kRed), 4);
  EXPECT_EQ(characters(img), (std::vector<std::string>{"rr#####", "rr#####", "##.####", "###..##", "###..##"}));
}

TEST(SeedFill, InteriorEightConnectedFollowsDiagonals) {
  Image img = picture({"..#####",
                       "..#####",
                       "##.####",
                       "###..##",
                       "###..##"});
  SeedFillOptions o;
  o.connectivity = Connectivity::Eight;
  EXPECT_EQ(flood_fill(img, 0, 0, kRed, o), 9);
  EXPECT_EQ(characters(img), (std::vector<std::string>{"rr#####", "rr#####", "##r####", "###rr##", "###rr##"}));
}

// Boundary-defined, as the seeds' Fill_Boundary_4_Connected: everything inside the black outline is filled, whatever
// its colour (here an inner red pixel and white ones), and the outline keeps the fill in.
TEST(SeedFill, BoundaryDefinedFillsUpToTheOutline) {
  Image img = picture({".......",
                       ".#####.",
                       ".#...#.",
                       ".#.r.#.",
                       ".#...#.",
                       ".#####.",
                       "......."});
  SeedFillOptions o;
  o.region = SeedRegion::Boundary;
  o.boundary = kBlack;
  const Color green{0, 1, 0, 1};
  EXPECT_EQ(flood_fill(img, 3, 2, green, o), 9);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 7; ++x) {
      const bool inner = x >= 2 && x <= 4 && y >= 2 && y <= 4;
      EXPECT_EQ(img.pixel(x, y)[1] == 255 && img.pixel(x, y)[0] == 0, inner) << x << "," << y;
    }
  }
}

// An outline that is only 8-connected (a diagonal step) lets an 8-connected boundary fill leak out; a 4-connected
// fill stays in. (A region's boundary must be 4-connected for 8-connected filling, as the seeds explain.)
TEST(SeedFill, EightConnectedBoundaryFillLeaksThroughDiagonalGaps) {
  const std::vector<std::string> rows = {"......",
                                         ".###..",
                                         ".#..#.",
                                         ".#..#.",
                                         ".####.",
                                         "......"};
  SeedFillOptions o;
  o.region = SeedRegion::Boundary;
  Image four = picture(rows);
  EXPECT_EQ(flood_fill(four, 2, 2, kRed, o), 4);
  o.connectivity = Connectivity::Eight;
  Image eight = picture(rows);
  EXPECT_GT(flood_fill(eight, 2, 2, kRed, o), 4);
  EXPECT_EQ(characters(eight)[0], "rrrrrr");
}

TEST(SeedFill, ToleranceJoinsNearbyColours) {
  Image img(4, 1);
  const int levels[4] = {100, 104, 110, 101};
  for (int x = 0; x < 4; ++x) {
    std::uint8_t* p = img.pixel(x, 0);
    p[0] = p[1] = p[2] = static_cast<std::uint8_t>(levels[x]);
    p[3] = 255;
  }
  SeedFillOptions o;
  o.tolerance = 5.0 / 255;  // 100 and 104 join, 110 does not (and blocks 101 beyond it)
  EXPECT_EQ(seed_fill_region(img, 0, 0, o).pixel_count, 2);
  o.tolerance = 10.0 / 255;
  EXPECT_EQ(seed_fill_region(img, 0, 0, o).pixel_count, 4);
  o.tolerance = 0;
  EXPECT_EQ(seed_fill_region(img, 0, 0, o).pixel_count, 1);
}

TEST(SeedFill, FillColourInsideTheRegionEnds) {
  Image img = picture({"....", "...."});
  // Replacing white by white: every pixel is still in the region after it is written; marking ends the fill.
  EXPECT_EQ(flood_fill(img, 1, 1, kWhite), 8);
}

TEST(SeedFill, SeedOutsideOrOnTheBoundaryFillsNothing) {
  Image img = picture({".#.", ".#."});
  EXPECT_EQ(flood_fill(img, -1, 0, kRed), 0);
  EXPECT_EQ(flood_fill(img, 3, 0, kRed), 0);
  EXPECT_EQ(flood_fill(img, 0, 2, kRed), 0);
  SeedFillOptions o;
  o.region = SeedRegion::Boundary;
  EXPECT_EQ(flood_fill(img, 1, 0, kRed, o), 0);
  EXPECT_EQ(characters(img), (std::vector<std::string>{".#.", ".#."}));
}

TEST(SeedFill, BadToleranceIsAnError) {
  Image img(2, 2);
  SeedFillOptions o;
  o.tolerance = std::nan("");
  EXPECT_THROW(flood_fill(img, 0, 0, kRed, o), Error);
  o.tolerance = -0.1;
  EXPECT_THROW(flood_fill(img, 0, 0, kRed, o), Error);
}

// The obviously correct reference: breadth-first search over single pixels with the same region test.
template <class T>
std::vector<std::uint8_t> bfs_region(const BasicImage<T>& img, int sx, int sy, const SeedFillOptions& o) {
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(img.width) * img.height, 0);
  T ref[4];
  if (o.region == SeedRegion::Interior) {
    std::copy(img.pixel(sx, sy), img.pixel(sx, sy) + 4, ref);
  } else {
    premultiply_to(o.boundary, ref);
  }
  const int tol = static_cast<int>(std::floor(o.tolerance * BasicImage<T>::kMax + 1e-9));
  auto in = [&](int x, int y) {
    bool close = true;
    for (int c = 0; c < 4; ++c) close = close && std::abs(int(img.pixel(x, y)[c]) - int(ref[c])) <= tol;
    return o.region == SeedRegion::Interior ? close : !close;
  };
  if (!in(sx, sy)) return mask;
  std::deque<std::pair<int, int>> queue{{sx, sy}};
  mask[static_cast<std::size_t>(sy) * img.width + sx] = 1;
  while (!queue.empty()) {
    const auto [x, y] = queue.front();
    queue.pop_front();
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || (o.connectivity == Connectivity::Four && dx != 0 && dy != 0)) continue;
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= img.width || ny >= img.height) continue;
        std::uint8_t& m = mask[static_cast<std::size_t>(ny) * img.width + nx];
        if (m || !in(nx, ny)) continue;
        m = 1;
        queue.emplace_back(nx, ny);
      }
    }
  }
  return mask;
}

TEST(SeedFill, MatchesBreadthFirstSearchOnRandomImages) {
  std::mt19937 rng(16);
  for (int trial = 0; trial < 300; ++trial) {
    const int w = 1 + static_cast<int>(rng() % 40), h = 1 + static_cast<int>(rng() % 40);
    Image img(w, h);
    const int density = static_cast<int>(rng() % 70);  // share of "wall" pixels, in percent
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const bool wall = static_cast<int>(rng() % 100) < density;
        const int level = wall ? static_cast<int>(rng() % 3) : 200 + static_cast<int>(rng() % 8);
        std::uint8_t* p = img.pixel(x, y);
        p[0] = p[1] = p[2] = static_cast<std::uint8_t>(level);
        p[3] = 255;
      }
    }
    SeedFillOptions o;
    o.connectivity = trial % 2 ? Connectivity::Eight : Connectivity::Four;
    o.region = trial % 3 == 0 ? SeedRegion::Boundary : SeedRegion::Interior;
    o.tolerance = (trial % 5) * 2.0 / 255;
    o.boundary = kBlack;
    const int sx = static_cast<int>(rng() % w), sy = static_cast<int>(rng() % h);
    const SeedFillRegion region = seed_fill_region(img, sx, sy, o);
    const std::vector<std::uint8_t> expected = bfs_region(img, sx, sy, o);
    ASSERT_EQ(region.mask, expected) << "trial " << trial;
    std::int64_t count = 0;
    for (auto m : expected) count += m;
    EXPECT_EQ(region.pixel_count, count);
  }
}

TEST(SeedFill, SixteenBitImages) {
  Image16 img(3, 3);
  img.clear(kWhite);
  img.pixel(1, 1)[0] = 65534;  // one level off in 16 bits: a different colour without tolerance
  EXPECT_EQ(flood_fill(img, 0, 0, kRed), 8);
  EXPECT_EQ(img.pixel(2, 2)[1], 0);
  EXPECT_EQ(img.pixel(1, 1)[1], 65535);
  SeedFillOptions o;
  o.tolerance = 2.0 / 65535;
  Image16 again(3, 3);
  again.clear(kWhite);
  again.pixel(1, 1)[0] = 65534;
  EXPECT_EQ(flood_fill(again, 0, 0, kRed, o), 9);
}

// A square spiral corridor one pixel wide through a 4096 x 4096 wall: about 8 million pixels along one path.
// A recursive fill would need millions of nested calls; the span fill with its heap stack must reach the centre.
TEST(SeedFill, SpiralMaze4096DoesNotOverflowTheStack) {
  const int n = 4096;
  Image img(n, n);
  img.clear(kBlack);
  std::int64_t carved = 0;
  int x = 1, y = 1, dx = 1, dy = 0, length = n - 3, legs = 0;
  auto carve = [&](int px, int py) {
    std::uint8_t* p = img.pixel(px, py);
    if (p[0] == 0) ++carved;
    p[0] = p[1] = p[2] = 255;
  };
  carve(x, y);
  while (length > 0) {
    for (int i = 0; i < length; ++i) carve(x += dx, y += dy);
    const int t = dx;  // turn right (clockwise on screen)
    dx = -dy, dy = t;
    if (++legs >= 3 && legs % 2 == 1) length -= 2;
  }
  for (const Connectivity c : {Connectivity::Four, Connectivity::Eight}) {
    SeedFillOptions o;
    o.connectivity = c;
    const SeedFillRegion region = seed_fill_region(img, 1, 1, o);
    EXPECT_EQ(region.pixel_count, carved);
    EXPECT_TRUE(region.contains(x, y)) << "the corridor's far end " << x << "," << y;
  }
  EXPECT_GT(carved, std::int64_t{n} * n / 3);
}

}  // namespace
}  // namespace vraster
