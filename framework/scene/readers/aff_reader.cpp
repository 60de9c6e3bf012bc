// AFF, the Animated File Format of BART (Lext, Assarsson and Möller): NFF extended with
// includes, triangle meshes, static and animated transforms, keyframes, animated triangles and
// an animated camera. Read into an AnimatedScene (animated_scene.h). What the specification
// leaves open is decided here as BART's reference parser (parse.c, animation.c) and its files
// decide it:
// - Tokens are separated by any whitespace; CR LF, CR and LF all end lines; '#' and '%' start
//   comments to the end of the line; a UTF-8 byte order mark is skipped; other bytes beyond
//   ASCII are taken as they are. NFF's entities
//   (v b l f p pp s c) keep their line layout (nff_entities.h); the rest is free-format.
// - `i LEVEL FILE` includes FILE (relative to the including file's folder; backslashes are
//   taken as slashes when no file has the name as written) when LEVEL is at most the detail
//   level (`d N`, 0 by default), as BART's does; an include of a file that is
//   already being read is an error (a cycle), as is a missing file. A `{` block closes in the
//   file that opens it.
// - `xs sx sy sz  ax ay az degrees  tx ty tz { ... }` transforms its block by T * R * S;
//   `x NAME { ... }` by the keyframes `k NAME`, which may come before or after it, in any file;
//   an `x` without them is an error, a `k` that nothing uses a warning; a `k NAME` read again (a
//   file included twice, as the kitchen's wheels are) replaces the earlier one for every `x NAME`,
//   as BART's lookup of the newest animation does. Nested blocks compose,
//   outer first. Spheres and cones under a transform must keep their shape: a non-uniform
//   scale in their chain is an error.
// - `k NAME { transl N ... rot N ... scale N ... visibility N ... }`: at least 4 keys each (the
//   first and last shape the tangents only, kochanek_bartels.h), times not decreasing, rotation
//   angles in degrees. Visibility keys are read and ignored (a warning): objects stay visible.
//   `k camera` moves the `v` block's eye (translation) and turns its view (rotation: looking
//   along -z, y up); `la NAME x y z [r g b]` is a light whose position follows `k NAME`'s
//   translation. Lights and the viewpoint are in world space wherever they stand, as BART's
//   parser takes them.
// - `tpa N`: N keys of a time and three vertices with normals, interpolated linearly, held
//   before the first key and after the last (BART's definition).
// - `m`: `vertices N`, optional `normals N`, optional `texturecoords N FILE`, `triangles N`
//   with vertex, then normal, then texture indices per triangle. `tt`/`ttp` are triangles whose
//   texture is not read; every texture reference is counted in one warning.
// - `fm`: ambient, diffuse and specular colour, Phong exponent, transmittance and index of
//   refraction: the diffuse colour, exponent, transmittance and index are used (the specular
//   colour is a highlight, not a mirror). `am` (ambient light) is read and not used.
// - `a START END FRAMES`: frame i at START + i (END - START) / (FRAMES - 1). A file without it
//   is a still scene at time 0 (one frame).
// - Any other keyword is an error naming file, line and keyword, as BART's parser stops on it.
#include "framework/scene/readers/nff_entities.h"
#include "framework/scene/scene_loader.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace bvhlab {
namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxIncludeDepth = 64;

// The text without a UTF-8 byte order mark (editors on Windows write one), and with lone CRs
// (old Mac line ends) as LFs, so that lines and their numbers are right; CR LF stays.
std::string asText(std::string_view raw) {
    constexpr std::string_view kByteOrderMark = "\xef\xbb\xbf";
    if (raw.starts_with(kByteOrderMark)) raw.remove_prefix(kByteOrderMark.size());
    std::string bytes(raw);
    for (size_t i = 0; i < bytes.size(); ++i) {
        if (bytes[i] == '\r' && (i + 1 == bytes.size() || bytes[i + 1] != '\n')) bytes[i] = '\n';
    }
    return bytes;
}

// The file `name` of an `i` line in `includer` names, relative to its folder; backslashes are
// taken as slashes (a file written on Windows: sub\\part.aff) when no file has the name as written.
fs::path includedPath(const fs::path& includer, std::string_view name) {
    fs::path included = includer.parent_path() / fs::path(name);
    std::error_code ec;
    if (fs::is_regular_file(included, ec) || name.find('\\') == std::string_view::npos) return included;
    std::string slashes(name);
    std::replace(slashes.begin(), slashes.end(), '\\', '/');
    return includer.parent_path() / fs::path(slashes);
}

glm::dmat4 staticTransform(const glm::dvec3& scale, const glm::dvec3& axis, double degrees,
                           const glm::dvec3& translation) {
    const glm::dmat4 r = glm::mat4_cast(quaternionFromAxisAngle(axis, glm::radians(degrees)));
    return glm::translate(glm::dmat4(1.0), translation) * r * glm::scale(glm::dmat4(1.0), scale);
}

bool isUniform(const glm::dvec3& s) {
    const double largest = std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)});
    return std::abs(s.x - s.y) <= 1e-6 * largest && std::abs(s.x - s.z) <= 1e-6 * largest;
}

// Where something was read, for errors found after the file was read.
struct Origin {
    fs::path file;
    size_t line = 0;
};

class AffReader {
public:
    explicit AffReader(AnimatedScene& out) : out_(out), scene_(out.scene) {}

    void readFile(const fs::path& file, const std::string& rawBytes);
    void finish(const fs::path& root);

private:
    void readEntity(TextParser& text, std::string_view keyword, const fs::path& file);
    void readInclude(TextParser& text, const fs::path& file);
    void readMesh(TextParser& text);
    void readKeyframes(TextParser& text, const fs::path& file);
    void readAnimatedTriangle(TextParser& text);
    void readTexturedTriangle(TextParser& text, bool withNormals);
    void openBlock(TextParser& text, const fs::path& file, TransformNode node);
    int trackNamed(const std::string& name, const Origin& use);
    Vec3 readVec3(TextParser& text, std::string_view what) {
        const float x = text.read<float>(what), y = text.read<float>(what), z = text.read<float>(what);
        return {x, y, z};
    }

    struct Mark {
        size_t vertices, triangles, spheres, cones;
    };
    Mark mark() const {
        return {scene_.positions.size(), scene_.indices.size(), scene_.spheres.size(), scene_.cones.size()};
    }
    // Puts what was appended since `from` under the current transform: into world space once
    // when no transform of the chain moves, else into a rigid part. Gives it the material.
    void place(const Mark& from, const Origin& origin);
    // Applies a static transform to what was appended between `from` and `to`.
    void bake(const Mark& from, const Mark& to, const glm::dmat4& m, const Origin& origin);
    int currentNode() const { return blocks_.empty() ? -1 : blocks_.back().node; }

    AnimatedScene& out_;
    Scene& scene_;
    struct Block {
        int node;
        Origin origin;
    };
    std::vector<Block> blocks_;
    std::vector<Origin> partOrigins_;  // per part: where its first geometry was read
    std::vector<fs::path> includeStack_;
    std::map<std::string, int> trackIndex_;
    struct TrackUse {
        bool defined = false;
        bool used = false;
        bool nonUniformScale = false;
        Origin firstUse, definition;
    };
    std::vector<TrackUse> trackUses_;
    uint32_t material_ = 0;
    int detail_ = 0;
    bool hasNormals_ = false;
    size_t textureReferences_ = 0;
    size_t visibilityBlocks_ = 0;
    PolygonTriangulator triangulator_;
    std::vector<uint32_t> corners_;
};

void AffReader::readFile(const fs::path& file, const std::string& rawBytes) {
    const std::string bytes = asText(rawBytes);
    TextParser text(file, bytes, /*hashComments=*/true);
    text.alsoCommentWith('%');
    includeStack_.push_back(fs::weakly_canonical(file));
    const size_t outerBlocks = blocks_.size();
    for (std::string_view keyword = text.next(); !keyword.empty(); keyword = text.next()) {
        if (keyword == "}") {
            if (blocks_.size() == outerBlocks) throw text.error("'}' without an open '{' block in this file");
            blocks_.pop_back();
            continue;
        }
        readEntity(text, keyword, file);
    }
    if (blocks_.size() > outerBlocks) {
        const Origin& open = blocks_.back().origin;
        throw inputError(open.file, open.line, "missing '}': the block opened here is not closed in its file");
    }
    includeStack_.pop_back();
}

void AffReader::readEntity(TextParser& text, std::string_view keyword, const fs::path& file) {
    const Mark before = mark();
    const Origin origin{file, text.line()};
    if (keyword == "v") {
        scene_.camera = nff::readViewpoint(text);
        out_.staticCamera = scene_.camera;
    } else if (keyword == "b") {
        scene_.background = nff::readVec3(text, "the background colour");
    } else if (keyword == "l") {
        scene_.lights.push_back(nff::readLight(text));
    } else if (keyword == "la") {
        const std::string name(text.nextOnLine());
        if (name.empty()) throw text.error("expected the animated light's name");
        scene_.lights.push_back(nff::readLight(text));
        out_.animatedLights.push_back({uint32_t(scene_.lights.size() - 1), trackNamed(name, origin)});
    } else if (keyword == "am") {
        readVec3(text, "the ambient light");
    } else if (keyword == "f") {
        scene_.materials.push_back(nff::readFill(text));
        material_ = uint32_t(scene_.materials.size() - 1);
    } else if (keyword == "fm") {
        readVec3(text, "the ambient colour");
        const Vec3 diffuse = readVec3(text, "the diffuse colour");
        readVec3(text, "the specular colour");
        const float shine = text.read<float>("the Phong exponent");
        const float transmission = text.read<float>("the transmittance");
        const float ior = text.read<float>("the index of refraction");
        scene_.materials.push_back(
            Material{.diffuse = diffuse, .shine = shine, .transmission = transmission, .ior = ior});
        material_ = uint32_t(scene_.materials.size() - 1);
    } else if (keyword == "s") {
        scene_.spheres.push_back(nff::readSphere(text));
    } else if (keyword == "c") {
        scene_.cones.push_back(nff::readCone(text));
    } else if (keyword == "p" || keyword == "pp") {
        nff::readPolygon(text, scene_, triangulator_, corners_, keyword == "pp", file);
        hasNormals_ |= keyword == "pp";
    } else if (keyword == "m") {
        readMesh(text);
    } else if (keyword == "tt" || keyword == "ttp") {
        readTexturedTriangle(text, keyword == "ttp");
    } else if (keyword == "tpa") {
        readAnimatedTriangle(text);
    } else if (keyword == "i") {
        readInclude(text, file);  // its entities placed themselves
        return;
    } else if (keyword == "d") {
        detail_ = text.read<int>("the detail level");
    } else if (keyword == "xs") {
        const glm::dvec3 scale = readVec3(text, "the static transform's scale");
        const glm::dvec3 axis = readVec3(text, "the static transform's rotation axis");
        const double degrees = text.read<double>("the static transform's rotation angle");
        const glm::dvec3 translation = readVec3(text, "the static transform's translation");
        openBlock(text, file, TransformNode{.local = staticTransform(scale, axis, degrees, translation)});
    } else if (keyword == "x") {
        const std::string name(text.next());
        if (name.empty() || name == "{") throw text.error("expected the animated transform's name after 'x'");
        openBlock(text, file, TransformNode{.track = trackNamed(name, origin)});
    } else if (keyword == "k") {
        readKeyframes(text, file);
    } else if (keyword == "a") {
        out_.startTime = text.read<float>("the animation's start time");
        out_.endTime = text.read<float>("the animation's end time");
        const int64_t frames = text.read<int64_t>("the animation's frame count");
        if (!std::isfinite(out_.startTime) || !std::isfinite(out_.endTime) || out_.endTime < out_.startTime)
            throw text.error("the animation must end at or after its start, both finite");
        if (frames < 1 || frames > (int64_t(1) << 30))
            throw text.error(fmt::format("{} frames: need 1 or more", frames));
        out_.frameCount = int(frames);
    } else {
        throw text.error(fmt::format("unknown AFF keyword {}", quoted(keyword)));
    }
    place(before, origin);
}

void AffReader::openBlock(TextParser& text, const fs::path& file, TransformNode node) {
    const std::string_view brace = text.next();
    if (brace != "{")
        throw text.error(fmt::format("expected '{{' to open the transform's block, found {}", quoted(brace)));
    node.parent = currentNode();
    out_.nodes.push_back(node);
    blocks_.push_back({int(out_.nodes.size() - 1), Origin{file, text.line()}});
}

int AffReader::trackNamed(const std::string& name, const Origin& use) {
    auto [it, inserted] = trackIndex_.try_emplace(name, int(out_.tracks.size()));
    if (inserted) {
        out_.tracks.emplace_back().name = name;
        trackUses_.emplace_back();
    }
    TrackUse& u = trackUses_[size_t(it->second)];
    if (!u.used && use.line > 0) {
        u.used = true;
        u.firstUse = use;
    }
    return it->second;
}

void AffReader::readInclude(TextParser& text, const fs::path& file) {
    const int level = text.read<int>("the include's detail level");
    const std::string_view name = text.next();
    if (name.empty()) throw text.error("expected the file to include");
    if (level > detail_) return;
    const fs::path included = includedPath(file, name);
    std::error_code ec;
    if (!fs::is_regular_file(included, ec))
        throw text.error(fmt::format("cannot open the included file {}", quoted(name)));
    const fs::path canonical = fs::weakly_canonical(included);
    if (std::find(includeStack_.begin(), includeStack_.end(), canonical) != includeStack_.end())
        throw text.error(fmt::format("include cycle: {} is already being read", quoted(name)));
    if (includeStack_.size() >= kMaxIncludeDepth)
        throw text.error(fmt::format("includes nested deeper than {}", kMaxIncludeDepth));
    readFile(included, readFileBytes(included));
}

void AffReader::readMesh(TextParser& text) {
    const auto readCount = [&](std::string_view what) {
        const uint64_t count = text.read<uint64_t>(what);
        if (count >= (uint64_t(1) << 31)) throw text.error(fmt::format("{} {}: too many", count, what));
        return size_t(count);
    };
    const auto expect = [&](std::string_view found, std::string_view keyword) {
        if (found != keyword)
            throw text.error(fmt::format("expected '{}' in the mesh, found {}", keyword, quoted(found)));
    };
    expect(text.next(), "vertices");
    // Lists read item by item: a count that the rest of the file cannot hold is not allocated.
    const auto readVectors = [&](std::string_view count, std::string_view item) {
        const size_t n = readCount(count);
        std::vector<Vec3> list;
        list.reserve(plausibleCount(n, text.bytesLeft(), 6));
        for (size_t k = 0; k < n; ++k) list.push_back(readVec3(text, item));
        return list;
    };
    const std::vector<Vec3> vertices = readVectors("vertex count", "a mesh vertex");
    std::vector<Vec3> normals;
    std::string_view keyword = text.next();
    if (keyword == "normals") {
        normals = readVectors("normal count", "a mesh normal");
        keyword = text.next();
    }
    size_t texcoords = 0;
    if (keyword == "texturecoords") {
        texcoords = readCount("texture coordinate count");
        if (text.next().empty()) throw text.error("expected the texture's file name");
        ++textureReferences_;
        for (size_t k = 0; k < 2 * texcoords; ++k) text.read<float>("a texture coordinate");
        keyword = text.next();
    }
    expect(keyword, "triangles");
    const size_t triangles = readCount("triangle count");
    const auto readIndex = [&](size_t count, std::string_view what) {
        const uint64_t index = text.read<uint64_t>(what);
        if (index >= count) throw text.error(fmt::format("{} {} out of range: the mesh has {}", what, index, count));
        return uint32_t(index);
    };
    // Normals have indices of their own: a vertex per (position, normal) pair.
    const uint32_t base = uint32_t(scene_.positions.size());
    std::unordered_map<uint64_t, uint32_t> pairs;
    if (normals.empty()) {
        scene_.positions.insert(scene_.positions.end(), vertices.begin(), vertices.end());
        scene_.normals.resize(scene_.positions.size(), Vec3(0.0f));
    }
    for (size_t t = 0; t < triangles; ++t) {
        glm::uvec3 v, n;
        for (int c = 0; c < 3; ++c) v[c] = readIndex(vertices.size(), "vertex index");
        if (!normals.empty())
            for (int c = 0; c < 3; ++c) n[c] = readIndex(normals.size(), "normal index");
        for (int c = 0; c < 3 && texcoords > 0; ++c) readIndex(texcoords, "texture coordinate index");
        if (normals.empty()) {
            scene_.indices.emplace_back(base + v.x, base + v.y, base + v.z);
            continue;
        }
        glm::uvec3 corner;
        for (int c = 0; c < 3; ++c) {
            const auto [it, inserted] =
                pairs.try_emplace(uint64_t(v[c]) << 32 | n[c], uint32_t(scene_.positions.size()));
            if (inserted) {
                scene_.positions.push_back(vertices[v[c]]);
                scene_.normals.push_back(normals[n[c]]);
            }
            corner[c] = it->second;
        }
        scene_.indices.push_back(corner);
    }
    hasNormals_ |= !normals.empty();
}

void AffReader::readTexturedTriangle(TextParser& text, bool withNormals) {
    if (text.next().empty()) throw text.error("expected the texture's file name");
    ++textureReferences_;
    const uint32_t first = uint32_t(scene_.positions.size());
    for (int c = 0; c < 3; ++c) {
        scene_.positions.push_back(readVec3(text, "a vertex"));
        scene_.normals.push_back(withNormals ? readVec3(text, "a vertex normal") : Vec3(0.0f));
        text.read<float>("a texture coordinate");
        text.read<float>("a texture coordinate");
    }
    scene_.indices.emplace_back(first, first + 1, first + 2);
    hasNormals_ |= withNormals;
}

void AffReader::readAnimatedTriangle(TextParser& text) {
    const uint64_t keys = text.read<uint64_t>("the animated triangle's key count");
    if (keys < 1) throw text.error("an animated triangle needs at least one key");
    AnimatedTriangle tri;
    tri.times.reserve(plausibleCount(keys, text.bytesLeft(), 38));  // a key takes 19 numbers at least
    for (uint64_t k = 0; k < keys; ++k) {
        const float time = text.read<float>("the key's time");
        if (!std::isfinite(time) || (!tri.times.empty() && time < tri.times.back()))
            throw text.error("the animated triangle's key times must be finite and not decrease");
        tri.times.push_back(time);
        std::array<Vec3, 3> p, n;
        for (int c = 0; c < 3; ++c) {
            p[size_t(c)] = readVec3(text, "a vertex");
            n[size_t(c)] = readVec3(text, "a vertex normal");
        }
        tri.positions.push_back(p);
        tri.normals.push_back(n);
    }
    const uint32_t first = uint32_t(scene_.positions.size());
    for (int c = 0; c < 3; ++c) {
        scene_.positions.push_back(tri.positions[0][size_t(c)]);
        scene_.normals.push_back(tri.normals[0][size_t(c)]);
    }
    tri.triangle = uint32_t(scene_.indices.size());
    scene_.indices.emplace_back(first, first + 1, first + 2);
    hasNormals_ = true;
    // Keys under transforms that never move are put in world space now; under a moving one
    // the triangle is interpolated in that transform's space, then carried by it.
    // Keys are put in the space of the innermost animated transform (world space when none
    // moves); that transform then carries the interpolated triangle.
    int anchor = currentNode();
    while (anchor >= 0 && out_.nodes[size_t(anchor)].track < 0) anchor = out_.nodes[size_t(anchor)].parent;
    glm::dmat4 below(1.0);
    for (int n = currentNode(); n != anchor; n = out_.nodes[size_t(n)].parent)
        below = out_.nodes[size_t(n)].local * below;
    tri.node = anchor;
    const glm::mat4 m(below);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    for (size_t k = 0; k < tri.times.size(); ++k) {
        for (size_t c = 0; c < 3; ++c) {
            tri.positions[k][c] = Vec3(m * glm::vec4(tri.positions[k][c], 1.0f));
            tri.normals[k][c] = normalMatrix * tri.normals[k][c];
        }
    }
    out_.animatedTriangles.push_back(std::move(tri));
    scene_.materialIds.resize(scene_.indices.size(), material_);
}

void AffReader::readKeyframes(TextParser& text, const fs::path& file) {
    const Origin origin{file, text.line()};
    const std::string name(text.next());
    if (name.empty() || name == "{") throw text.error("expected the name of the keyframes after 'k'");
    const std::string_view brace = text.next();
    if (brace != "{") throw text.error(fmt::format("expected '{{' after 'k {}', found {}", name, quoted(brace)));
    const int index = trackNamed(name, Origin{});
    TrackUse& use = trackUses_[size_t(index)];
    TransformTrack& track = out_.tracks[size_t(index)];
    track = TransformTrack{.name = name, .translation = {}, .rotation = {}, .scale = {}};
    use.nonUniformScale = false;
    use.defined = true;
    use.definition = origin;
    if (name == "camera") out_.cameraTrack = index;

    for (std::string_view type = text.next(); type != "}"; type = text.next()) {
        if (type.empty()) throw inputError(origin.file, origin.line, fmt::format("missing '}}' of 'k {}'", name));
        const std::string motion(type);
        const uint64_t count = text.read<uint64_t>("the keyframe count");
        if (motion == "visibility") {
            for (uint64_t k = 0; k < count; ++k) {
                text.read<float>("the visibility key's time");
                text.read<int>("the visibility flag");
            }
            ++visibilityBlocks_;
            continue;
        }
        if (motion != "transl" && motion != "rot" && motion != "scale")
            throw text.error(
                fmt::format("unknown keyframe type {}: transl, rot, scale or visibility", bvhlab::quoted(motion)));
        if (count < kMinSplineKeys)
            throw text.error(fmt::format("{} {} keyframes: a spline needs at least {}", count, motion, kMinSplineKeys));
        const bool rotation = motion == "rot";
        std::vector<PositionKey> positions;
        std::vector<RotationKey> rotations;
        double lastTime = -INFINITY;
        for (uint64_t k = 0; k < count; ++k) {
            SplineKey key;
            key.time = text.read<double>("the key's time");
            if (!std::isfinite(key.time) || key.time < lastTime)
                throw text.error(
                    fmt::format("key time {} of 'k {}': times must be finite and not decrease", key.time, name));
            lastTime = key.time;
            const glm::dvec3 value = readVec3(text, rotation ? "the rotation axis" : "the key's value");
            const double degrees = rotation ? text.read<double>("the rotation angle") : 0.0;
            key.tension = text.read<double>("the tension");
            key.continuity = text.read<double>("the continuity");
            key.bias = text.read<double>("the bias");
            if (rotation) {
                rotations.push_back(RotationKey{key, value, glm::radians(degrees)});
            } else {
                positions.push_back(PositionKey{key, value});
            }
        }
        const auto twice = [&] { return text.error(fmt::format("'{}' given twice in 'k {}'", motion, name)); };
        if (motion == "transl") {
            if (track.translation) throw twice();
            track.translation.emplace(positions);
        } else if (motion == "scale") {
            if (track.scale) throw twice();
            for (const PositionKey& key : positions) {
                if (!isUniform(key.value)) use.nonUniformScale = true;
            }
            track.scale.emplace(positions);
        } else {
            if (track.rotation) throw twice();
            track.rotation.emplace(rotations);
        }
    }
}

void AffReader::bake(const Mark& from, const Mark& to, const glm::dmat4& dm, const Origin& origin) {
    if (dm == glm::dmat4(1.0)) return;
    const glm::mat4 m(dm);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    for (size_t v = from.vertices; v < to.vertices; ++v) {
        scene_.positions[v] = Vec3(m * glm::vec4(scene_.positions[v], 1.0f));
        const Vec3 n = normalMatrix * scene_.normals[v];
        scene_.normals[v] = glm::length(n) > 0.0f ? glm::normalize(n) : Vec3(0.0f);
    }
    if (to.spheres == from.spheres && to.cones == from.cones) return;
    const glm::dvec3 scales(glm::length(glm::dvec3(dm[0])), glm::length(glm::dvec3(dm[1])),
                            glm::length(glm::dvec3(dm[2])));
    if (!isUniform(scales))
        throw inputError(origin.file, origin.line, "a sphere or cone under a non-uniform scale: it would not stay one");
    const float s = float(scales.x);
    for (size_t k = from.spheres; k < to.spheres; ++k) {
        Sphere& sphere = scene_.spheres[k];
        sphere = {Vec3(m * glm::vec4(sphere.centre, 1.0f)), sphere.radius * s};
    }
    for (size_t k = from.cones; k < to.cones; ++k) {
        Cone& cone = scene_.cones[k];
        cone = {Vec3(m * glm::vec4(cone.base, 1.0f)), cone.baseRadius * s, Vec3(m * glm::vec4(cone.apex, 1.0f)),
                cone.apexRadius * s};
    }
}

void AffReader::place(const Mark& from, const Origin& origin) {
    const Mark to = mark();
    scene_.materialIds.resize(to.triangles, material_);
    scene_.sphereMaterialIds.resize(to.spheres, material_);
    scene_.coneMaterialIds.resize(to.cones, material_);
    const int node = currentNode();
    if (node < 0 || (to.vertices == from.vertices && to.spheres == from.spheres && to.cones == from.cones)) return;
    // The static transforms below the innermost animated one (all of them when none moves) are
    // applied now, once: a part's object space is that of its animated transform.
    int anchor = node;
    while (anchor >= 0 && out_.nodes[size_t(anchor)].track < 0) anchor = out_.nodes[size_t(anchor)].parent;
    glm::dmat4 below(1.0);
    for (int n = node; n != anchor; n = out_.nodes[size_t(n)].parent) below = out_.nodes[size_t(n)].local * below;
    bake(from, to, below, origin);
    if (anchor < 0) return;
    // A rigid part, or more of the last one if this continues it under the same transform.
    const bool continues =
        !out_.parts.empty() && out_.parts.back().node == anchor && out_.parts.back().vertices.end() == from.vertices &&
        out_.parts.back().triangles.end() == from.triangles && out_.parts.back().spheres.end() == from.spheres &&
        out_.parts.back().cones.end() == from.cones;
    if (!continues) {
        RigidPart part;
        part.node = anchor;
        part.vertices.first = uint32_t(from.vertices);
        part.triangles.first = uint32_t(from.triangles);
        part.spheres.first = uint32_t(from.spheres);
        part.cones.first = uint32_t(from.cones);
        out_.parts.push_back(std::move(part));
        partOrigins_.push_back(origin);
    }
    RigidPart& part = out_.parts.back();
    part.vertices.count = uint32_t(to.vertices - part.vertices.first);
    part.triangles.count = uint32_t(to.triangles - part.triangles.first);
    part.spheres.count = uint32_t(to.spheres - part.spheres.first);
    part.cones.count = uint32_t(to.cones - part.cones.first);
    part.positions.insert(part.positions.end(), scene_.positions.begin() + std::ptrdiff_t(from.vertices),
                          scene_.positions.begin() + std::ptrdiff_t(to.vertices));
    part.normals.insert(part.normals.end(), scene_.normals.begin() + std::ptrdiff_t(from.vertices),
                        scene_.normals.begin() + std::ptrdiff_t(to.vertices));
    part.objectSpheres.insert(part.objectSpheres.end(), scene_.spheres.begin() + std::ptrdiff_t(from.spheres),
                              scene_.spheres.begin() + std::ptrdiff_t(to.spheres));
    part.objectCones.insert(part.objectCones.end(), scene_.cones.begin() + std::ptrdiff_t(from.cones),
                            scene_.cones.begin() + std::ptrdiff_t(to.cones));
}

void AffReader::finish(const fs::path& root) {
    for (size_t i = 0; i < trackUses_.size(); ++i) {
        const TrackUse& use = trackUses_[i];
        const std::string& name = out_.tracks[i].name;
        if (use.used && !use.defined)
            throw inputError(use.firstUse.file, use.firstUse.line,
                             fmt::format("unknown transform name '{}': no keyframes 'k {}' in the scene", name, name));
        if (!use.used && int(i) != out_.cameraTrack)
            scene_.report.warnings.push_back(std::string(
                inputError(use.definition.file, use.definition.line,
                           fmt::format("keyframes 'k {}' move nothing: no 'x {}' or 'la {}'", name, name, name))
                    .what()));
    }
    // The quadrics of a moving part must keep their shape in every frame.
    for (size_t p = 0; p < out_.parts.size(); ++p) {
        const RigidPart& part = out_.parts[p];
        if (part.spheres.count == 0 && part.cones.count == 0) continue;
        for (int node = part.node; node >= 0; node = out_.nodes[size_t(node)].parent) {
            const TransformNode& n = out_.nodes[size_t(node)];
            const bool uniform =
                n.track >= 0 ? !trackUses_[size_t(n.track)].nonUniformScale
                             : isUniform({glm::length(glm::dvec3(n.local[0])), glm::length(glm::dvec3(n.local[1])),
                                          glm::length(glm::dvec3(n.local[2]))});
            if (!uniform)
                throw inputError(partOrigins_[p].file, partOrigins_[p].line,
                                 "a sphere or cone under a non-uniform scale: it would not stay one");
        }
    }
    if (!hasNormals_) {
        scene_.normals.clear();
        for (RigidPart& part : out_.parts) part.normals.clear();
    }
    if (textureReferences_ > 0)
        scene_.report.warnings.push_back(fmt::format("{}: {} texture references skipped (textures are not read)",
                                                     root.string(), textureReferences_));
    if (visibilityBlocks_ > 0)
        scene_.report.warnings.push_back(fmt::format("{}: {} visibility keyframe blocks ignored (objects stay visible)",
                                                     root.string(), visibilityBlocks_));
    scene_.report.skippedTextureReferences = textureReferences_;
    scene_.finalize();
    out_.prepare();
}

}  // namespace

AnimatedScene readAnimatedAff(const std::filesystem::path& file, const std::string& bytes) {
    AnimatedScene animated;
    AffReader reader(animated);
    reader.readFile(file, bytes);
    reader.finish(file);
    return animated;
}

std::vector<std::filesystem::path> affIncludedFiles(const std::filesystem::path& file) {
    // Every `i LEVEL NAME` of every file reached, whatever the detail level: a superset of what
    // a read includes. A token `i` that is a name (`x i {`) has no LEVEL after it.
    std::vector<fs::path> files;
    std::vector<fs::path> seen = {fs::weakly_canonical(file)};
    for (size_t next = 0; next <= files.size(); ++next) {
        const fs::path current = next == 0 ? file : files[next - 1];
        const std::string bytes = asText(readFileBytes(current));
        TextParser text(current, bytes, /*hashComments=*/true);
        text.alsoCommentWith('%');
        int level;
        for (std::string_view token = text.next(); !token.empty(); token = text.next()) {
            if (token != "i" || !parseNumber(text.next(), level)) continue;
            const fs::path included = includedPath(current, text.next());
            std::error_code ec;
            if (!fs::is_regular_file(included, ec)) continue;
            const fs::path canonical = fs::weakly_canonical(included);
            if (std::find(seen.begin(), seen.end(), canonical) != seen.end()) continue;
            seen.push_back(canonical);
            files.push_back(included.lexically_normal());
        }
    }
    return files;
}

Scene readAff(const std::filesystem::path& file, const std::string& bytes) {
    return std::move(readAnimatedAff(file, bytes).scene);
}

}  // namespace bvhlab
