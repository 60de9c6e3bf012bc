// The trees the tests were built from and into. CMake sets them on test_paths.cpp alone, so the
// other test sources compile to the same objects in every checkout (a compiler cache shares them).
#pragma once

#include <string>

namespace bvhlab::test {

std::string sourceTree();     // the repository root
std::string bvhlabProgram();  // build/bvhlab
std::string testPlugins();    // the folder of the plugins built for the tests (build/test_plugins)

}  // namespace bvhlab::test
