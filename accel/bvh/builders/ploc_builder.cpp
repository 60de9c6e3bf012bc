#include "accel/bvh/builders/ploc_builder.h"

#include "accel/bvh/builders/build_steps.h"
#include "accel/bvh/builders/build_threads.h"
#include "accel/bvh/builders/cluster_tree.h"
#include "accel/bvh/builders/morton_code.h"
#include "accel/bvh/builders/radix_sort.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <limits>
#include <memory>

namespace bvhlab {

namespace {

// Clusters per task of the neighbour search and of the merge.
constexpr uint32_t kChunk = 4096;

// Pairs are ordered by the area of the box around both, then by how far apart they lie in the
// array, then even first index before odd, then by index. A total order on pairs, so the least
// pair of the whole array is mutual (every iteration merges); and a run of equal areas (equal
// boxes) pairs up 0-1, 2-3, ... rather than chaining each cluster to its left neighbour, which
// would merge one pair per iteration.
uint64_t pairRank(uint32_t first, uint32_t second) {
    return uint64_t(second - first) << 33 | uint64_t(first & 1) << 32 | first;
}

constexpr int kLanes = 8;
constexpr uint32_t kNoCluster = ~uint32_t(0);
constexpr int kMaxRowVectors = (256 + kLanes - 1) / kLanes;  // BVH::plocRadius <= 256

// Added to a vector of areas whose first k lanes are candidates: NaN rules out the others (no
// comparison holds for it, and min(NaN, x) is x).
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
alignas(32) constexpr float kLanePenalty[kLanes + 1][kLanes] = {{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN},
                                                                {0, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN},
                                                                {0, 0, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN},
                                                                {0, 0, 0, kNaN, kNaN, kNaN, kNaN, kNaN},
                                                                {0, 0, 0, 0, kNaN, kNaN, kNaN, kNaN},
                                                                {0, 0, 0, 0, 0, kNaN, kNaN, kNaN},
                                                                {0, 0, 0, 0, 0, 0, kNaN, kNaN},
                                                                {0, 0, 0, 0, 0, 0, 0, kNaN},
                                                                {0, 0, 0, 0, 0, 0, 0, 0}};

// The best left neighbour found so far of the clusters of a chunk and the radius around it:
// areas, and cluster indices as float bit patterns (blended by the same SIMD select).
struct LeftBest {
    std::vector<float> area;
    std::vector<float> index;
};

// The clusters' boxes by coordinate (lower x y z, upper x y z), eight candidates per SIMD load,
// with `pad` infinite boxes before and after them (a merge with one costs +inf), so that a
// window may read past either end.
class ClusterBoxes {
public:
    void reset(uint32_t n, uint32_t pad) {
        pad_ = pad;
        for (int c = 0; c < 6; ++c) coord_[c].assign(n + 2 * size_t(pad), c < 3 ? -kInf : kInf);
    }
    void set(uint32_t i, const ClusterBox& b) {
        for (int a = 0; a < 3; ++a) coord_[a][pad_ + i] = b.lower[a], coord_[3 + a][pad_ + i] = b.upper[a];
    }
    ClusterBox get(uint32_t i) const {
        ClusterBox b{};
        for (int a = 0; a < 3; ++a) b.lower[a] = coord_[a][pad_ + i], b.upper[a] = coord_[3 + a][pad_ + i];
        return b;
    }
    // Infinite boxes after the first `count` again.
    void endAt(uint32_t count) {
        for (int c = 0; c < 6; ++c) std::fill_n(coord_[c].begin() + pad_ + count, pad_, c < 3 ? -kInf : kInf);
    }
    // Coordinate c of cluster i, i from -pad on.
    const float* at(int c, int64_t i) const { return coord_[c].data() + pad_ + i; }

private:
    uint32_t pad_ = 0;
    std::vector<float> coord_[6];
};

class Clustering {
public:
    Clustering(const BuildConfig& config, const PlocConfig& ploc, std::span<const PrimRef> leafRefs)
        : config_(config), radius_(uint32_t(std::clamp(ploc.radius, 1, 256))) {
        const uint32_t n = uint32_t(leafRefs.size());
        const uint32_t pad = (radius_ + kLanes - 1) / kLanes * kLanes + kLanes;
        tree_.resize(n);
        ids_.resize(n), nextIds_.resize(n), neighbour_.resize(n);
        boxes_.reset(n, pad), nextBoxes_.reset(n, pad);
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, kChunk), [&](const tbb::blocked_range<uint32_t>& r) {
            for (uint32_t i = r.begin(); i < r.end(); ++i) {
                const PrimRef& p = leafRefs[i];
                tree_.boxes[i] = {{p.lower[0], p.lower[1], p.lower[2], 0.0f},
                                  {p.upper[0], p.upper[1], p.upper[2], 0.0f}};
                boxes_.set(i, tree_.boxes[i]);
                formNode(tree_, i, config_);
                ids_[i] = i;
            }
        });
    }

    ClusterTree run() {
        uint32_t count = tree_.leafCount, next = tree_.leafCount;
        while (count > 1) {
            if (config_.simd) {
                findNeighbours<simd::Floats<kLanes>>(count);
            } else {
                findNeighbours<simd::Scalar<kLanes>>(count);
            }
            count = merge(count, next);
        }
        return std::move(tree_);
    }

private:
    // neighbour_[i] for every cluster i < count: the least pair (pairRank) among the radius_
    // clusters on either side. Each pair is computed once, by its left cluster, eight per SIMD
    // step: the row of i's right neighbours gives i's best on the right and is offered to each
    // of them as their left candidate. A chunk [b, e) computes the rows from b - r on.
    template <typename F>
    void findNeighbours(uint32_t count) {
        const int r = int(radius_), vectors = (r + kLanes - 1) / kLanes;
        tbb::parallel_for(uint32_t(0), (count + kChunk - 1) / kChunk, [&](uint32_t chunk) {
            const uint32_t b = chunk * kChunk, e = std::min(count, b + kChunk);
            const uint32_t lo = b > uint32_t(r) ? b - r : 0;
            LeftBest& left = leftBest_.local();
            left.area.assign(e - lo + r + kLanes, kInf);
            left.index.assign(e - lo + r + kLanes, std::bit_cast<float>(kNoCluster));
            F row[kMaxRowVectors];
            for (uint32_t i = lo; i < e; ++i) {
                F lower[3], upper[3];
                for (int a = 0; a < 3; ++a)
                    lower[a] = F::broadcast(*boxes_.at(a, i)), upper[a] = F::broadcast(*boxes_.at(3 + a, i));
                const F self = F::broadcast(std::bit_cast<float>(i));
                F least = F::broadcast(kInf);
                for (int v = 0; v < vectors; ++v) {
                    const int64_t start = int64_t(i) + 1 + kLanes * v;
                    F d[3];
                    for (int a = 0; a < 3; ++a)
                        d[a] = max(upper[a], F::loadu(boxes_.at(3 + a, start))) -
                               min(lower[a], F::loadu(boxes_.at(a, start)));
                    F area = d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
                    if (r - kLanes * v < kLanes) area = area + F::loadu(kLanePenalty[r - kLanes * v]);
                    row[v] = area;
                    least = min(area, least);
                    // Offered to the eight as their left candidate: i is the nearest so far, so
                    // it wins ties (the nearer pair ranks first).
                    float* bestArea = left.area.data() + (start - lo);
                    float* bestIndex = left.index.data() + (start - lo);
                    const F oldArea = F::loadu(bestArea);
                    const auto better = area <= oldArea;
                    select(better, area, oldArea).storeu(bestArea);
                    select(better, self, F::loadu(bestIndex)).storeu(bestIndex);
                }
                if (i < b) continue;
                // i's best on the right: the least area, ties to the nearest (first lane).
                alignas(32) float lanes[kLanes];
                least.store(lanes);
                const float rightArea = *std::min_element(lanes, lanes + kLanes);
                uint32_t right = kNoCluster;
                for (int v = 0; v < vectors && right == kNoCluster; ++v) {
                    if (const int bits = movemask(row[v] <= F::broadcast(rightArea)))
                        right = i + 1 + kLanes * v + uint32_t(std::countr_zero(unsigned(bits)));
                }
                if (right >= count) right = kNoCluster;  // only the infinite boxes past the end
                const uint32_t leftIndex = std::bit_cast<uint32_t>(left.index[i - lo]);
                const float leftArea = left.area[i - lo];
                uint32_t best;
                if (right == kNoCluster || leftIndex == kNoCluster) {
                    best = right == kNoCluster ? leftIndex : right;
                } else if (rightArea != leftArea) {
                    best = rightArea < leftArea ? right : leftIndex;
                } else {
                    best = pairRank(leftIndex, i) < pairRank(i, right) ? leftIndex : right;
                }
                neighbour_[i] = best;
            }
        });
    }

    bool mergesHere(uint32_t i) const { return neighbour_[neighbour_[i]] == i && i < neighbour_[i]; }
    bool mergedAway(uint32_t i) const { return neighbour_[neighbour_[i]] == i && neighbour_[i] < i; }

    // Merges the mutual pairs into new nodes from `next` on (advanced) and compacts the clusters;
    // returns how many are left. Offsets per chunk first, so each chunk writes its own places.
    uint32_t merge(uint32_t count, uint32_t& next) {
        const uint32_t chunks = (count + kChunk - 1) / kChunk;
        chunkMerges_.assign(chunks + 1, 0);
        chunkKept_.assign(chunks + 1, 0);
        tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t chunk) {
            uint32_t merges = 0, kept = 0;
            for (uint32_t i = chunk * kChunk; i < std::min(count, (chunk + 1) * kChunk); ++i) {
                merges += mergesHere(i);
                kept += !mergedAway(i);
            }
            chunkMerges_[chunk + 1] = merges, chunkKept_[chunk + 1] = kept;
        });
        for (uint32_t c = 0; c < chunks; ++c) {
            chunkMerges_[c + 1] += chunkMerges_[c];
            chunkKept_[c + 1] += chunkKept_[c];
        }
        tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t chunk) {
            uint32_t node = next + chunkMerges_[chunk], out = chunkKept_[chunk];
            for (uint32_t i = chunk * kChunk; i < std::min(count, (chunk + 1) * kChunk); ++i) {
                if (mergedAway(i)) continue;
                if (mergesHere(i)) {
                    const uint32_t j = neighbour_[i];
                    const ClusterBox a = boxes_.get(i), b = boxes_.get(j);
                    ClusterBox& box = tree_.boxes[node];
                    for (int c = 0; c < 4; ++c) {
                        box.lower[c] = std::min(a.lower[c], b.lower[c]);
                        box.upper[c] = std::max(a.upper[c], b.upper[c]);
                    }
                    tree_.children[2 * size_t(node - tree_.leafCount)] = ids_[i];
                    tree_.children[2 * size_t(node - tree_.leafCount) + 1] = ids_[j];
                    formNode(tree_, node, config_);
                    nextIds_[out] = node++;
                    nextBoxes_.set(out++, box);
                } else {
                    nextIds_[out] = ids_[i];
                    nextBoxes_.set(out++, boxes_.get(i));
                }
            }
        });
        const uint32_t kept = chunkKept_[chunks];
        next += chunkMerges_[chunks];
        nextBoxes_.endAt(kept);
        std::swap(ids_, nextIds_);
        std::swap(boxes_, nextBoxes_);
        return kept;
    }

    const BuildConfig& config_;
    uint32_t radius_;
    ClusterTree tree_;
    std::vector<uint32_t> ids_, nextIds_;  // the clusters' nodes, in order
    ClusterBoxes boxes_, nextBoxes_;       // and their boxes
    std::vector<uint32_t> neighbour_;
    std::vector<uint32_t> chunkMerges_, chunkKept_;
    tbb::enumerable_thread_specific<LeftBest> leftBest_;
};

// `refs` in Morton order of their centres into `sorted` (ties by index: the radix sort is stable).
void sortByMortonCode(std::span<const PrimRef> refs, const BuildRange& root, PrimRef* sorted) {
    const uint32_t n = uint32_t(refs.size());
    const MortonGrid grid(root.centroidBounds);
    std::vector<KeyValue> keys(n), scratch;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, kChunk), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t i = r.begin(); i < r.end(); ++i) {
            const PrimRef& p = refs[i];
            keys[i] = {grid.code({p.center(0), p.center(1), p.center(2)}), i};
        }
    });
    radixSort(keys, scratch, MortonGrid::kBits);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, kChunk), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t i = r.begin(); i < r.end(); ++i) sorted[i] = refs[keys[i].value];
    });
}

}  // namespace

BinaryBvh buildPlocBvh(const BuildConfig& config, const PlocConfig& ploc, const PrimitiveSet& prims) {
    const size_t n = prims.validTriangles().size();
    BinaryBvh bvh;
    if (n == 0) return bvh;
    // Uninitialised storage: every PrimRef is written before it is read.
    const std::unique_ptr<PrimRef[]> refs = std::make_unique_for_overwrite<PrimRef[]>(n);
    const std::unique_ptr<PrimRef[]> sorted = std::make_unique_for_overwrite<PrimRef[]>(n);
    const BuildRange root = preparePrimRefs(prims, refs.get(), config.simd);
    ClusterTree tree;
    onThreads(config.threads, [&] {
        sortByMortonCode({refs.get(), n}, root, sorted.get());
        tree = Clustering(config, ploc, {sorted.get(), n}).run();
    });
    bvh.nodes = bvhNodesFromClusterTree(tree, {sorted.get(), n}, config, {refs.get(), n});
    fillLeafArrays(bvh, refs.get(), prims, config.threads);
    return bvh;
}

}  // namespace bvhlab
