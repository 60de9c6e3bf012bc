// The process's CPU time, the clock the measuring subcommands read beside wall time. With one
// thread at work it leaves out the time a shared, loaded machine gives to other processes,
// which wall time does not; with several it sums their threads.
#pragma once

namespace bvhlab {

// CPU time of the whole process so far [ms].
double processCpuMs();

}  // namespace bvhlab
