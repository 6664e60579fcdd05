// `gjklab schema`: the results archive's schema tables (Markdown), from the same descriptors
// the writer and the reader use; `--update FILE` rewrites the marked tables of a document
// (results/README.md).
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct SchemaArgs {
  std::string update;  ///< empty: print the tables
};

CLI::App* add_schema_command(CLI::App& app, SchemaArgs& args);
int run_schema_command(const SchemaArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
