// `gjklab inspect`: an archive's provenance and summary, as text, or its summary tables alone
// as Markdown or LaTeX (booktabs) for a document.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct InspectArgs {
  std::string archive;
  std::string format = "text";  ///< a TableFormat name (experiment/run/table.hpp)
};

CLI::App* add_inspect_command(CLI::App& app, InspectArgs& args);
int run_inspect_command(const InspectArgs& args, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
