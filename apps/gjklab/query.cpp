#include "gjklab/query.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <istream>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <variant>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"
#include "gjklab/experiment/meshes/mesh_query.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/query_answers.hpp"
#include "gjklab/query_table.hpp"

namespace gjklab::cli {

namespace {

using experiment::AlgorithmInfo;
using experiment::CaseError;
using experiment::CaseOrError;
using experiment::PointCase;

/// Cases from the two point files or the cases file; file-level problems become CaseErrors.
std::vector<CaseOrError> load_cases(const QueryArgs& args, std::istream& in, std::string& source) {
  if (args.cases.empty()) {
    source = args.files[0] + " " + args.files[1];
    const std::string id = args.files[0] + " vs " + args.files[1];
    if (!args.decomposition.empty()) {
      try {
        PointCase c{id,
                    {},
                    {},
                    0,
                    0,
                    exact::read_closed_mesh(args.files[0]),
                    exact::read_closed_mesh(args.files[1])};
        c.a = c.mesh_a->vertices;
        c.b = c.mesh_b->vertices;
        return {std::move(c)};
      } catch (const std::runtime_error& e) {
        return {CaseError{id, 0, e.what()}};
      }
    }
    try {
      return {PointCase{id, experiment::read_point_file(args.files[0]),
                        experiment::read_point_file(args.files[1]), args.radius_a, args.radius_b}};
    } catch (const experiment::InputError& e) {
      return {CaseError{id, 0, e.what()}};
    }
  }
  source = args.cases;
  if (args.cases == "-") {
    std::vector<CaseOrError> out;
    std::string raw;
    for (int number = 1; std::getline(in, raw); ++number)
      if (raw.find_first_not_of(" \t\r") != std::string::npos)
        out.push_back(experiment::parse_case_line(raw, number));
    source = "<stdin>";
    return out;
  }
  try {
    return experiment::read_cases_file(args.cases);
  } catch (const experiment::InputError& e) {
    return {CaseError{args.cases, 0, e.problem()}};
  }
}

/// What every case is asked, from the options: the algorithms and mesh peers by name (an
/// unknown name is a usage error, reported on err), their options and the decomposition with
/// its options. nullopt after a usage error.
std::optional<QueryAsked> asked_of(const QueryArgs& args, std::ostream& err) {
  QueryAsked asked;
  asked.named = !args.algorithms.empty();
  if (args.algorithms.empty()) {
    // All but `sat`: its cost grows with the cube of the vertex count, so on a large cloud it
    // would run for hours; it answers when named.
    for (const AlgorithmInfo& a : experiment::algorithms())
      if (a.name != "sat") asked.algorithms.push_back(&a);
    for (const experiment::MeshPeerInfo& p : experiment::mesh_peers())
      asked.mesh_peers.push_back(&p);
  }
  for (const std::string& name : args.algorithms) {
    if (const AlgorithmInfo* a = experiment::find_algorithm(name)) {
      asked.algorithms.push_back(a);
    } else if (const experiment::MeshPeerInfo* p = experiment::find_mesh_peer(name)) {
      asked.mesh_peers.push_back(p);
    } else {
      err << "gjklab query: unknown algorithm '" << name
          << "'; valid names: " << experiment::algorithm_names() << "\n";
      std::string peers;
      for (const experiment::MeshPeerInfo& p : experiment::mesh_peers())
        peers += (peers.empty() ? "" : ", ") + std::string(p.name);
      if (!peers.empty()) err << "gjklab query: mesh cases also take: " << peers << "\n";
      return std::nullopt;
    }
  }
  experiment::AlgorithmOptions& options = asked.options;
  if (args.max_iterations > 0) options.set_max_iterations(args.max_iterations);
  options.oracle.depth = args.depth;
  options.precision = *precision_from_string(args.precision);  // checked by the parser
  asked.decomposition = &experiment::decomposition_named(
      args.decomposition.empty() ? "hull" : args.decomposition);  // checked by the parser
  for (const std::string& option : args.decomposition_options) {
    const std::size_t equals = option.find('=');
    try {
      if (equals == std::string::npos)
        throw std::invalid_argument("--decomposition-option '" + option + "': expected KEY=VALUE");
      experiment::set_decomposition_option(*asked.decomposition, asked.decomposition_options,
                                           option.substr(0, equals), option.substr(equals + 1));
    } catch (const std::invalid_argument& e) {
      err << "gjklab query: " << e.what() << "\n";
      return std::nullopt;
    }
  }

  return asked;
}

/// Every valid case's answer lines, in case order, on `threads` workers.
std::vector<std::vector<std::string>> answer_all(const std::vector<CaseOrError>& cases,
                                                 const QueryAsked& asked, int threads) {
  std::vector<std::vector<std::string>> lines(cases.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < cases.size(); i = next++) {
      if (const auto* c = std::get_if<PointCase>(&cases[i])) lines[i] = answer_lines(*c, asked);
    }
  };
  std::vector<std::thread> pool;
  const int workers = std::min<int>(threads, std::max<std::size_t>(cases.size(), 1));
  for (int t = 1; t < workers; ++t)
    pool.emplace_back(worker);
  worker();
  for (auto& t : pool)
    t.join();

  return lines;
}

}  // namespace

CLI::App* add_query_command(CLI::App& app, QueryArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "query", "answer one pair (two point files) or every case of a JSON-lines file");
  cmd->add_option("files", args.files, "point files A and B (.xyz, .off, .obj, .ply or .stl)")
      ->expected(0, 2);
  cmd->add_option("--cases", args.cases,
                  "JSON-lines cases file, one {\"id\", \"a\", \"b\"} per line ('-' for stdin)");
  cmd->add_option(
         "--algorithms", args.algorithms,
         "comma-separated algorithm names (default: all but sat): " + experiment::algorithm_names())
      ->delimiter(',');
  cmd->add_option("--max-iterations", args.max_iterations,
                  "iteration bound for every iterative algorithm (default: each one's own)")
      ->check(CLI::Range(1, 1 << 20));
  std::vector<std::string> decompositions;
  for (const auto& d : experiment::decompositions())
    decompositions.emplace_back(d.name);
  cmd->add_option("--decomposition", args.decomposition,
                  "read the two files as closed meshes (non-convex solids): the convex "
                  "algorithms answer the pieces of this decomposition (" +
                      experiment::decomposition_names() +
                      "), `exact` the solids; in a cases file, the decomposition of the mesh "
                      "sides (default hull)")
      ->check(CLI::IsMember(decompositions));
  cmd->add_option("--decomposition-option", args.decomposition_options,
                  "KEY=VALUE: an option of the decomposition (repeatable; `approximate`: HACD's "
                  "parameters, e.g. concavity=50)");
  cmd->add_option("--threads", args.threads, "worker threads")->check(CLI::Range(1, 256));
  cmd->add_flag("--depth", args.depth, "exact penetration depth for intersecting pairs (slow)");
  cmd->add_option("--radius-a", args.radius_a,
                  "sweep A's hull by a ball of this radius (sphere, capsule, rounded polytope); "
                  "a cases file gives radius_a per line")
      ->check(CLI::Range(0.0, std::numeric_limits<double>::max()));
  cmd->add_option("--format", args.format,
                  "json (default: one JSON line per answer) or table (aligned, for a terminal)")
      ->check(CLI::IsMember({"json", "table"}));
  cmd->add_option("--radius-b", args.radius_b, "sweep B's hull by a ball of this radius")
      ->check(CLI::Range(0.0, std::numeric_limits<double>::max()));
  cmd->add_option("--precision", args.precision,
                  "floating-point type of the GJK queries (gjk-bool, the distance variants, "
                  "epa): float, double (default) or long double; the point files are rounded "
                  "to it. Without --algorithms, only those queries answer")
      ->check(CLI::IsMember({"float", "double", "long double"}));
  return cmd;
}

int run_query(const QueryArgs& args, std::istream& in, std::ostream& out, std::ostream& err) {
  // CLI11's range check lets NaN through (every comparison with NaN is false).
  if (!std::isfinite(args.radius_a) || !std::isfinite(args.radius_b)) {
    err << "gjklab query: --radius-a/--radius-b must be finite numbers >= 0\n";
    return 2;
  }
  if (args.cases.empty() == (args.files.size() != 2)) {
    err << "gjklab query: give two point files or --cases FILE (not both)\n";
    return 2;
  }
  if (!args.decomposition.empty() && (args.radius_a != 0 || args.radius_b != 0)) {
    err << "gjklab query: --radius-a/--radius-b sweep point clouds, not meshes "
           "(--decomposition)\n";
    return 2;
  }
  if (!args.cases.empty() && (args.radius_a != 0 || args.radius_b != 0)) {
    err << "gjklab query: --radius-a/--radius-b apply to two point files; a cases file gives "
           "\"radius_a\" and \"radius_b\" on each line\n";
    return 2;
  }
  std::optional<QueryAsked> asked = asked_of(args, err);
  if (!asked) return 2;

  std::string source;
  const std::vector<CaseOrError> cases = load_cases(args, in, source);
  const std::vector<std::vector<std::string>> lines = answer_all(cases, *asked, args.threads);

  int status = 0;
  std::vector<std::string> output;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (const auto* e = std::get_if<CaseError>(&cases[i])) {
      err << "gjklab query: " << source;
      if (e->line > 0) err << ":" << e->line;
      err << ": case '" << e->id << "': " << e->problem << "\n";
      output.push_back(error_line(e->id, e->problem));
      status = 1;
      continue;
    }
    output.insert(output.end(), lines[i].begin(), lines[i].end());
  }
  if (args.format == "table") {
    write_answer_table(out, output);
  } else {
    for (const std::string& line : output)
      out << line << "\n";
  }
  out.flush();
  return status;
}

}  // namespace gjklab::cli
