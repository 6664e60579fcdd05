#include "gjklab/names.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/names.hpp"

namespace gjklab::cli {

using Json = nlohmann::ordered_json;

CLI::App* add_names_command(CLI::App& app, NamesArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "names",
      "list every algorithm (with its options and defaults), shape, contact, placement, "
      "hunt objective and bench suite");
  cmd->add_flag("--json", args.json,
                "print the full document as JSON (types, accepted values and meanings), for tools");
  return cmd;
}

namespace {

/// A value as an experiment file writes it: a name without quotes, a number in its shortest
/// form (0, not 0.0), a direction as [1, 0, 0].
std::string plain(const Json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_float()) return experiment::round_trip(value.get<double>());
  if (!value.is_array()) return value.dump();
  std::string text = "[";
  for (const Json& x : value) {
    if (text.size() > 1) text += ", ";
    text += plain(x);
  }
  return text + "]";
}

/// "boolean distance depth": what the algorithm answers.
std::string answers(const Json& algorithm) {
  std::string text;
  for (const auto& [what, yes] : algorithm["answers"].items())
    if (yes.get<bool>()) text += (text.empty() ? "" : " ") + what;
  return text;
}

void print_algorithms(std::ostream& out, const Json& algorithms) {
  std::size_t width = 0;
  for (const Json& a : algorithms)
    width = std::max(width, a["name"].get<std::string>().size());
  out << "algorithms (name, group, answers; then each option's default):\n";
  for (const Json& a : algorithms) {
    const std::string name = a["name"];
    out << "  " << name << std::string(width - name.size() + 2, ' ') << plain(a["group"]) << ", "
        << answers(a) << ": " << plain(a["description"]) << "\n";
    if (a["options"].empty()) continue;
    out << "   ";
    for (const Json& o : a["options"])
      out << " " << plain(o["key"]) << "=" << plain(o["default"]);
    out << "\n";
  }
}

/// "section: a, b, c", naming the entries of a list of names or of named objects.
void print_list(std::ostream& out, const std::string& section, const Json& list) {
  out << section << ":";
  const char* separator = " ";
  for (const Json& entry : list) {
    out << separator << plain(entry.is_object() ? entry["name"] : entry);
    separator = ", ";
  }
  out << "\n";
}

}  // namespace

int run_names_command(const NamesArgs& args, std::ostream& out) {
  const Json doc = experiment::names_document();
  if (args.json) {
    out << doc.dump(2) << "\n";
    return 0;
  }
  print_algorithms(out, doc["algorithms"]);
  for (const auto& [section, list] : doc.items())
    if (section != "algorithms") print_list(out, section, list);
  out << "(gjklab names --json gives each option's type, accepted values and meaning)\n";
  return 0;
}

}  // namespace gjklab::cli
