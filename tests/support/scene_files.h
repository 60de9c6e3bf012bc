// Scene files for the reader tests: written into a folder of the test's own, loaded, and
// checked to fail with an InputError that names what is wrong; and the truncation and byte
// mutation sweep that every reader must survive (it loads or throws InputError, never crashes).
#pragma once

#include "framework/core/error.h"
#include "framework/scene/scene_loader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>

namespace bvhlab::test {

namespace fs = std::filesystem;

// A directory of its own under the system's temp directory, removed afterwards.
class TempDir {
public:
    TempDir() {
        static std::atomic<int> counter{0};
        path_ = fs::temp_directory_path() / fmt::format("bvhlab_readers_{}_{}", getpid(), counter++);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    fs::path write(const std::string& name, std::string_view bytes) const {
        const fs::path file = path_ / name;
        std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        return file;
    }
    fs::path writeGzipped(const std::string& name, std::string_view bytes) const {
        const fs::path file = path_ / name;
        gzFile gz = gzopen(file.c_str(), "wb");
        EXPECT_NE(gz, nullptr);
        EXPECT_EQ(gzwrite(gz, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
        EXPECT_EQ(gzclose(gz), Z_OK);
        return file;
    }
    fs::path path() const { return path_; }

private:
    fs::path path_;
};

inline Scene loadText(const std::string& name, std::string_view text) {
    TempDir dir;
    return loadScene(dir.write(name, text));
}

// Runs `load`, which must throw an InputError whose message contains every one of `parts`.
inline void expectInputError(const std::function<void()>& load, std::initializer_list<std::string_view> parts) {
    try {
        load();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& e) {
        const std::string_view message = e.what();
        for (std::string_view part : parts)
            EXPECT_NE(message.find(part), std::string_view::npos) << message << "\n  lacks: " << part;
    }
}

inline void expectLoadError(const std::string& name, std::string_view text,
                            std::initializer_list<std::string_view> parts) {
    TempDir dir;
    const fs::path file = dir.write(name, text);
    expectInputError([&] { loadScene(file); }, parts);
}

using SceneReader = Scene (*)(const fs::path&, const std::string&);

// Reads truncations and byte mutations of `valid` (which must load): each loads or throws
// InputError.
inline void fuzzReader(SceneReader read, const std::string& valid) {
    const auto loadsOrThrowsInputError = [&](const std::string& bytes) {
        try {
            Scene scene = read("fuzz", bytes);
            scene.finalize();
        } catch (const InputError&) {
        }
    };
    ASSERT_NO_THROW(read("valid", valid));
    for (size_t length = 0; length < valid.size(); ++length) loadsOrThrowsInputError(valid.substr(0, length));
    // Every byte replaced by characters that change meaning in one format or another.
    for (size_t i = 0; i < valid.size(); ++i) {
        for (const char c : {'\0', '\n', ' ', '-', '9', '#', '/', '\xff', '\x80'}) {
            std::string mutated = valid;
            mutated[i] = c;
            loadsOrThrowsInputError(mutated);
        }
    }
}

}  // namespace bvhlab::test
