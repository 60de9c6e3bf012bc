#include "accel/bvh/layout/traversal_allocator.h"

#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace bvhlab {

namespace {

constexpr size_t kHugePage = size_t(2) << 20;
constexpr std::align_val_t kCacheLine{64};

}  // namespace

void* allocateTraversalMemory(size_t bytes) {
    if (bytes < kHugePage) return ::operator new(bytes, kCacheLine);
    // Whole huge pages: the advice covers the array and nothing else.
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = ::operator new (rounded, std::align_val_t{kHugePage});
#if defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without THP the pages stay small
#endif
    return p;
}

void freeTraversalMemory(void* p, size_t bytes) {
    if (bytes < kHugePage) {
        ::operator delete(p, kCacheLine);
        return;
    }
    ::operator delete (p, std::align_val_t{kHugePage});
}

}  // namespace bvhlab
