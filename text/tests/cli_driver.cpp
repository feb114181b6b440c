// Test driver for `vraster text` (the real CLI calls run_text_command from src/cli/main.cpp the same way).
#include <string_view>

#include "vraster_text/cli.hpp"

int main(int argc, char** argv) {
  if (argc >= 2 && std::string_view(argv[1]) == "text") return vraster::text::run_text_command(argc, argv);
  return 2;
}
