#include "gjklab/query.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <istream>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <thread>
#include <type_traits>
#include <variant>

#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/registry/answer_fields.hpp"

namespace gjklab::cli {

namespace {

using experiment::AlgorithmInfo;
using experiment::CaseError;
using experiment::CaseOrError;
using experiment::PointCase;
using Json = nlohmann::ordered_json;

/// A field's value as JSON: a point or direction as [x, y, z].
Json json_of(const experiment::AnswerValue& v) {
  return std::visit(
      [](const auto& x) -> Json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, Vec3>)
          return Json::array({x.x(), x.y(), x.z()});
        else
          return Json(x);
      },
      v);
}

/// The JSON line of one algorithm's answer for one case: its id, then answer_fields.
std::string answer_line(const PointCase& c, const AlgorithmInfo& algorithm,
                        const experiment::Outcome& o, ScalarPrecision precision) {
  Json j;
  j["id"] = c.id;
  for (const auto& [key, value] :
       experiment::answer_fields(algorithm.name, o, precision, c.radius_a, c.radius_b))
    j[key] = json_of(value);
  return experiment::json_line(j);
}

std::string error_line(const std::string& id, const std::string& problem,
                       const AlgorithmInfo* algorithm = nullptr) {
  Json j;
  j["id"] = id;
  if (algorithm) j["algorithm"] = algorithm->name;
  j["error"] = problem;
  return experiment::json_line(j);
}

/// Every selected algorithm on one valid case: one output line each. Unless the algorithms
/// were named, those that answer for polytopes only skip sphere-swept cases.
std::vector<std::string> answer_case(const PointCase& c,
                                     const std::vector<const AlgorithmInfo*>& selected, bool named,
                                     const experiment::AlgorithmOptions& options) {
  std::vector<std::string> lines;
  const Polytope a(c.a), b(c.b);
  const SweptRadii radii{c.radius_a, c.radius_b};
  const bool other_precision = options.precision != ScalarPrecision::double_float;
  for (const AlgorithmInfo* algorithm : selected) {
    if (!named && !experiment::handles(*algorithm, radii)) continue;
    if (!named && other_precision && !experiment::takes_precision(*algorithm)) continue;
    try {
      lines.push_back(
          answer_line(c, *algorithm, experiment::run_algorithm(*algorithm, a, b, radii, options),
                      experiment::takes_precision(*algorithm) ? options.precision
                                                              : ScalarPrecision::double_float));
    } catch (const std::exception& e) {
      lines.push_back(error_line(c.id, e.what(), algorithm));
    }
  }
  return lines;
}

/// A JSON value as a table cell: numbers with 12 significant digits (the JSON lines keep all
/// 17), booleans as yes/no, vectors in brackets, absent as "-".
std::string cell(const Json& j) {
  if (j.is_null()) return "-";
  if (j.is_boolean()) return j.get<bool>() ? "yes" : "no";
  if (j.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.12g", j.get<double>());
    return buffer;
  }
  if (j.is_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < j.size(); ++k)
      out += (k ? " " : "") + cell(j[k]);
    return out + "]";
  }
  if (j.is_string()) return j.get<std::string>();
  return j.dump();
}

/// The answers as an aligned table, one row per answer line, for people at a terminal: the
/// columns every answer has, then the distance, depth and exact fields that some have.
void write_table(std::ostream& out, const std::vector<std::string>& lines) {
  static const std::vector<std::string> kColumns = {"id",          "algorithm", "intersect",
                                                    "distance",    "depth",     "iterations",
                                                    "termination", "method",    "error"};
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> used(kColumns.size(), false);
  for (const std::string& line : lines) {
    const Json j = Json::parse(line);
    std::vector<std::string> row;
    for (std::size_t c = 0; c < kColumns.size(); ++c) {
      const auto found = j.find(kColumns[c]);
      row.push_back(found == j.end() ? "-" : cell(*found));
      used[c] = used[c] || found != j.end();
    }
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> width(kColumns.size(), 0);
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    width[c] = kColumns[c].size();
    for (const auto& row : rows)
      width[c] = std::max(width[c], row[c].size());
  }
  auto write_row = [&](const std::vector<std::string>& row) {
    std::string text;
    for (std::size_t c = 0; c < kColumns.size(); ++c)
      if (used[c]) text += row[c] + std::string(width[c] - row[c].size() + 2, ' ');
    while (!text.empty() && text.back() == ' ')
      text.pop_back();
    out << text << "\n";
  };
  write_row(kColumns);
  for (const auto& row : rows)
    write_row(row);
}

/// Cases from the two point files or the cases file; file-level problems become CaseErrors.
std::vector<CaseOrError> load_cases(const QueryArgs& args, std::istream& in, std::string& source) {
  if (args.cases.empty()) {
    source = args.files[0] + " " + args.files[1];
    try {
      return {PointCase{args.files[0] + " vs " + args.files[1],
                        experiment::read_point_file(args.files[0]),
                        experiment::read_point_file(args.files[1]), args.radius_a, args.radius_b}};
    } catch (const experiment::InputError& e) {
      return {CaseError{args.files[0] + " vs " + args.files[1], 0, e.what()}};
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
  if (!args.cases.empty() && (args.radius_a != 0 || args.radius_b != 0)) {
    err << "gjklab query: --radius-a/--radius-b apply to two point files; a cases file gives "
           "\"radius_a\" and \"radius_b\" on each line\n";
    return 2;
  }
  std::vector<const AlgorithmInfo*> selected;
  if (args.algorithms.empty()) {
    // All but `sat`: its cost grows with the cube of the vertex count, so on a large cloud it
    // would run for hours; it answers when named.
    for (const AlgorithmInfo& a : experiment::algorithms())
      if (a.name != "sat") selected.push_back(&a);
  }
  for (const std::string& name : args.algorithms) {
    const AlgorithmInfo* a = experiment::find_algorithm(name);
    if (!a) {
      err << "gjklab query: unknown algorithm '" << name
          << "'; valid names: " << experiment::algorithm_names() << "\n";
      return 2;
    }
    selected.push_back(a);
  }
  experiment::AlgorithmOptions options;
  if (args.max_iterations > 0) options.set_max_iterations(args.max_iterations);
  options.oracle.depth = args.depth;
  options.precision = *precision_from_string(args.precision);  // checked by the parser

  std::string source;
  const std::vector<CaseOrError> cases = load_cases(args, in, source);
  std::vector<std::vector<std::string>> lines(cases.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < cases.size(); i = next++) {
      if (const auto* c = std::get_if<PointCase>(&cases[i]))
        lines[i] = answer_case(*c, selected, !args.algorithms.empty(), options);
    }
  };
  std::vector<std::thread> pool;
  const int threads = std::min<int>(args.threads, std::max<std::size_t>(cases.size(), 1));
  for (int t = 1; t < threads; ++t)
    pool.emplace_back(worker);
  worker();
  for (auto& t : pool)
    t.join();

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
    write_table(out, output);
  } else {
    for (const std::string& line : output)
      out << line << "\n";
  }
  out.flush();
  return status;
}

}  // namespace gjklab::cli
