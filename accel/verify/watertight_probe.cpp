#include "accel/verify/watertight_probe.h"

#include "accel/verify/verify_rng.h"

#include <fmt/format.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>
#include <unordered_map>

namespace bvhlab::verify {
namespace {

struct PositionKey {
    std::array<uint32_t, 3> bits;
    bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
    size_t operator()(const PositionKey& k) const {
        uint64_t h = 0x9E3779B97F4A7C15ull;
        for (uint32_t b : k.bits) h = (h ^ b) * 0x100000001B3ull + (h >> 29);
        return size_t(h);
    }
};
PositionKey keyOf(const Vec3& v) {
    // + 0.0f turns -0 into +0, so that both weld together.
    return {{std::bit_cast<uint32_t>(v.x + 0.0f), std::bit_cast<uint32_t>(v.y + 0.0f),
             std::bit_cast<uint32_t>(v.z + 0.0f)}};
}

// Distance from p to segment [a, b], measured in the plane perpendicular to unit u.
double distanceAcross(const DVec3& p, const DVec3& u, const DVec3& a, const DVec3& b) {
    auto across = [&](const DVec3& q) {
        const DVec3 w = q - p;
        return w - glm::dot(w, u) * u;
    };
    const DVec3 wa = across(a), wb = across(b), e = wb - wa;
    const double l2 = glm::dot(e, e);
    const double s = l2 > 0 ? std::clamp(-glm::dot(wa, e) / l2, 0.0, 1.0) : 0.0;
    return glm::length(wa + s * e);
}

// A probe that leaked, with the calls that missed it (as they answered while counting).
struct Leak {
    size_t index;
    bool missed[4];  // findNearest, isOccluded, findNearestBatch, isOccludedBatch
};

std::string describeProbe(const WatertightProbeRay& p, const Leak& leak) {
    const Ray& r = p.ray;
    std::string missed;
    const char* calls[4] = {"findNearest", "isOccluded", "findNearestBatch", "isOccludedBatch"};
    for (int c = 0; c < 4; ++c)
        if (leak.missed[c]) missed += fmt::format("{}{} missed", missed.empty() ? "" : ", ", calls[c]);
    return fmt::format(
        "probe #{} at {} {}: org ({:.9g}, {:.9g}, {:.9g}) dir ({:.9g}, {:.9g}, {:.9g}) tmax {:.9g} "
        "aimed at ({:.17g}, {:.17g}, {:.17g}); {}",
        leak.index, p.atVertex ? "vertex" : "edge", p.feature, r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z,
        r.tmax, p.target.x, p.target.y, p.target.z, missed);
}

}  // namespace

std::string MeshTopology::summary() const {
    return fmt::format(
        "{} faces, {} vertices, {} interior edges, {} boundary, {} non-manifold, {} inconsistently "
        "wound edges: {}",
        faces.size(), vertices.size(), interiorEdges.size(), boundaryEdges, nonManifoldEdges, inconsistentEdges,
        closed() ? "closed" : "not closed");
}

MeshTopology MeshTopology::of(const Scene& scene) {
    MeshTopology m;
    std::unordered_map<PositionKey, uint32_t, PositionHash> ids;
    ids.reserve(scene.validPrimitives.size());
    auto weld = [&](const Vec3& v) {
        const auto [it, inserted] = ids.try_emplace(keyOf(v), uint32_t(m.vertices.size()));
        if (inserted) m.vertices.emplace_back(v);
        return it->second;
    };
    for (uint32_t prim : scene.validPrimitives) {
        const Triangle& t = scene.triangles[prim];
        Face f{{weld(t.v0), weld(t.v1), weld(t.v2)}, prim, DVec3(0.0)};
        if (f.v[0] == f.v[1] || f.v[1] == f.v[2] || f.v[2] == f.v[0]) continue;
        m.faces.push_back(f);
        m.bounds.extend(t.bounds());
    }

    // Normals and the signed volume (about the centre, to keep the sum well conditioned).
    const DVec3 centre = m.bounds.isEmpty() ? DVec3(0.0) : DVec3(m.bounds.center());
    for (Face& f : m.faces) {
        const DVec3 a = m.vertices[f.v[0]] - centre, b = m.vertices[f.v[1]] - centre, c = m.vertices[f.v[2]] - centre;
        m.signedVolume += glm::dot(a, glm::cross(b, c)) / 6.0;
        f.normal = glm::cross(b - a, c - a);
    }
    const double orientation = m.signedVolume < 0 ? -1.0 : 1.0;
    for (Face& f : m.faces) {
        const double l = glm::length(f.normal);
        f.normal = l > 0 && std::isfinite(l) ? orientation * f.normal / l : DVec3(0.0);
    }

    // Edges: sort the half-edges by their undirected key and look at each group.
    struct HalfEdge {
        uint32_t lo, hi, face;
        bool forward;  // lo -> hi in the face's winding
    };
    std::vector<HalfEdge> halfEdges;
    halfEdges.reserve(3 * m.faces.size());
    for (uint32_t i = 0; i < m.faces.size(); ++i)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = m.faces[i].v[e], b = m.faces[i].v[(e + 1) % 3];
            halfEdges.push_back({std::min(a, b), std::max(a, b), i, a < b});
        }
    std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
    });
    m.vertexInterior.assign(m.vertices.size(), 1);
    for (size_t i = 0; i < halfEdges.size();) {
        size_t j = i;
        while (j < halfEdges.size() && halfEdges[j].lo == halfEdges[i].lo && halfEdges[j].hi == halfEdges[i].hi) ++j;
        const size_t n = j - i;
        bool interior = false;
        if (n == 1)
            ++m.boundaryEdges;
        else if (n > 2)
            ++m.nonManifoldEdges;
        else if (halfEdges[i].forward == halfEdges[i + 1].forward)
            ++m.inconsistentEdges;
        else
            interior = true;
        if (interior)
            m.interiorEdges.push_back({halfEdges[i].lo, halfEdges[i].hi, {halfEdges[i].face, halfEdges[i + 1].face}});
        else
            m.vertexInterior[halfEdges[i].lo] = m.vertexInterior[halfEdges[i].hi] = 0;
        i = j;
    }

    m.starOffsets.assign(m.vertices.size() + 1, 0);
    for (const Face& f : m.faces)
        for (uint32_t v : f.v) ++m.starOffsets[v + 1];
    for (size_t v = 0; v < m.vertices.size(); ++v) m.starOffsets[v + 1] += m.starOffsets[v];
    m.starFaces.resize(m.starOffsets.back());
    std::vector<uint32_t> fill(m.starOffsets.begin(), m.starOffsets.end() - 1);
    for (uint32_t i = 0; i < m.faces.size(); ++i)
        for (uint32_t v : m.faces[i].v) m.starFaces[fill[v]++] = i;
    for (size_t v = 0; v < m.vertices.size(); ++v)
        if (m.starOffsets[v] == m.starOffsets[v + 1]) m.vertexInterior[v] = 0;
    for (const Face& f : m.faces)
        if (f.normal == DVec3(0.0))
            for (uint32_t v : f.v) m.vertexInterior[v] = 0;
    return m;
}

namespace {

using Rim = std::vector<std::pair<DVec3, DVec3>>;  // segments bounding the faces around a point

// A point on an interior vertex, or inside an interior edge, of a mesh.
struct ProbePoint {
    DVec3 p;
    uint32_t feature;  // the vertex or the edge
    bool atVertex;
    double localSize;  // the mean length of the vertex's edges, or the edge's length
};

// A random point on one of `vertices` (with probability vertexFraction) or `edges`, with the faces
// around it and their rim.
ProbePoint pickPoint(const MeshTopology& m, const std::vector<uint32_t>& vertices, const std::vector<uint32_t>& edges,
                     double vertexFraction, VerifyRng& rng, std::vector<uint32_t>& faces, Rim& rim) {
    faces.clear();
    rim.clear();
    const bool atVertex = edges.empty() || (!vertices.empty() && rng.uniform() < vertexFraction);
    if (atVertex) {
        const uint32_t v = vertices[rng.index(vertices.size())];
        const DVec3& p = m.vertices[v];
        double sum = 0.0;
        for (uint32_t k = m.starOffsets[v]; k < m.starOffsets[v + 1]; ++k) {
            const MeshTopology::Face& f = m.faces[m.starFaces[k]];
            faces.push_back(m.starFaces[k]);
            const int at = f.v[0] == v ? 0 : f.v[1] == v ? 1 : 2;
            const DVec3& u = m.vertices[f.v[(at + 1) % 3]];
            const DVec3& w = m.vertices[f.v[(at + 2) % 3]];
            rim.emplace_back(u, w);
            sum += glm::length(u - p);
        }
        return {p, v, true, sum / double(faces.size())};
    }
    const uint32_t edge = edges[rng.index(edges.size())];
    const MeshTopology::Edge& e = m.interiorEdges[edge];
    const DVec3 &a = m.vertices[e.a], &b = m.vertices[e.b];
    const DVec3 p = a + rng.uniform(0.01, 0.99) * (b - a);
    for (uint32_t fi : e.faces) {
        faces.push_back(fi);
        const MeshTopology::Face& f = m.faces[fi];
        const uint32_t c = f.v[0] != e.a && f.v[0] != e.b ? f.v[0] : f.v[1] != e.a && f.v[1] != e.b ? f.v[1] : f.v[2];
        rim.emplace_back(a, m.vertices[c]);
        rim.emplace_back(b, m.vertices[c]);
    }
    return {p, edge, false, glm::length(b - a)};
}

// How squarely the least front-facing of `faces` faces direction d (the smallest cosine).
double worstFacing(const MeshTopology& m, const std::vector<uint32_t>& faces, const DVec3& d) {
    double worst = 1.0;
    for (uint32_t f : faces) worst = std::min(worst, glm::dot(m.faces[f].normal, d));
    return worst;
}

// A direction within the cone where every one of `faces` is front-facing by more than sinMin;
// zero when none is found.
DVec3 frontFacingDirection(const MeshTopology& m, const std::vector<uint32_t>& faces, double sinMin, VerifyRng& rng) {
    DVec3 mean(0.0);
    for (uint32_t f : faces) mean += m.faces[f].normal;
    if (!(glm::length(mean) > 1e-9)) return DVec3(0.0);
    mean = glm::normalize(mean);
    for (int tries = 0; tries < 8; ++tries) {
        const DVec3 d = glm::normalize(mean + rng.uniform(0.0, 1.2) * rng.unitVector());
        if (worstFacing(m, faces, d) > sinMin) return d;
    }
    return DVec3(0.0);
}

// Whether the ray towards p along u, from `length` away, passes clear of the rim by more than
// the float ray and the float triangle test may stray from the point: a few roundings of the
// distances involved; 256 float epsilons leave a wide margin.
bool clearOfRim(const DVec3& p, const DVec3& u, double length, const Rim& rim) {
    constexpr double kStrayUlps = 256.0 * 0x1.0p-24;
    double reach = 0.0;
    for (const auto& [a, b] : rim) reach = std::max({reach, glm::length(a - p), glm::length(b - p)});
    const double stray = kStrayUlps * (length + reach);
    for (const auto& [a, b] : rim)
        if (distanceAcross(p, u, a, b) < stray) return false;
    return true;
}

}  // namespace

ProbeSet makeWatertightProbes(const MeshTopology& m, const ProbeOptions& o) {
    ProbeSet set;
    std::vector<uint32_t> vertices;
    for (uint32_t v = 0; v < m.vertices.size(); ++v)
        if (m.vertexInterior[v]) vertices.push_back(v);
    std::vector<uint32_t> edges;
    for (uint32_t e = 0; e < m.interiorEdges.size(); ++e) {
        const MeshTopology::Edge& edge = m.interiorEdges[e];
        if (m.faces[edge.faces[0]].normal != DVec3(0.0) && m.faces[edge.faces[1]].normal != DVec3(0.0))
            edges.push_back(e);
    }
    if (vertices.empty() && edges.empty()) return set;

    VerifyRng rng(o.seed * 0x2545F4914F6CDD1Dull + 0x1234567);
    const double radius = 0.5 * glm::length(DVec3(m.bounds.diagonal()));
    const double sinMin = std::sin(o.minDegreesFromGrazing * std::numbers::pi / 180.0);
    std::vector<uint32_t> faces;
    Rim rim;
    set.probes.reserve(o.rays);
    for (size_t r = 0; r < o.rays; ++r) {
        for (int attempt = 0; attempt < o.maxAttemptsPerRay; ++attempt) {
            ++set.candidates;
            const ProbePoint point = pickPoint(m, vertices, edges, o.vertexFraction, rng, faces, rim);
            const DVec3 out = frontFacingDirection(m, faces, sinMin, rng);
            if (out == DVec3(0.0)) continue;

            const double lo = o.minDistance * point.localSize, hi = std::max(o.maxDistance * radius, lo * 1.0001);
            if (!(lo > 0) || !std::isfinite(hi)) continue;
            const double distance = rng.logUniform(lo, hi);
            const Vec3 org(point.p + distance * out);
            if (!isFinite(org)) continue;
            const DVec3 toP = point.p - DVec3(org);
            const double length = glm::length(toP);
            if (!(length > 0)) continue;
            const DVec3 u = toP / length;
            if (worstFacing(m, faces, -u) <= sinMin) continue;  // the rounded origin moved the ray too far
            if (!clearOfRim(point.p, u, length, rim)) continue;

            const Ray ray{org, Vec3(u), 0.0f, float(o.tmaxFactor * length)};
            set.probes.push_back({ray, point.p, point.feature, point.atVertex});
            break;
        }
    }
    set.rejected = set.candidates - set.probes.size();
    return set;
}

LeakStats countLeaks(const Accelerator& accel, std::span<const WatertightProbeRay> probes, int threads,
                     size_t maxExamples) {
    struct Partial {
        LeakStats stats;
        std::vector<Leak> leaked;  // for the examples
    };
    tbb::enumerable_thread_specific<Partial> partials;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, probes.size(), 1024), [&](const tbb::blocked_range<size_t>& range) {
                Partial& local = partials.local();
                QueryCounters counters;
                const size_t n = range.size();
                std::vector<Ray> rays(n);
                for (size_t i = 0; i < n; ++i) rays[i] = probes[range.begin() + i].ray;
                // The batch calls under both hints: a structure may trace each by another path.
                std::vector<Hit> hits(n), coherentHits(n);
                std::vector<uint8_t> occluded(n), coherentOccluded(n);
                accel.findNearestBatch(rays, hits, counters, {}, RayCoherence::Incoherent);
                accel.isOccludedBatch(rays, occluded, counters, {}, RayCoherence::Incoherent);
                accel.findNearestBatch(rays, coherentHits, counters, {}, RayCoherence::Coherent);
                accel.isOccludedBatch(rays, coherentOccluded, counters, {}, RayCoherence::Coherent);
                for (size_t i = range.begin(); i < range.end(); ++i) {
                    const WatertightProbeRay& p = probes[i];
                    Hit hit;
                    const bool missed = !accel.findNearest(p.ray, hit, counters);
                    const bool notOccluded = !accel.isOccluded(p.ray, counters);
                    LeakStats& s = local.stats;
                    ++s.rays;
                    ++(p.atVertex ? s.vertexRays : s.edgeRays);
                    if (missed) {
                        ++s.leaks;
                        ++(p.atVertex ? s.vertexLeaks : s.edgeLeaks);
                    }
                    if (notOccluded) ++s.occlusionLeaks;
                    const size_t k = i - range.begin();
                    const bool batchMissed = !hits[k].found() || !coherentHits[k].found();
                    const bool batchNotOccluded = occluded[k] == 0 || coherentOccluded[k] == 0;
                    s.batchLeaks += batchMissed;
                    s.batchOcclusionLeaks += batchNotOccluded;
                    if ((missed || notOccluded || batchMissed || batchNotOccluded) && local.leaked.size() < maxExamples)
                        local.leaked.push_back({i, {missed, notOccluded, batchMissed, batchNotOccluded}});
                }
            });
    });
    LeakStats total;
    std::vector<Leak> leaked;
    for (const Partial& p : partials) {
        total.rays += p.stats.rays;
        total.leaks += p.stats.leaks;
        total.edgeRays += p.stats.edgeRays;
        total.edgeLeaks += p.stats.edgeLeaks;
        total.vertexRays += p.stats.vertexRays;
        total.vertexLeaks += p.stats.vertexLeaks;
        total.occlusionLeaks += p.stats.occlusionLeaks;
        total.batchLeaks += p.stats.batchLeaks;
        total.batchOcclusionLeaks += p.stats.batchOcclusionLeaks;
        leaked.insert(leaked.end(), p.leaked.begin(), p.leaked.end());
    }
    std::sort(leaked.begin(), leaked.end(), [](const Leak& a, const Leak& b) { return a.index < b.index; });
    leaked.resize(std::min(leaked.size(), maxExamples));
    for (const Leak& leak : leaked) total.examples.push_back(describeProbe(probes[leak.index], leak));
    return total;
}

}  // namespace bvhlab::verify
