// `gjklab names`: everything the program selects by name (algorithms with their options and
// defaults, shapes, contacts, placements, hunt objectives, bench suites), as a short listing or,
// with --json, as the document tools read (experiment/registry/names.hpp).
#pragma once

#include <iosfwd>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct NamesArgs {
  bool json = false;
};

CLI::App* add_names_command(CLI::App& app, NamesArgs& args);
int run_names_command(const NamesArgs& args, std::ostream& out);

}  // namespace gjklab::cli
