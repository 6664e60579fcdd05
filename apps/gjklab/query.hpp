// `gjklab query`: every selected algorithm on user-supplied point clouds, as JSON lines.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace gjklab::cli {

struct QueryArgs {
  std::vector<std::string> files;       ///< two point files (A and B), or none with --cases
  std::string cases;                    ///< JSON-lines cases file ("-" for standard input)
  std::vector<std::string> algorithms;  ///< empty: all
  int max_iterations = 0;               ///< 0: each algorithm's default
  int threads = 1;
  bool depth = false;  ///< exact penetration depth for intersecting pairs
  /// Sphere-swept shapes for the two point files (a cases file gives radii per line).
  double radius_a = 0;
  double radius_b = 0;
  std::string format = "json";  ///< "json" (a line per answer) or "table" (for a terminal)
  /// Floating-point type of the GJK queries: "float", "double" or "long double".
  std::string precision = "double";
  /// A decomposition's name: the two files are closed meshes, and the convex algorithms answer
  /// its pieces (a cases file: the decomposition of its mesh sides). Empty: the files are point
  /// clouds, and mesh sides of a cases file use `hull`.
  std::string decomposition;
  /// The decomposition's options, KEY=VALUE each (e.g. concavity=50 for `approximate`).
  std::vector<std::string> decomposition_options;
};

/// Registers the `query` subcommand and its options on app.
CLI::App* add_query_command(CLI::App& app, QueryArgs& args);

/// Runs the query; returns 0, 1 if any case was invalid, 2 for a usage error.
int run_query(const QueryArgs& args, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace gjklab::cli
