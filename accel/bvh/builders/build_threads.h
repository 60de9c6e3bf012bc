// How the builders (and the collapse into wide nodes) run on BuildConfig::threads (internal to
// build/ and its caller, bvh_accelerator.cpp).
#pragma once

#include <tbb/task_arena.h>

namespace bvhlab {

// Runs f() on `threads` TBB threads (0 = all hardware threads). An arena even for one: TBB
// algorithms called outside any arena would run on all hardware threads.
template <typename F>
void onThreads(int threads, F&& f) {
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute(f);
}

}  // namespace bvhlab
