#include "apps/runtime/build_watch.h"

#include "apps/runtime/progress.h"

#include <fmt/core.h>

#include <chrono>

namespace bvhlab {
namespace {

constexpr auto kFirstLine = std::chrono::seconds(2);
constexpr auto kInterval = std::chrono::seconds(10);

}  // namespace

BuildWatch::BuildWatch(std::string label) {
    if (Progress::defaultStyle() == Progress::Style::Quiet) return;
    thread_ = std::thread([this, label = std::move(label)] {
        const auto start = std::chrono::steady_clock::now();
        std::unique_lock lock(mutex_);
        for (auto next = start + kFirstLine; !done_.wait_until(lock, next, [this] { return finished_; });
             next += kInterval) {
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            fmt::print(stderr, "{}: still building after {}\n", label, Progress::formatDuration(elapsed));
            std::fflush(stderr);
        }
    });
}

BuildWatch::~BuildWatch() {
    if (!thread_.joinable()) return;
    {
        const std::lock_guard lock(mutex_);
        finished_ = true;
    }
    done_.notify_one();
    thread_.join();
}

}  // namespace bvhlab
