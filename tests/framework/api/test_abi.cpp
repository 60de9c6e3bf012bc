// The ABI a plugin is checked against (<bvhlab/abi.h>): every enumerator of a public enum and
// every virtual function of a public class of framework/api/bvhlab/ is one of its figures, and a
// virtual function's slot is read as the Itanium C++ ABI lays the table out.
#include "tests/support/test_paths.h"

#include <bvhlab/plugin.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace bvhlab::test {
namespace {

std::set<std::string> figureNames() {
    std::set<std::string> names;
    for (const AbiFigure& f : abiFigures()) names.insert(f.what);
    return names;
}

TEST(Abi, ListsEveryEnumeratorAndEveryVirtualFunctionOfThePublicHeaders) {
    const std::set<std::string> figures = figureNames();
    const std::regex enumeration(R"(enum class (\w+)[^{;]*\{([^}]*)\})");
    const std::regex enumerator(R"((?:^|,)\s*(\w+))");
    const std::regex comment(R"(//[^\n]*)");
    const std::regex classLine(R"(^(?:class|struct) (\w+))");
    const std::regex virtualFunction(R"(virtual [^(~]*\b(\w+)\()");
    size_t enumerators = 0, virtuals = 0;
    for (const auto& header : std::filesystem::directory_iterator(sourceTree() + "/framework/api/bvhlab")) {
        std::ifstream in(header.path());
        std::stringstream text;
        text << in.rdbuf();
        const std::string code = std::regex_replace(text.str(), comment, "");
        for (std::sregex_iterator e(code.begin(), code.end(), enumeration), end; e != end; ++e) {
            const std::string body = (*e)[2];
            for (std::sregex_iterator v(body.begin(), body.end(), enumerator); v != end; ++v, ++enumerators)
                EXPECT_TRUE(figures.count((*e)[1].str() + "::" + (*v)[1].str())) << (*e)[1] << "::" << (*v)[1];
        }
        std::string currentClass;
        std::istringstream lines(code);
        for (std::string line; std::getline(lines, line);) {
            std::smatch m;
            if (std::regex_search(line, m, classLine)) currentClass = m[1];
            if (std::regex_search(line, m, virtualFunction)) {
                ++virtuals;
                EXPECT_TRUE(figures.count("vtable slot of " + currentClass + "::" + m[1].str()))
                    << currentClass << "::" << m[1];
                EXPECT_TRUE(figures.count("type of " + currentClass + "::" + m[1].str()))
                    << currentClass << "::" << m[1];
            }
        }
    }
    EXPECT_GE(enumerators, 11u);
    EXPECT_GE(virtuals, 20u);
}

TEST(Abi, AVirtualFunctionsSlotIsItsPlaceInTheTable) {
    // Accelerator's virtual destructor takes the first two slots (the complete and the deleting
    // destructor), then come its functions in the order they are declared.
    EXPECT_EQ(abi::vtableSlot(&Accelerator::name), 2u);
    EXPECT_EQ(abi::vtableSlot(&Accelerator::build), 3u);
    EXPECT_EQ(abi::vtableSlot(&Accelerator::update), 4u);
    EXPECT_EQ(abi::vtableSlot(&PluginRegistrar::addAccelerator), 0u);
    EXPECT_EQ(abi::vtableSlot(&PluginRegistrar::addBuilder), 1u);
}

}  // namespace
}  // namespace bvhlab::test
