// Progress of long work on stderr, so a user knows a run is alive and when it will end.
// On a terminal: one live line (phase, percent, rays/s, ETA), redrawn at most 5 times a second
// and only once the phase has run 2 s, so quick runs stay silent. Off a terminal (a log file, CI):
// a line when a phase starts and at most one line per 10 s. `--quiet` silences both.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace bvhlab {

class Progress {
public:
    enum class Style { Live, Lines, Quiet };
    using Clock = std::chrono::steady_clock;

    // The style every subcommand's progress takes: Live on a terminal, Lines elsewhere, or
    // Quiet after setQuiet(true) (the --quiet flag).
    static Style defaultStyle();
    static void setQuiet(bool quiet);

    explicit Progress(Style style = defaultStyle(), std::FILE* out = stderr,
                      std::function<Clock::time_point()> now = Clock::now);
    ~Progress();  // ends the live line
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Starts a phase of `total` units (0: no percentage or ETA). `label` prefixes every line
    // of the phase, e.g. "[job 3/30] conference sahbvh: rendering".
    void phase(std::string label, uint64_t total = 0);
    // `units` of the phase done and `rays` traced meanwhile; cheap and safe from any thread.
    void advance(uint64_t units, uint64_t rays = 0);
    // Ends the phase; prints its duration off a terminal if it took longer than 2 s.
    void finish();

    // Clears a live line that another process left unfinished on stderr (a child that died).
    static void endInterruptedLine();

    // "12s", "1m12s", "1h05m".
    static std::string formatDuration(double seconds);

private:
    void draw(Clock::time_point now, bool final);

    Style style_;
    std::FILE* out_;
    std::function<Clock::time_point()> now_;
    std::mutex mutex_;  // guards the phase and the drawing; advance() only takes it to draw
    std::string label_;
    uint64_t total_ = 0;
    Clock::time_point start_;
    std::atomic<uint64_t> done_{0}, rays_{0};
    std::atomic<int64_t> nextDrawTicks_{0};
    bool lineShown_ = false;  // Live: a line is on screen and must be cleared
    bool active_ = false;
};

}  // namespace bvhlab
