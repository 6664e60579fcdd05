#include "gjklab/inspect.hpp"

#include <CLI/CLI.hpp>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/run/summary.hpp"
#include "gjklab/experiment/run/table.hpp"

namespace gjklab::cli {

namespace {

std::vector<std::string> format_names() {
  std::vector<std::string> names;
  for (const auto& row : experiment::kTableFormatNames)
    names.emplace_back(row.name);
  return names;
}

}  // namespace

CLI::App* add_inspect_command(CLI::App& app, InspectArgs& args) {
  CLI::App* cmd = app.add_subcommand("inspect", "print an archive's provenance and summary");
  cmd->add_option("archive", args.archive, "HDF5 archive written by `gjklab run`")->required();
  cmd->add_option("--format", args.format,
                  "text: provenance and summary (the default); markdown or latex: the summary "
                  "tables alone, as pipe tables or booktabs tabulars")
      ->check(CLI::IsMember(format_names()));
  return cmd;
}

namespace {

/// The archive's summaries, computed once for whichever form prints them.
struct Summaries {
  experiment::RunSummary all;
  std::vector<std::pair<std::string, experiment::RunSummary>> families;
  std::size_t kept = 0;  ///< cases that keep their geometry
};

Summaries summarise(const experiment::Archive& archive) {
  const auto& h = archive.header;
  experiment::SummaryBuilder summary(h.algorithm_names);
  experiment::FamilySummaryBuilder by_family(h.family_names, h.algorithm_names);
  Summaries s;
  for (const auto& r : archive.results) {
    summary.add(r);
    by_family.add(r);
    s.kept += r.geometry.has_value();
  }
  s.all = summary.build();
  s.families = by_family.build();
  return s;
}

void print_provenance(std::ostream& out, const std::string& path,
                      const experiment::Archive& archive) {
  const auto& h = archive.header;
  out << "archive: " << path << " (schema " << archive.schema_version << ")\n";
  out << "experiment: " << h.experiment_name << ", seed " << h.seed << ", "
      << archive.results.size() << " of " << h.cases_planned << " cases, "
      << (archive.complete ? "complete" : "INCOMPLETE") << "\n";
  out << "run: " << h.start_time << " to " << archive.end_time << "\n";
  for (const auto& [key, value] : h.provenance)
    out << key << ": " << value << "\n";
  for (std::size_t i = 0; i < h.algorithm_names.size(); ++i) {
    out << "options " << h.algorithm_names[i] << ":";
    for (const auto& [key, value] : h.algorithm_options[i])
      out << " " << key << "=" << value;
    out << "\n";
  }
  out << "\n";
}

/// The text form: provenance, the summary with its lists, per family, the oracle's methods.
/// Non-convex pairs: how the solids' truth was decided, over the cases.
void print_mesh_truth(std::ostream& out, const experiment::Archive& archive) {
  std::map<std::string, std::uint64_t> decided;
  for (const experiment::CaseResult& r : archive.results)
    if (r.mesh && r.mesh->exact) ++decided[r.mesh->exact->contact];
  out << "\nexact answers (the solids' truth: triangles that meet, containment, or the least "
         "exact triangle distance):\n";
  for (const auto& [contact, count] : decided)
    out << "  " << contact << ": " << count << "\n";
}

void print_text(std::ostream& out, const std::string& path, const experiment::Archive& archive,
                const Summaries& s) {
  print_provenance(out, path, archive);
  experiment::print_summary(out, s.all);
  if (archive.header.family_names.size() > 1) {
    out << "\nper family:\n";
    experiment::print_family_table(out, s.families);
  }
  out << s.kept << " cases keep their geometry (wrong or not converged)\n";
  if (archive.header.oracle && archive.header.meshes) {
    print_mesh_truth(out, archive);
  } else if (archive.header.oracle) {
    out << "\nexact answers (certified, or by the QP):\n";
    experiment::print_oracle_methods(
        out, experiment::oracle_method_counts(archive.results, archive.header.family_names));
  }
}

/// The summary tables alone, as the text form's tables show them, for a document.
void print_tables(std::ostream& out, const std::string& path, const experiment::Archive& archive,
                  const Summaries& s, experiment::TableFormat format) {
  experiment::Table all = experiment::summary_table(s.all);
  all.caption = path + ": per algorithm, " + std::to_string(s.all.cases) + " cases";
  experiment::render(out, all, format);
  if (archive.header.family_names.size() > 1) {
    experiment::Table families = experiment::family_table(s.families);
    families.caption = path + ": per family and algorithm";
    out << "\n";
    experiment::render(out, families, format);
  }
}

}  // namespace

int run_inspect_command(const InspectArgs& args, std::ostream& out, std::ostream& err) {
  // The command line admits only the format names; a caller in-process may pass anything.
  const auto format = experiment::table_format_from_string(args.format);
  if (!format) {
    err << "gjklab inspect: unknown format '" << args.format << "'; valid:";
    for (const std::string& name : format_names())
      err << " " << name;
    err << "\n";
    return 2;
  }
  try {
    const experiment::Archive archive = experiment::read_archive_isolated(args.archive);
    const Summaries summaries = summarise(archive);
    if (*format == experiment::TableFormat::text)
      print_text(out, args.archive, archive, summaries);
    else
      print_tables(out, args.archive, archive, summaries, *format);
    return 0;
  } catch (const std::exception& e) {
    err << "gjklab inspect: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjklab::cli
