// svg_subset: SVG path data ("M 10 10 L 20 20 Z") into a vraster::Path.
//
// A hand-written scanner over the SVG 1.1 path grammar. Every command letter is followed by one or more
// argument sets (implicit repetition); each set becomes one Path segment as soon as it is complete, so on an
// error the path holds everything before the faulty set, which is what SVG asks renderers to draw.
#include <initializer_list>
#include <string>
#include <string_view>

#include "scan.hpp"
#include "svg_subset/svg.hpp"

namespace vraster::svg {
namespace {

using detail::at_number_start;
using detail::NumberScan;
using detail::scan_number;
using detail::skip_comma_wsp;
using detail::skip_wsp;

/// How many arguments one set of each command takes (0 for Z and for non-commands).
int argument_count(char upper) {
  switch (upper) {
    case 'M':
    case 'L':
    case 'T':
      return 2;
    case 'H':
    case 'V':
      return 1;
    case 'C':
      return 6;
    case 'S':
    case 'Q':
      return 4;
    case 'A':
      return 7;
    default:
      return 0;
  }
}

bool is_command(char c) { return std::string_view("MmLlHhVvCcSsQqTtAaZz").find(c) != std::string_view::npos; }

char to_upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

/// "'x'" for a printable character, "byte 0xNN" otherwise (messages must stay readable).
std::string describe_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  static const char* const hex = "0123456789abcdef";
  return std::string("byte 0x") + hex[u >> 4] + hex[u & 15];
}

class PathDataParser {
 public:
  PathDataParser(std::string_view d, Path& out) : d_(d), out_(out) {}

  void run() {
    skip_wsp(d_, pos_);
    if (pos_ == d_.size()) return;  // empty path data is valid and draws nothing
    if (d_[pos_] != 'M' && d_[pos_] != 'm') {
      fail(pos_, "path data must begin with a moveto ('M' or 'm'), found " + describe_char(d_[pos_]));
    }
    while (true) {
      skip_wsp(d_, pos_);
      if (pos_ == d_.size()) return;
      const char command = d_[pos_];
      if (!is_command(command)) {
        if (at_number_start(d_, pos_)) {
          fail(pos_, std::string("unexpected number after '") + last_letter_ + "' (it takes no more arguments)");
        }
        fail(pos_, "unexpected character " + describe_char(command));
      }
      ++pos_;
      last_letter_ = command;
      run_command(command);
    }
  }

 private:
  [[noreturn]] void fail(std::size_t offset, const std::string& message) { throw PathDataError(offset, message); }

  /// Reads the argument sets that follow a command letter and emits one segment per set.
  void run_command(char command) {
    const char upper = to_upper(command);
    const bool relative = command != upper;
    if (upper == 'Z') {
      emit(pos_ - 1, [&] { out_.close(); });
      current_ = subpath_start_;
      previous_ = 'Z';
      return;
    }
    const int count = argument_count(upper);
    skip_wsp(d_, pos_);
    char effective = upper;  // extra pairs after a moveto are linetos
    while (true) {
      const std::size_t set_start = pos_;
      double v[7] = {};
      bool flags[2] = {false, false};
      for (int i = 0; i < count; ++i) {
        if (i > 0) skip_comma_wsp(d_, pos_);
        if (upper == 'A' && (i == 3 || i == 4)) {
          flags[i - 3] = read_flag(command, i, count);
        } else {
          v[i] = read_number(command, i, count);
        }
      }
      execute(effective, relative, v, flags, set_start);
      if (effective == 'M') effective = 'L';
      // Another set follows when, after an optional comma, the next thing is a number.
      const bool comma = skip_comma_wsp(d_, pos_);
      if (at_number_start(d_, pos_)) continue;
      if (comma) fail(pos_, std::string("expected a number after ',' in the arguments of '") + command + "'");
      return;
    }
  }

  double read_number(char command, int index, int count) {
    const std::size_t start = pos_;
    double value = 0;
    switch (scan_number(d_, pos_, value)) {
      case NumberScan::Ok:
        return value;
      case NumberScan::OutOfRange:
        fail(start, "number out of range: " + printable(d_.substr(start, pos_ - start)));
      case NumberScan::NotANumber:
        break;
    }
    fail(start, missing_argument(command, index, count, "a number"));
  }

  bool read_flag(char command, int index, int count) {
    if (pos_ < d_.size() && (d_[pos_] == '0' || d_[pos_] == '1')) return d_[pos_++] == '1';
    if (pos_ == d_.size()) fail(pos_, missing_argument(command, index, count, "an arc flag"));
    fail(pos_, "arc flag must be 0 or 1, found " + describe_char(d_[pos_]));
  }

  std::string missing_argument(char command, int index, int count, const char* what) const {
    std::string message = std::string("expected ") + what + " after '" + command + "'";
    if (pos_ < d_.size()) message += ", found " + describe_char(d_[pos_]);
    if (index > 0) {
      message += " ('" + std::string(1, command) + "' takes " + std::to_string(count) + " numbers per segment, got " +
                 std::to_string(index) + ")";
    }
    return message;
  }

  /// Runs one Path call, turning a core error (e.g. a coordinate that overflowed) into a positioned one.
  template <class F>
  void emit(std::size_t offset, F&& call) {
    try {
      call();
    } catch (const Error& e) {
      fail(offset, e.what());
    }
  }

  Point absolute(bool relative, double x, double y) const {
    return relative ? Point{current_.x + x, current_.y + y} : Point{x, y};
  }

  void check_finite(std::initializer_list<Point> points, std::size_t offset) {
    for (const Point& p : points) {
      if (!is_finite(p)) fail(offset, "coordinate out of range");
    }
  }

  void execute(char command, bool relative, const double* v, const bool* flags, std::size_t offset) {
    switch (command) {
      case 'M': {
        const Point p = absolute(relative, v[0], v[1]);
        check_finite({p}, offset);
        emit(offset, [&] { out_.move_to(p); });
        current_ = subpath_start_ = p;
        break;
      }
      case 'L':
      case 'H':
      case 'V': {
        Point p;
        if (command == 'L')
          p = absolute(relative, v[0], v[1]);
        else if (command == 'H')
          p = {relative ? current_.x + v[0] : v[0], current_.y};
        else
          p = {current_.x, relative ? current_.y + v[0] : v[0]};
        check_finite({p}, offset);
        emit(offset, [&] { out_.line_to(p); });
        current_ = p;
        break;
      }
      case 'C':
      case 'S': {
        Point c1, c2, p;
        if (command == 'C') {
          c1 = absolute(relative, v[0], v[1]);
          c2 = absolute(relative, v[2], v[3]);
          p = absolute(relative, v[4], v[5]);
        } else {
          // The first control point mirrors the previous cubic's second one, if the previous segment was a cubic.
          c1 = (previous_ == 'C' || previous_ == 'S') ? current_ * 2.0 - last_control_ : current_;
          c2 = absolute(relative, v[0], v[1]);
          p = absolute(relative, v[2], v[3]);
        }
        check_finite({c1, c2, p}, offset);
        emit(offset, [&] { out_.cubic_to(c1, c2, p); });
        last_control_ = c2;
        current_ = p;
        break;
      }
      case 'Q':
      case 'T': {
        Point c, p;
        if (command == 'Q') {
          c = absolute(relative, v[0], v[1]);
          p = absolute(relative, v[2], v[3]);
        } else {
          c = (previous_ == 'Q' || previous_ == 'T') ? current_ * 2.0 - last_control_ : current_;
          p = absolute(relative, v[0], v[1]);
        }
        check_finite({c, p}, offset);
        emit(offset, [&] { out_.quad_to(c, p); });
        last_control_ = c;
        current_ = p;
        break;
      }
      case 'A': {
        // v[3] and v[4] are unused: the flags arrive separately.
        const Point p = absolute(relative, v[5], v[6]);
        check_finite({p}, offset);
        emit(offset, [&] { out_.arc_to(v[0], v[1], v[2], flags[0], flags[1], p); });
        current_ = p;
        break;
      }
      default:
        break;
    }
    previous_ = command;
  }

  std::string_view d_;
  Path& out_;
  std::size_t pos_ = 0;
  Point current_{};
  Point subpath_start_{};
  Point last_control_{};  // second control point of the last cubic, or control point of the last quadratic
  char previous_ = 0;     // upper-case command of the last segment (M's extra pairs count as L)
  char last_letter_ = 0;  // the last command letter as written, for messages
};

}  // namespace

void parse_path_data(std::string_view d, Path& out) { PathDataParser(d, out).run(); }

}  // namespace vraster::svg
