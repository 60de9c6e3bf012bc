// The progress line (apps/runtime/progress.h) on a memory stream with a clock the test moves: the
// phase line and the 10 s rate off a terminal, the 2 s silence and the redraws on one, --quiet.
#include "apps/runtime/progress.h"
#include "tests/support/text_count.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

using namespace bvhlab;

namespace {

// A Progress of one style on a memory stream, with a clock the test moves.
class ProgressUnderTest {
public:
    explicit ProgressUnderTest(Progress::Style style)
        : progress_(std::in_place, style, stream_, [this] { return now_; }) {}
    ~ProgressUnderTest() {
        progress_.reset();
        std::fclose(stream_);
        std::free(buffer_);
    }

    Progress& progress() { return *progress_; }
    // Moves the clock on by `step`, then reports `units` of the phase done and `rays` traced.
    void advanceAfter(Progress::Clock::duration step, uint64_t units, uint64_t rays = 0) {
        now_ += step;
        progress_->advance(units, rays);
    }
    // What the progress has written so far.
    std::string text() {
        std::fflush(stream_);
        return std::string(buffer_, size_);
    }
    // Destroys the progress (which ends its line) and returns everything it wrote.
    std::string textAfterEnd() {
        progress_.reset();
        return text();
    }

private:
    Progress::Clock::time_point now_{};
    char* buffer_ = nullptr;
    size_t size_ = 0;
    std::FILE* stream_ = open_memstream(&buffer_, &size_);
    std::optional<Progress> progress_;  // last: it writes to stream_ and reads now_
};

}  // namespace

TEST(Progress, LinesStyleWritesAPhaseLineThenAtMostOneEveryTenSeconds) {
    ProgressUnderTest t(Progress::Style::Lines);
    t.progress().phase("rendering", 1000);
    for (int i = 0; i < 350; ++i) t.advanceAfter(std::chrono::milliseconds(100), 2, 512);  // 35 s in steps of 0.1 s
    const std::string text = t.textAfterEnd();
    EXPECT_EQ(text.find("rendering\n"), 0u) << text;
    EXPECT_EQ(test::occurrences(text, "\n"), 1u + 3u + 1u) << text;  // the phase, at 10, 20, 30 s, done
    EXPECT_NE(text.find("rendering:  20%, ETA 40s (elapsed 10s), 5120 rays/s\n"), std::string::npos) << text;
    EXPECT_NE(text.find("rendering: done in 35s"), std::string::npos) << text;
    EXPECT_EQ(text.find('\r'), std::string::npos) << text;
}

TEST(Progress, LiveStyleStaysSilentForTwoSecondsThenRedrawsOneLine) {
    ProgressUnderTest t(Progress::Style::Live);
    t.progress().phase("building", 10);
    t.advanceAfter(std::chrono::milliseconds(1900), 1);
    EXPECT_EQ(t.text(), "");  // quick work prints nothing
    t.advanceAfter(std::chrono::milliseconds(200), 1);
    t.advanceAfter(std::chrono::milliseconds(50), 1);  // too soon to redraw
    t.advanceAfter(std::chrono::milliseconds(200), 1);
    t.progress().finish();
    const std::string text = t.text();
    EXPECT_EQ(test::occurrences(text, "\r\033[K"), 3u) << text;  // two redraws and the final line
    EXPECT_EQ(test::occurrences(text, "\n"), 1u) << text;
    EXPECT_NE(text.find("building:  40%"), std::string::npos) << text;
}

TEST(Progress, QuietWritesNothing) {
    ProgressUnderTest t(Progress::Style::Quiet);
    t.progress().phase("rendering", 10);
    t.advanceAfter(std::chrono::seconds(60), 5, 100);
    EXPECT_EQ(t.textAfterEnd(), "");
}
