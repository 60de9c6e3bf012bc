#include "tests/support/test_paths.h"

namespace bvhlab::test {

std::string sourceTree() { return BVHLAB_SOURCE_DIR; }
std::string bvhlabProgram() { return BVHLAB_BINARY; }
std::string testPlugins() { return BVHLAB_TEST_PLUGINS; }

}  // namespace bvhlab::test
