// The hostile-input suite (issue 12): runs the vraster command on generated hostile inputs, each in a child
// process with an address-space cap, and checks per input: exit status 0 or 2, no signal, wall time and peak
// memory (getrusage's maximum resident set) under the caps below, and no file left in the output folder
// except the requested output after status 0.
//
//   hostile_suite VRASTER_BINARY SCRATCH_DIR
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr double kMaxSeconds = 20;                       // per input
constexpr long kMaxResidentKb = 1024 * 1024;             // 1 GiB peak resident memory per input
constexpr rlim_t kAddressSpace = rlim_t{3} << 30;        // 3 GiB: a runaway allocation fails instead of swapping

struct Case {
  std::string name;
  std::vector<std::string> args;  // after the binary; "OUT" is replaced by the output path
  std::string svg;                // written to IN.svg when not empty ("IN" in args)
};

std::string svg(const std::string& size, const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" " + size + ">" + body + "</svg>";
}

std::vector<Case> cases() {
  std::vector<Case> out;
  const std::string s10 = "width=\"10\" height=\"10\"", s200 = "width=\"200\" height=\"200\"";
  out.push_back({"dasharray 1e308 offset -1", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<path d=\"M0 5 L10 5\" stroke=\"red\" stroke-dasharray=\"1e308\" stroke-dashoffset=\"-1\"/>")});
  out.push_back({"stroke-width 100 dasharray 0.0000477", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<path d=\"M0 5 L10 5\" stroke=\"red\" stroke-width=\"100\" "
                          "stroke-dasharray=\"0.0000477 0.0000477\" stroke-linecap=\"round\"/>")});
  out.push_back({"circle r 1e155 stroke-width 1e300", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<circle r=\"1e155\" stroke=\"red\" stroke-width=\"1e300\"/>")});
  out.push_back({"huge circle, moderate stroke", {"render", "IN", "-o", "OUT"},
                 svg(s200, "<circle cx=\"1e7\" r=\"1e7\" fill=\"none\" stroke=\"red\" stroke-width=\"20\" "
                           "stroke-linejoin=\"round\"/>")});
  {
    std::string style;
    for (int i = 0; i < 300000; ++i) style += "fill:red;";
    out.push_back({"style with 300000 declarations", {"render", "IN", "-o", "OUT"},
                   svg(s10, "<rect width=\"5\" height=\"5\" style=\"" + style + "\"/>")});
  }
  {
    std::string d = "M5 5";
    unsigned state = 7;
    auto next = [&] { return (state = state * 1103515245u + 12345u) >> 16 & 255; };
    for (int i = 0; i < 100000; ++i) {
      d += " C" + std::to_string(next() % 200) + " " + std::to_string(next() % 200) + " " +
           std::to_string(next() % 200) + " " + std::to_string(next() % 200) + " " + std::to_string(next() % 200) +
           " " + std::to_string(next() % 200);
    }
    out.push_back({"100000 cubics at tolerance 0.0001", {"render", "IN", "-o", "OUT", "--tolerance", "0.0001"},
                   svg(s200, "<path d=\"" + d + "\"/>")});
  }
  for (const int n : {100000, 30000}) {
    std::string points;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i * (n / 2 - 1) / n;
      points += std::to_string(100 + 99 * std::cos(a)) + "," + std::to_string(100 + 99 * std::sin(a)) + " ";
    }
    if (n == 100000)
      out.push_back({"aa exact on a 100000-segment star", {"render", "IN", "-o", "OUT", "--aa", "exact"},
                     svg(s200, "<polygon points=\"" + points + "\"/>")});
    else
      out.push_back({"fill-rules on a 30000-segment star", {"fill-rules", "IN", "-o", "OUT", "--panel", "200"},
                     svg(s200, "<polygon points=\"" + points + "\"/>")});
  }
  {
    std::string body;
    for (int i = 0; i < 300000; ++i) body += "<foo/>";
    out.push_back({"300000 ignored elements", {"render", "IN", "-o", "OUT"}, svg(s10, body)});
  }
  {
    // Just under the element limit, each shape filled and stroked (two draw calls): a recording of every call
    // ran out of the address space below; drawn straight onto the image it fits in about a third of it.
    std::string body = "<style>rect { fill: red; stroke: blue }</style>";
    body.reserve(44'000'000);
    for (int i = 0; i < 999000; ++i) {
      body += "<rect x=\"" + std::to_string(i % 997) + "\" y=\"" + std::to_string(i % 991) +
              "\" width=\"3\" height=\"3\"/>";
    }
    out.push_back({"999000 filled and stroked rects", {"render", "IN", "-o", "OUT"},
                   svg("width=\"1000\" height=\"1000\"", body)});
  }
  out.push_back({"largest image (8192 x 8192) 8 bits", {"render", "IN", "-o", "OUT"},
                 svg("width=\"8192\" height=\"8192\"", "<rect width=\"100\" height=\"100\"/>")});
  out.push_back({"largest image (8192 x 8192) 16 bits", {"render", "IN", "-o", "OUT", "--depth", "16"},
                 svg("width=\"8192\" height=\"8192\"", "<rect width=\"100\" height=\"100\"/>")});
  out.push_back({"render /dev/zero", {"render", "/dev/zero", "-o", "OUT"}, ""});
  out.push_back({"text with --font /dev/zero", {"text", "x", "--font", "/dev/zero", "-o", "OUT"}, ""});
  out.push_back({"two root elements", {"render", "IN", "-o", "OUT"}, svg(s10, "") + "<svg/>"});
  out.push_back({"undefined entity", {"render", "IN", "-o", "OUT"}, svg(s10, "<g id=\"&x;\"/>")});
  {
    // A billion laughs of DOCTYPE entities (ten levels of ten references): stops at the expansion limit.
    std::string dtd = "<!DOCTYPE svg [<!ENTITY a \"lol\">";
    for (char c = 'b'; c <= 'k'; ++c) {
      dtd += std::string("<!ENTITY ") + c + " \"";
      for (int i = 0; i < 10; ++i) dtd += std::string("&") + char(c - 1) + ";";
      dtd += "\">";
    }
    out.push_back({"billion laughs of entities", {"render", "IN", "-o", "OUT"},
                   dtd + "]>" + svg(s10, "<desc>&k;</desc><g id=\"&k;\"/>")});
  }
  out.push_back({"escape sequences in values", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<rect fill=\"\x1b]0;x\x07\x1b[2J\" width=\"1\" height=\"1\"/>")});
  out.push_back({"100 KB number", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<path d=\"M1" + std::string(100000, '0') + " 0 L1 1\"/>")});
  out.push_back({"transform out of range", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<g transform=\"scale(1e300)\"><rect x=\"1e10\" width=\"1\" height=\"1\"/></g>")});
  out.push_back({"hairline endpoints beyond 1e19", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<path d=\"M-1e20 -1e20 L1e20 1e20\" stroke=\"red\" stroke-width=\"0.5\"/>")});
  out.push_back({"arc radius 1e18", {"render", "IN", "-o", "OUT"},
                 svg(s10, "<path d=\"M1 5 A1e18 1e18 0 1 1 9 5\" stroke=\"red\" fill=\"none\"/>")});
  {
    std::string body;
    for (int i = 0; i < 5000; ++i) body += "<g>";
    for (int i = 0; i < 5000; ++i) body += "</g>";
    out.push_back({"deep nesting", {"render", "IN", "-o", "OUT"}, svg(s10, body)});
  }
  {
    // Masks in masks, clips in clips, patterns in patterns, 40 deep, on a 4096 x 4096 image: each level wants
    // offscreen images the size of the image (the offscreen budget and the nesting limit stop it).
    std::string body;
    const int n = 40;
    for (int i = 0; i < n; ++i) {
      const std::string next = std::to_string(i + 1);
      body += "<mask id=\"m" + std::to_string(i) + "\"><rect width=\"100\" height=\"100\" fill=\"white\"" +
              (i + 1 < n ? " mask=\"url(#m" + next + ")\"" : "") + "/></mask>";
      body += "<clipPath id=\"c" + std::to_string(i) + "\"><rect width=\"100\" height=\"100\"" +
              (i + 1 < n ? " clip-path=\"url(#c" + next + ")\"" : "") + "/><rect width=\"1\" height=\"1\"/></clipPath>";
      body += "<pattern id=\"p" + std::to_string(i) + "\" patternUnits=\"userSpaceOnUse\" width=\"90\" height=\"90\">"
              "<rect width=\"90\" height=\"90\" fill=\"" + (i + 1 < n ? "url(#p" + next + ")" : "red") + "\"/></pattern>";
    }
    body += "<rect width=\"100\" height=\"100\" fill=\"url(#p0)\" mask=\"url(#m0)\" clip-path=\"url(#c0)\" opacity=\"0.5\"/>";
    out.push_back({"masks, clips and patterns nested 40 deep on a 4096 x 4096 image",
                   {"render", "IN", "-o", "OUT", "-w", "4096"}, svg("width=\"100\" height=\"100\"", body)});
  }
  {
    // Marker instances count as elements: 300000 vertices of five-element markers stop at the element limit.
    std::string points;
    for (int i = 0; i < 300000; ++i) points += std::to_string(i % 100) + "," + std::to_string(i % 7) + " ";
    out.push_back({"300000 marker instances", {"render", "IN", "-o", "OUT"},
                   svg(s10, "<marker id=\"m\"><rect width=\"1\" height=\"1\"/><rect width=\"1\" height=\"1\"/>"
                            "<rect width=\"1\" height=\"1\"/><rect width=\"1\" height=\"1\"/></marker>"
                            "<polyline points=\"" + points + "\" stroke=\"red\" marker-mid=\"url(#m)\"/>")});
  }
  {
    // Markers inside markers: nine markers whose 100-vertex content is marked by the next ones multiply by 100
    // per level (up to the nesting cap of 8): the element limit stops them.
    std::string points;
    for (int i = 0; i < 100; ++i) points += std::to_string(i) + "," + std::to_string(i % 2) + " ";
    std::string body;
    for (int i = 0; i < 9; ++i) {
      body += "<marker id=\"m" + std::to_string(i) + "\" markerUnits=\"userSpaceOnUse\"><polyline points=\"" + points +
              "\" stroke=\"red\" marker-mid=\"url(#m" + std::to_string((i + 1) % 9) + ")\" marker-start=\"url(#m" +
              std::to_string((i + 2) % 9) + ")\"/></marker>";
    }
    body += "<polyline points=\"" + points + "\" stroke=\"red\" marker-mid=\"url(#m0)\"/>";
    out.push_back({"markers nested in markers", {"render", "IN", "-o", "OUT"}, svg(s10, body)});
  }
  {
    // SVG images nested through data: URLs far beyond the nesting limit.
    std::string doc = svg(s10, "<rect width=\"5\" height=\"5\"/>");
    for (int level = 0; level < 12; ++level) {
      std::string escaped;
      for (const char c : doc) escaped += c == '<' ? "%3C" : c == '>' ? "%3E" : c == '"' ? "%22" : c == '%' ? "%25" : std::string(1, c);
      doc = svg(s10, "<image width=\"10\" height=\"10\" href=\"data:image/svg+xml," + escaped + "\"/>");
    }
    out.push_back({"SVG images nested 12 deep", {"render", "IN", "-o", "OUT"}, doc});
  }
  {
    // Viewports at fractional positions, 200 deep: each clip is a coverage plane the size of the image.
    std::string body;
    for (int i = 0; i < 200; ++i) body += "<svg x=\"0.3\" y=\"0.3\" width=\"99.5\" height=\"99.5\">";
    body += "<rect width=\"100\" height=\"100\" fill=\"green\"/>";
    for (int i = 0; i < 200; ++i) body += "</svg>";
    out.push_back({"200 nested fractional viewports on a 4096 x 4096 image", {"render", "IN", "-o", "OUT", "-w", "4096"},
                   svg("width=\"100\" height=\"100\"", body)});
  }
  out.push_back({"accuracy with missing scenes", {"accuracy", "-o", "OUT"}, ""});
  return out;
}

bool is_leftover(const fs::path& p, const fs::path& in, const fs::path& output, bool success) {
  if (p == in) return false;
  if (success && p == output) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: hostile_suite VRASTER SCRATCH_DIR\n");
    return 2;
  }
  const std::string vraster = argv[1];
  const fs::path scratch = argv[2];
  int failures = 0;
  const auto suite_start = std::chrono::steady_clock::now();
  for (const Case& c : cases()) {
    const fs::path dir = scratch / "case";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path in = dir / "IN.svg";
    if (!c.svg.empty()) std::ofstream(in, std::ios::binary) << c.svg;
    const fs::path output = c.args[0] == "accuracy" ? dir / "report" : dir / "out.png";
    std::vector<std::string> args{vraster};
    for (const std::string& a : c.args) args.push_back(a == "IN" ? in.string() : a == "OUT" ? output.string() : a);
    const auto t0 = std::chrono::steady_clock::now();
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
      rlimit as{kAddressSpace, kAddressSpace};
      setrlimit(RLIMIT_AS, &as);
      if (c.args[0] == "accuracy") setenv("VRASTER_BENCH_SCENES", "/nonexistent", 1);
      if (!freopen("/dev/null", "w", stdout) || !freopen((dir.string() + "/../stderr.txt").c_str(), "w", stderr))
        _exit(127);
      std::vector<char*> cargs;
      for (std::string& a : args) cargs.push_back(a.data());
      cargs.push_back(nullptr);
      execv(cargs[0], cargs.data());
      _exit(127);
    }
    int status = 0;
    rusage usage{};
    bool timed_out = false;
    for (;;) {
      const pid_t r = wait4(pid, &status, WNOHANG, &usage);
      if (r == pid) break;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (elapsed > kMaxSeconds && !timed_out) {
        timed_out = true;
        kill(pid, SIGTERM);  // as a timeout does: the partial file must go too
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::string problem;
    const bool exited = WIFEXITED(status);
    const int code = exited ? WEXITSTATUS(status) : -1;
    if (timed_out) problem += " over " + std::to_string(kMaxSeconds) + " s;";
    if (!exited) problem += " killed by signal " + std::to_string(WTERMSIG(status)) + ";";
    if (exited && code != 0 && code != 2) problem += " exit status " + std::to_string(code) + ";";
    if (usage.ru_maxrss > kMaxResidentKb) problem += " peak memory " + std::to_string(usage.ru_maxrss / 1024) + " MiB;";
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
      if (e.is_directory()) continue;
      const bool under_report = c.args[0] == "accuracy" && e.path().parent_path() == output && code == 0;
      if (!under_report && is_leftover(e.path(), in, output, code == 0)) problem += " left behind " + e.path().string() + ";";
    }
    std::printf("%-40s status %3d  %6.2f s  %5ld MiB%s%s\n", c.name.c_str(), code, seconds, usage.ru_maxrss / 1024,
                problem.empty() ? "" : "  FAILED:", problem.c_str());
    if (!problem.empty()) {
      ++failures;
      std::ifstream err(scratch / "stderr.txt");
      std::string line;
      for (int i = 0; i < 5 && std::getline(err, line); ++i) std::printf("    stderr: %s\n", line.substr(0, 200).c_str());
    }
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - suite_start).count();
  std::printf("%d failure(s), %.1f s in all\n", failures, total);
  return failures == 0 ? 0 : 1;
}
