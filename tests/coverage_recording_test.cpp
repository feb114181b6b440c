// detail::CoverageRecording, what a queued rectangle waits as: calls recorded row by row, a run of rows alike
// recorded once (repeat_row), replayed for any range of rows (a band's) as the calls themselves would have come,
// against the same calls expanded by hand.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "raster/rasterizer_p.hpp"

namespace vraster::test {
namespace {

using detail::CoverageRecording;

// Every call as text, in the order it came.
class CallLog final : public CoverageSink {
 public:
  void span(int y, int x0, int x1, float coverage) override {
    calls.push_back("span " + std::to_string(y) + " " + std::to_string(x0) + " " + std::to_string(x1) + " " +
                    std::to_string(coverage));
  }
  void row(int y, int x0, int x1, const float* coverage) override {
    std::string c = "row " + std::to_string(y) + " " + std::to_string(x0) + " " + std::to_string(x1);
    for (int x = x0; x < x1; ++x) {
      c += ' ';  // (appended apart: " " + std::to_string(...) draws a false -Wrestrict warning from GCC 12)
      c += std::to_string(coverage[x - x0]);
    }
    calls.push_back(c);
  }
  std::vector<std::string> calls;
};

// A rectangle's calls: row 2 partial (one row), rows 3-7 alike (a border pixel, the inside, a border pixel), row 8
// partial; each `inside` row as recorded (once, then repeated) or given in full.
void rectangle_calls(CoverageSink& sink, CoverageRecording* recording) {
  const float top[3] = {0.125f, 0.25f, 0.125f}, border[1] = {0.5f};
  sink.row(2, 10, 13, top);
  for (int y = 3; y < 8; ++y) {
    sink.row(y, 10, 11, border);
    sink.span(y, 11, 20, 1.0f);
    sink.span(y, 20, 21, 0.5f);
    if (recording) {
      recording->repeat_row(y, 8);
      break;
    }
  }
  sink.row(8, 10, 13, top);
}

TEST(CoverageRecording, RowsRecordedOnceReplayAsEveryRowForAnyRange) {
  CoverageRecording recording;
  rectangle_calls(recording, &recording);
  CallLog all;
  rectangle_calls(all, nullptr);
  EXPECT_EQ(recording.y_min(), 2);
  EXPECT_EQ(recording.y_max(), 9);
  EXPECT_EQ(recording.calls(), all.calls.size());  // the calls a replay makes, not the ones stored
  EXPECT_EQ(recording.pixels(), 3u + 5u * 11u + 3u);
  // Every range of rows, as bands cut them: the calls of those rows, in order.
  for (int from = 0; from <= 10; ++from) {
    for (int to = from; to <= 10; ++to) {
      CallLog replayed, expected;
      recording.replay(from, to, replayed);
      for (const std::string& c : all.calls) {
        const int y = std::stoi(c.substr(c.find(' ') + 1));
        if (y >= from && y < to) expected.calls.push_back(c);
      }
      EXPECT_EQ(replayed.calls, expected.calls) << "rows " << from << " to " << to;
    }
  }
}

TEST(CoverageRecording, RepeatingARowWithoutCallsChangesNothing) {
  CoverageRecording recording;
  const float c[2] = {0.5f, 0.25f};
  recording.row(4, 0, 2, c);
  recording.repeat_row(5, 9);  // row 5 has no calls: row 4's must not stand for rows 5-8
  EXPECT_EQ(recording.y_max(), 5);
  EXPECT_EQ(recording.calls(), 1u);
  CallLog replayed;
  recording.replay(0, 20, replayed);
  ASSERT_EQ(replayed.calls.size(), 1u);
  recording.clear();
  EXPECT_TRUE(recording.empty());
  EXPECT_EQ(recording.calls(), 0u);
  EXPECT_EQ(recording.pixels(), 0u);
}

}  // namespace
}  // namespace vraster::test
