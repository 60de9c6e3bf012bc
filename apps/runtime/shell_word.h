// A word as a POSIX shell reads it back, for the command lines bvhlab records (run_record.h)
// and the scripts it writes (`batch --slurm`).
#pragma once

#include <string>

namespace bvhlab {

// `word` itself when it holds only safe characters (letters, digits, _-+=/.,:@%), else quoted.
std::string shellWord(const std::string& word);

}  // namespace bvhlab
