// Inputs the fuzz targets (tests/fuzz/) found to crash or to trip a sanitizer, each kept as a named test once
// fixed. Under the sanitizer build (scripts/sanitize.sh) they also check that the undefined behaviour is gone.
#include <gtest/gtest.h>

#include <string>

#include "svg_subset/svg.hpp"
#include "vraster/error.hpp"
#include "vraster/image.hpp"

using namespace vraster;

// fuzz_svg: a root width of 3.9e50 px reached check_image_size's message, which cast the size to long long
// (undefined for values beyond its range; UBSan: "outside the range of representable values").
TEST(FuzzRegression, HugeFiniteImageSizeIsReportedWithoutOverflow) {
  try {
    check_image_size(3.88888888888e50, 32);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3.89e+50x32 is too large"), std::string::npos) << e.what();
  }
  try {
    svg::parse_svg(R"(<svg xmlns="http://www.w3.org/2000/svg" width="388888888888888888888888888888888888888888888888882" height="32"><rect width="1" height="1"/></svg>)",
                   "huge.svg");
    FAIL() << "no error for a 3.9e50 px wide document";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("huge.svg"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_image_size(1e300, 1e300), Error);
  EXPECT_NO_THROW(check_image_size(kMaxImageSide, 1));
}
