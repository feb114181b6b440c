// `vraster text` through the test driver: output, exit status 2 with a message, no partial file.
#include <gtest/gtest.h>

#include <filesystem>

#include "text_support.hpp"
#include "vraster/png.hpp"

using namespace vraster;
using namespace vraster::text::testing;

namespace {

std::string driver() { return std::string(VRASTER_TEXT_TEST_OUT) + "/../vraster_text_cli_driver"; }

int run(const std::string& args, std::string& output) {
  int status = 0;
  output = run_command(driver() + " text " + args + " 2>&1", status);
  return status;
}

}  // namespace

TEST(TextCli, RendersAPngSizedToTheText) {
  const std::string out = out_dir() + "/cli_ok.png";
  std::filesystem::remove(out);
  std::string log;
  ASSERT_EQ(run("'Hello, world' --size 32 --color '#336699' -o " + out, log), 0) << log;
  const Image img = read_png(out);
  EXPECT_GT(img.width, 150);
  EXPECT_LT(img.height, 80);
  const InkStats s = ink_stats(ink_of(img, false), img.width, img.height);
  EXPECT_GT(s.total, 100);
  EXPECT_GE(s.x0, 6);  // the margin is kept (8 px, antialiasing may reach one pixel further)
  EXPECT_LE(s.x1, img.width - 7);
}

TEST(TextCli, WrapsAlignsAndUsesFallbackFonts) {
  const std::string out = out_dir() + "/cli_wrap.png";
  std::string log;
  ASSERT_EQ(run("'Wrapped text in a narrow box, centred' --width 120 --align center --features liga=0,kern --lang en "
                "--font '" + system_font(kNotoSerif) + "' --aa none -o " + out, log),
            0)
      << log;
  const Image img = read_png(out);
  EXPECT_GT(img.height, 60);  // more than one line
}

TEST(TextCli, BadInputGivesStatus2AMessageAndNoFile) {
  const std::string out = out_dir() + "/cli_bad.png";
  const std::string missing = out_dir() + "/missing-font.ttf";
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {"'x' --font " + missing + " -o " + out, missing},
      {"'x' --size 0 -o " + out, "font size"},
      {"'x' --size 1e6 -o " + out, "too large"},
      {"'x' --size abc -o " + out, "not a number"},
      {"'x' --align middle -o " + out, "--align"},
      {"'x' --color nocolour -o " + out, "not a colour"},
      {"'x' --features '+' -o " + out, "feature"},
      {"'x' --bogus -o " + out, "unknown option"},
      {"-o " + out, "no text"},
      {"'x'", "no output"},
  };
  for (const Case& c : cases) {
    std::filesystem::remove(out);
    std::string log;
    EXPECT_EQ(run(c.args, log), 2) << c.args;
    EXPECT_EQ(log.rfind("vraster: ", 0), 0u) << log;
    EXPECT_NE(log.find(c.needle), std::string::npos) << c.args << " -> " << log;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
  }
}

TEST(TextCli, InvalidUtf8StillRenders) {
  const std::string out = out_dir() + "/cli_utf8.png";
  std::string log;
  EXPECT_EQ(run("\"$(printf 'ok\\377\\376!')\" -o " + out, log), 0) << log;  // bytes FF FE: never UTF-8
  EXPECT_GT(read_png(out).width, 40);
}
