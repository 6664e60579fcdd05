#include "gjklab/schema.hpp"

#include <CLI/CLI.hpp>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "gjklab/experiment/archive/archive.hpp"

namespace gjklab::cli {

CLI::App* add_schema_command(CLI::App& app, SchemaArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "schema",
      "print the archives' schema tables (Markdown): the results archive's as results/README.md "
      "has them, the scene archive's (scene/GROUP) as docs/scenes.md has them");
  cmd->add_option("--update", args.update,
                  "rewrite the tables between \"<!-- schema table: GROUP -->\" and \"<!-- end "
                  "schema table -->\" lines of this file");
  return cmd;
}

namespace {

void print_tables(std::ostream& out) {
  for (const char* group : {"root", "cases", "exact", "algorithms", "traces", "geometry",
                            "meshes/exact", "meshes/algorithms", "meshes/geometry", "enums",
                            "scene/root", "scene/frames", "scene/bodies", "scene/contacts",
                            "scene/audit", "scene/queries", "scene/shapes", "scene/state"})
    out << "<!-- schema table: " << group << " -->\n"
        << experiment::archive_schema_table(group) << "<!-- end schema table -->\n\n";
}

/// Rewrites the file's tables; says whether anything changed.
int update_tables(const std::string& path, std::ostream& out, std::ostream& err) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    err << "gjklab schema: cannot read " << path << "\n";
    return 1;
  }
  std::stringstream text;
  text << in.rdbuf();
  const std::string old_text = text.str();
  std::string new_text;
  try {
    new_text = experiment::with_schema_tables(old_text);
  } catch (const std::invalid_argument& e) {
    err << "gjklab schema: " << path << ": " << e.what() << "\n";
    return 1;
  }
  if (new_text == old_text) {
    out << path << ": the schema tables are up to date\n";
    return 0;
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!(file << new_text)) {
    err << "gjklab schema: cannot write " << path << "\n";
    return 1;
  }
  out << path << ": schema tables rewritten\n";
  return 0;
}

}  // namespace

int run_schema_command(const SchemaArgs& args, std::ostream& out, std::ostream& err) {
  if (args.update.empty()) {
    print_tables(out);
    return 0;
  }
  return update_tables(args.update, out, err);
}

}  // namespace gjklab::cli
