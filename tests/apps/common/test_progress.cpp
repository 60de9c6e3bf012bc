// The progress line (apps/common/progress.h) on a memory stream with a clock the test moves: the
// phase line and the 10 s rate off a terminal, the 2 s silence and the redraws on one, --quiet.
#include "apps/common/progress.h"
#include "tests/support/text_count.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

using namespace bvhlab;

namespace {

// A Progress on a memory stream with a clock the test moves.
struct ProgressUnderTest {
    Progress::Clock::time_point now{};
    char* buffer = nullptr;
    size_t size = 0;
    std::FILE* stream = open_memstream(&buffer, &size);
    ~ProgressUnderTest() {
        std::fclose(stream);
        std::free(buffer);
    }
    std::string text() {
        std::fflush(stream);
        return std::string(buffer, size);
    }
};

}  // namespace

TEST(Progress, LinesStyleWritesAPhaseLineThenAtMostOneEveryTenSeconds) {
    ProgressUnderTest t;
    {
        Progress progress(Progress::Style::Lines, t.stream, [&] { return t.now; });
        progress.phase("rendering", 1000);
        for (int i = 0; i < 350; ++i) {  // 35 s in steps of 0.1 s
            t.now += std::chrono::milliseconds(100);
            progress.advance(2, 512);
        }
    }
    const std::string text = t.text();
    EXPECT_EQ(text.find("rendering\n"), 0u) << text;
    EXPECT_EQ(test::occurrences(text, "\n"), 1u + 3u + 1u) << text;  // the phase, at 10, 20, 30 s, done
    EXPECT_NE(text.find("rendering:  20%, ETA 40s (elapsed 10s), 5120 rays/s\n"), std::string::npos) << text;
    EXPECT_NE(text.find("rendering: done in 35s"), std::string::npos) << text;
    EXPECT_EQ(text.find('\r'), std::string::npos) << text;
}

TEST(Progress, LiveStyleStaysSilentForTwoSecondsThenRedrawsOneLine) {
    ProgressUnderTest t;
    Progress progress(Progress::Style::Live, t.stream, [&] { return t.now; });
    progress.phase("building", 10);
    t.now += std::chrono::milliseconds(1900);
    progress.advance(1);
    EXPECT_EQ(t.text(), "");  // quick work prints nothing
    t.now += std::chrono::milliseconds(200);
    progress.advance(1);
    t.now += std::chrono::milliseconds(50);
    progress.advance(1);  // too soon to redraw
    t.now += std::chrono::milliseconds(200);
    progress.advance(1);
    progress.finish();
    const std::string text = t.text();
    EXPECT_EQ(test::occurrences(text, "\r\033[K"), 3u) << text;  // two redraws and the final line
    EXPECT_EQ(test::occurrences(text, "\n"), 1u) << text;
    EXPECT_NE(text.find("building:  40%"), std::string::npos) << text;
}

TEST(Progress, QuietWritesNothing) {
    ProgressUnderTest t;
    {
        Progress progress(Progress::Style::Quiet, t.stream, [&] { return t.now; });
        progress.phase("rendering", 10);
        t.now += std::chrono::seconds(60);
        progress.advance(5, 100);
    }
    EXPECT_EQ(t.text(), "");
}
