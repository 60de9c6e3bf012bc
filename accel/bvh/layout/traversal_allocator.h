#pragma once

#include <cstddef>

namespace bvhlab {

void* allocateTraversalMemory(size_t bytes);
void freeTraversalMemory(void* p, size_t bytes);

// The allocator of the arrays the traversal reads. Allocates on 64-byte boundaries, so that a
// pair of sibling nodes fills one cache line. Arrays of 2 MiB or more start on a 2 MiB boundary
// and are advised to use transparent huge pages (Linux; as Embree does): a traversal step is
// bound by memory latency, and with 4 KiB pages most steps on a large tree also miss the TLB.
template <typename T>
struct TraversalAllocator {
    using value_type = T;
    TraversalAllocator() = default;
    template <typename U>
    TraversalAllocator(const TraversalAllocator<U>&) {}
    T* allocate(size_t n) { return static_cast<T*>(allocateTraversalMemory(n * sizeof(T))); }
    void deallocate(T* p, size_t n) { freeTraversalMemory(p, n * sizeof(T)); }
    template <typename U>
    bool operator==(const TraversalAllocator<U>&) const {
        return true;
    }
};

}  // namespace bvhlab
