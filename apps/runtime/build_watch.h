// A line on stderr while a build runs longer than 2 s, and every 10 s after, so that a user sees
// a long build alive, and one that never returns for what it is: "sahbvh on conference: still
// building after 12s". Quick builds print nothing; `--quiet` silences it (Progress::Style::Quiet).
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace bvhlab {

class BuildWatch {
public:
    // Starts watching a build that `label` names; the destructor ends the watch.
    explicit BuildWatch(std::string label);
    ~BuildWatch();
    BuildWatch(const BuildWatch&) = delete;
    BuildWatch& operator=(const BuildWatch&) = delete;

private:
    std::mutex mutex_;
    std::condition_variable done_;
    bool finished_ = false;
    std::thread thread_;
};

}  // namespace bvhlab
