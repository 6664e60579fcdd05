#include "gjklab/cli.hpp"

#include <CLI/CLI.hpp>
#include <ostream>

#include "gjklab/experiment/provenance.hpp"

namespace gjklab::cli {

int run(int argc, const char* const* argv, std::istream& /*in*/, std::ostream& out,
        std::ostream& err) {
  CLI::App app{"gjklab: a research testbed for GJK-family collision and distance queries"};
  app.require_subcommand(1);
  auto* version = app.add_subcommand("version", "print the version, build and library versions");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    out << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {
    err << "gjklab: " << e.what() << "\n" << "run 'gjklab --help' for usage\n";
    return 2;
  }
  if (version->parsed()) {
    for (const auto& [name, value] : experiment::build_provenance()) out << name << ": " << value << "\n";
  }
  return 0;
}

}  // namespace gjklab::cli
