#include "accel/bvh/build/ploc_builder.h"

#include "accel/bvh/build/build_threads.h"
#include "accel/bvh/build/cluster_tree.h"
#include "accel/bvh/build/morton_code.h"
#include "accel/bvh/build/radix_sort.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <limits>

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
constexpr int kMaxWindowVectors = 2 * ((256 + kLanes - 1) / kLanes);  // BVH::plocRadius <= 256

// Added to a vector of areas whose first k lanes are candidates: +inf rules out the others.
constexpr float kInf = std::numeric_limits<float>::infinity();
alignas(32) constexpr float kLanePenalty[kLanes + 1][kLanes] = {
    {kInf, kInf, kInf, kInf, kInf, kInf, kInf, kInf}, {0, kInf, kInf, kInf, kInf, kInf, kInf, kInf},
    {0, 0, kInf, kInf, kInf, kInf, kInf, kInf},       {0, 0, 0, kInf, kInf, kInf, kInf, kInf},
    {0, 0, 0, 0, kInf, kInf, kInf, kInf},             {0, 0, 0, 0, 0, kInf, kInf, kInf},
    {0, 0, 0, 0, 0, 0, kInf, kInf},                   {0, 0, 0, 0, 0, 0, 0, kInf},
    {0, 0, 0, 0, 0, 0, 0, 0}};

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
    Clustering(const BvhBuildConfig& config, std::span<const PrimRef> leafRefs)
        : radius_(uint32_t(std::clamp(config.plocRadius, 1, 256))), simd_(config.simd) {
        const uint32_t n = uint32_t(leafRefs.size());
        const uint32_t pad = (radius_ + kLanes - 1) / kLanes * kLanes + kLanes;
        tree_.leafCount = n;
        tree_.boxes.resize(2 * size_t(n) - 1);
        tree_.children.resize(2 * (size_t(n) - 1));
        ids_.resize(n), nextIds_.resize(n), neighbour_.resize(n);
        boxes_.reset(n, pad), nextBoxes_.reset(n, pad);
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, kChunk), [&](const tbb::blocked_range<uint32_t>& r) {
            for (uint32_t i = r.begin(); i < r.end(); ++i) {
                const PrimRef& p = leafRefs[i];
                tree_.boxes[i] = {{p.lower[0], p.lower[1], p.lower[2], 0.0f}, {p.upper[0], p.upper[1], p.upper[2], 0.0f}};
                boxes_.set(i, tree_.boxes[i]);
                ids_[i] = i;
            }
        });
    }

    ClusterTree run() {
        uint32_t count = tree_.leafCount, next = tree_.leafCount;
        while (count > 1) {
            if (simd_) {
                findNeighbours<simd::Floats<kLanes>>(count);
            } else {
                findNeighbours<simd::Scalar<kLanes>>(count);
            }
            count = merge(count, next);
            tree_.mergeEnds.push_back(next);
        }
        return std::move(tree_);
    }

private:
    // neighbour_[i] for every cluster i < count: the least pair (pairRank) among the radius_
    // clusters on either side, eight areas per SIMD step.
    template <typename F>
    void findNeighbours(uint32_t count) {
        const int r = int(radius_), vectorsPerSide = (r + kLanes - 1) / kLanes;
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, count, kChunk), [&](const tbb::blocked_range<uint32_t>& range) {
            F areas[kMaxWindowVectors];
            for (uint32_t i = range.begin(); i < range.end(); ++i) {
                F lo[3], hi[3];
                for (int a = 0; a < 3; ++a) lo[a] = F::broadcast(*boxes_.at(a, i)), hi[a] = F::broadcast(*boxes_.at(3 + a, i));
                F least = F::broadcast(kInf);
                // Candidates from `start` on, the first `valid` of eight.
                const auto areasFrom = [&](int64_t start, int valid) {
                    F d[3];
                    for (int a = 0; a < 3; ++a)
                        d[a] = max(hi[a], F::loadu(boxes_.at(3 + a, start))) - min(lo[a], F::loadu(boxes_.at(a, start)));
                    const F area = d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
                    return valid == kLanes ? area : area + F::loadu(kLanePenalty[valid]);
                };
                for (int k = 0; k < vectorsPerSide; ++k) {  // left: from i - r on
                    areas[k] = areasFrom(int64_t(i) - r + kLanes * k, std::min(kLanes, r - kLanes * k));
                    least = min(least, areas[k]);
                }
                for (int k = 0; k < vectorsPerSide; ++k) {  // right: from i + 1 on
                    areas[vectorsPerSide + k] = areasFrom(int64_t(i) + 1 + kLanes * k, std::min(kLanes, r - kLanes * k));
                    least = min(least, areas[vectorsPerSide + k]);
                }
                alignas(32) float lanes[kLanes];
                least.store(lanes);
                const float bestArea = *std::min_element(lanes, lanes + kLanes);
                // Among the candidates of that area (as a rule one), the least pair. Areas may
                // overflow to +inf, so a candidate is a lane inside the window and the array.
                uint64_t bestRank = ~uint64_t(0);
                uint32_t best = 0;
                for (int v = 0; v < 2 * vectorsPerSide; ++v) {
                    const int side = v / vectorsPerSide, k = v % vectorsPerSide;
                    const int valid = std::min(kLanes, r - kLanes * k);
                    for (int bits = movemask(areas[v] <= F::broadcast(bestArea)); bits != 0; bits &= bits - 1) {
                        const int lane = std::countr_zero(unsigned(bits));
                        const int64_t j = side == 0 ? int64_t(i) - r + kLanes * k + lane : int64_t(i) + 1 + kLanes * k + lane;
                        if (lane >= valid || j < 0 || j >= int64_t(count)) continue;
                        const uint64_t rank = j < i ? pairRank(uint32_t(j), i) : pairRank(i, uint32_t(j));
                        if (rank < bestRank) bestRank = rank, best = uint32_t(j);
                    }
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

    uint32_t radius_;
    bool simd_;
    ClusterTree tree_;
    std::vector<uint32_t> ids_, nextIds_;  // the clusters' nodes, in order
    ClusterBoxes boxes_, nextBoxes_;       // and their boxes
    std::vector<uint32_t> neighbour_;
    std::vector<uint32_t> chunkMerges_, chunkKept_;
};

// The PrimRefs in Morton order of their centres (ties by index: the radix sort is stable).
std::vector<PrimRef> sortByMortonCode(std::span<const PrimRef> refs, const BuildRange& root) {
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
    std::vector<PrimRef> sorted(n);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, kChunk), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t i = r.begin(); i < r.end(); ++i) sorted[i] = refs[keys[i].value];
    });
    return sorted;
}

}  // namespace

Bvh buildPlocBvh(const BvhBuildConfig& config, const PrimitiveSet& prims) {
    const size_t n = prims.validTriangles().size();
    Bvh bvh;
    if (n == 0) return bvh;
    std::vector<PrimRef> refs(n);
    const BuildRange root = preparePrimRefs(prims, refs.data(), config.simd);
    std::vector<PrimRef> sorted;
    ClusterTree tree;
    onThreads(config.threads, [&] {
        sorted = sortByMortonCode(refs, root);
        tree = Clustering(config, sorted).run();
    });
    bvh.nodes = bvhNodesFromClusterTree(tree, sorted, config, refs);
    fillLeafArrays(bvh, refs.data(), prims, config.threads);
    return bvh;
}

}  // namespace bvhlab
