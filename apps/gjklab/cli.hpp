// The gjklab command line, as a library so that tests can drive it in-process.
#pragma once

#include <iosfwd>

namespace gjklab::cli {

/// Runs `gjklab` with the given arguments; returns the process exit status
/// (0 success, 1 some input invalid, 2 usage error).
int run(int argc, const char* const* argv, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
