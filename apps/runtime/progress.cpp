#include "apps/runtime/progress.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include <unistd.h>

namespace bvhlab {
namespace {

using Seconds = std::chrono::duration<double>;

constexpr auto kLiveDelay = std::chrono::seconds(2);  // quick phases draw nothing
constexpr auto kLiveInterval = std::chrono::milliseconds(200);
constexpr auto kLinesInterval = std::chrono::seconds(10);  // log files stay short

std::atomic<bool> quietFlag{false};

// Carriage return and erase-line: the live line is redrawn in place.
constexpr const char* kEraseLine = "\r\033[K";

// 950, 12.3k, 4.56M
std::string formatCount(double value) {
    if (value < 1e4) return fmt::format("{:.0f}", value);
    if (value < 1e6) return fmt::format("{:.1f}k", value * 1e-3);
    return fmt::format("{:.2f}M", value * 1e-6);
}

}  // namespace

Progress::Style Progress::defaultStyle() {
    if (quietFlag) return Style::Quiet;
    return ::isatty(STDERR_FILENO) ? Style::Live : Style::Lines;
}

void Progress::setQuiet(bool quiet) { quietFlag = quiet; }

Progress::Progress(Style style, std::FILE* out, std::function<Clock::time_point()> now)
    : style_(style), out_(out), now_(std::move(now)) {}

Progress::~Progress() { finish(); }

void Progress::endInterruptedLine() {
    if (defaultStyle() != Style::Live) return;
    std::fputs(kEraseLine, stderr);
    std::fflush(stderr);
}

std::string Progress::formatDuration(double seconds) {
    const long s = std::lround(std::max(seconds, 0.0));
    if (s < 60) return fmt::format("{}s", s);
    if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
    return fmt::format("{}h{:02}m", s / 3600, s % 3600 / 60);
}

void Progress::phase(std::string label, uint64_t total) {
    finish();
    const std::lock_guard lock(mutex_);
    label_ = std::move(label);
    total_ = total;
    start_ = now_();
    done_ = 0;
    rays_ = 0;
    active_ = true;
    const auto first = style_ == Style::Live ? start_ + kLiveDelay : start_ + kLinesInterval;
    nextDrawTicks_ = first.time_since_epoch().count();
    if (style_ == Style::Lines) {
        fmt::print(out_, "{}\n", label_);
        std::fflush(out_);
    }
}

void Progress::advance(uint64_t units, uint64_t rays) {
    done_.fetch_add(units, std::memory_order_relaxed);
    rays_.fetch_add(rays, std::memory_order_relaxed);
    if (style_ == Style::Quiet) return;
    const Clock::time_point now = now_();
    int64_t next = nextDrawTicks_.load(std::memory_order_relaxed);
    if (now.time_since_epoch().count() < next) return;
    // One thread wins the right to draw this time; the others go back to work.
    const auto after = now + (style_ == Style::Live ? Clock::duration(kLiveInterval) : Clock::duration(kLinesInterval));
    if (!nextDrawTicks_.compare_exchange_strong(next, after.time_since_epoch().count())) return;
    const std::lock_guard lock(mutex_);
    if (active_) draw(now, false);
}

void Progress::finish() {
    const std::lock_guard lock(mutex_);
    if (!active_) return;
    active_ = false;
    const Clock::time_point now = now_();
    if (style_ == Style::Quiet) return;
    if (lineShown_ || (style_ == Style::Lines && now - start_ > kLiveDelay)) draw(now, true);
}

void Progress::draw(Clock::time_point now, bool final) {
    const double elapsed = Seconds(now - start_).count();
    const uint64_t done = done_.load(std::memory_order_relaxed), rays = rays_.load(std::memory_order_relaxed);
    std::string line = label_ + ":";
    if (final) {
        line += fmt::format(" done in {}", formatDuration(elapsed));
    } else if (total_ > 0) {
        const double fraction = std::min(1.0, double(done) / double(total_));
        line += fmt::format(" {:3.0f}%", 100.0 * fraction);
        line += fraction > 0.0 ? fmt::format(", ETA {}", formatDuration(elapsed * (1.0 - fraction) / fraction))
                               : std::string(", ETA ?");
        line += fmt::format(" (elapsed {})", formatDuration(elapsed));
    } else {
        line += fmt::format(" elapsed {}", formatDuration(elapsed));
    }
    if (rays > 0 && elapsed > 0.0) line += fmt::format(", {} rays/s", formatCount(double(rays) / elapsed));
    if (style_ == Style::Live) {
        fmt::print(out_, "{}{}{}", kEraseLine, line, final ? "\n" : "");
        lineShown_ = !final;
    } else {
        fmt::print(out_, "{}\n", line);
    }
    std::fflush(out_);
}

}  // namespace bvhlab
