// Reads a scene file, choosing the reader by extension (.obj .ply .off .nff .aff, each optionally
// .gz). Throws InputError with file and line on malformed input. An animated scene (.aff) loads
// as a still scene at its animation's start time; loadAnimatedScene gives what moves as well.
#pragma once

#include "framework/scene/animated_scene.h"
#include "framework/scene/scene.h"

#include <vector>

namespace bvhlab {

Scene loadScene(const std::filesystem::path& file);

// An animated scene (.aff, optionally .gz), at its start time. A still format is an error.
AnimatedScene loadAnimatedScene(const std::filesystem::path& file);

// True for an animated scene's format (.aff, optionally .gz), which loadAnimatedScene reads.
bool isAnimatedScene(const std::filesystem::path& file);

// True for a format whose scene can span other files (AFF's includes): a checksum of `file`
// alone does not identify its content, so the scene cache passes it by.
bool readsOtherFiles(const std::filesystem::path& file);

// The other files the scene of `file` may read, found without reading the scene (AFF: the files
// its `i` lines name at any detail level, and theirs), each once; names that are no file are
// left out. Empty for a format that reads no other files. Throws InputError if one is unreadable.
std::vector<std::filesystem::path> includedFiles(const std::filesystem::path& file);

// The file's name as loadScene reads it: without its folder and a trailing .gz (a10.obj.gz -> a10.obj).
std::filesystem::path uncompressedName(const std::filesystem::path& file);

// Throws InputError naming the file when a loaded, finalized scene has nothing to render (no
// primitives, all degenerate, or all of a kind we do not render). loadScene calls it; so does
// the scene cache on a hit. Scenes built in code may be empty on purpose and are not checked.
void requireSomethingToRender(const Scene& scene);

// The readers loadScene dispatches to; each takes the file's (decompressed) bytes.
Scene readObj(const std::filesystem::path& file, const std::string& bytes);
Scene readPly(const std::filesystem::path& file, const std::string& bytes);
Scene readOff(const std::filesystem::path& file, const std::string& bytes);
Scene readNff(const std::filesystem::path& file, const std::string& bytes);
// AFF reads the files it includes itself (readers/aff_reader.cpp).
Scene readAff(const std::filesystem::path& file, const std::string& bytes);
AnimatedScene readAnimatedAff(const std::filesystem::path& file, const std::string& bytes);
std::vector<std::filesystem::path> affIncludedFiles(const std::filesystem::path& file);

// The whole file as bytes, gunzipped when it is gzip-compressed.
std::string readFileBytes(const std::filesystem::path& file);

}  // namespace bvhlab
