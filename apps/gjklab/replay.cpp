#include "gjklab/replay.hpp"

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/run/driver.hpp"

namespace gjklab::cli {

namespace {

using experiment::AlgorithmRecord;
using experiment::CaseResult;

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

std::string vec(const Vec3& v) {
  return "(" + fmt("%.17g", v.x()) + ", " + fmt("%.17g", v.y()) + ", " + fmt("%.17g", v.z()) + ")";
}

/// Both clouds of the case: kept in the archive, or regenerated from the archived experiment.
experiment::CaseGeometry case_geometry(const experiment::Archive& archive, const CaseResult& c,
                                       const std::string& file) {
  if (c.geometry) return *c.geometry;
  const experiment::ExperimentConfig config =
      experiment::parse_experiment(archive.header.experiment_text, file + " (archived experiment)");
  experiment::GeneratedCase g = experiment::generate_case(config, c.record.case_id);
  experiment::CaseGeometry geometry;
  geometry.a = std::move(g.a);
  geometry.b = std::move(g.b);
  return geometry;
}

/// The case's recorded warm start (`stream` family), regenerated from the archived experiment
/// when an algorithm of the archive was warm-started; empty otherwise.
std::vector<SimplexVertex> case_warm_start(const experiment::Archive& archive, const CaseResult& c,
                                           const std::string& file) {
  bool wanted = false;
  for (const auto& options : archive.header.algorithm_options)
    for (const auto& [key, value] : options)
      wanted = wanted || (key == "warm_start" && value == "true");
  if (!wanted) return {};
  const experiment::ExperimentConfig config =
      experiment::parse_experiment(archive.header.experiment_text, file + " (archived experiment)");
  return experiment::generate_case(config, c.record.case_id).warm;
}

/// Prints a trace. The boolean walk's rows hold ‖d‖² and its separation test d·w (separated
/// when < 0), and have no closest point, weights or lower bound; after a `cycled` row the
/// distance walk's rows follow.
void print_trace(std::ostream& out, const TraceRecorder& trace, bool boolean_walk) {
  for (const GjkIterationTrace& t : trace.iterations) {
    out << "    it " << t.iteration << " " << to_string(t.step) << ": ";
    if (boolean_walk)
      out << "|d|^2 " << fmt("%.17g", t.v_norm_squared) << ", d.w " << fmt("%.17g", t.v_dot_w)
          << (t.v_dot_w < 0 ? " < 0: separated" : "") << "\n";
    else
      out << "|v|^2 " << fmt("%.17g", t.v_norm_squared) << ", v.w " << fmt("%.17g", t.v_dot_w)
          << ", lower bound " << fmt("%.17g", t.lower_bound) << "\n";
    out << "      direction " << vec(t.direction) << ", support w " << vec(t.support.w) << " (A["
        << t.support.index_a << "] - B[" << t.support.index_b << "])\n";
    out << "      simplex:";
    for (int i = 0; i < t.simplex.size(); ++i)
      out << " A[" << t.simplex[i].index_a << "]-B[" << t.simplex[i].index_b << "]"
          << (t.simplex[i].index_a < 0 ? " " + vec(t.simplex[i].w) : "")
          << (boolean_walk ? "" : " λ=" + fmt("%.6g", t.weights[i]));
    out << "\n";
    if (t.step == GjkStep::cycled) boolean_walk = false;
  }
}

bool same(double x, double y) {
  return (std::isnan(x) && std::isnan(y)) || x == y;
}

/// The differences between the rerun and the archived record ("" when equal).
std::string differences(const experiment::Outcome& now, const AlgorithmRecord& then) {
  std::string d;
  const double distance = now.distance.value_or(std::nan(""));
  if (now.intersect != then.intersect)
    d += " intersect " + std::to_string(then.intersect) + "→" + std::to_string(now.intersect);
  if (!same(distance, then.distance))
    d += " distance " + fmt("%.17g", then.distance) + "→" + fmt("%.17g", distance);
  if (now.iterations != then.iterations)
    d += " iterations " + std::to_string(then.iterations) + "→" + std::to_string(now.iterations);
  if (now.termination != then.termination)
    d += " termination " + std::string(to_string(then.termination)) + "→" +
         std::string(to_string(now.termination));
  return d;
}

/// The differences between a rerun's record and the archived one ("" when equal).
std::string differences(const AlgorithmRecord& now, const AlgorithmRecord& then) {
  experiment::Outcome o;
  o.intersect = now.intersect;
  if (!std::isnan(now.distance)) o.distance = now.distance;
  o.iterations = now.iterations;
  o.termination = now.termination;
  return differences(o, then);
}

/// A non-convex pair (nonconvex families): the case regenerated from the archived experiment
/// and evaluated again, truth, decompositions and queries, each answer compared with the
/// archive's. Returns the exit status.
int replay_mesh_case(const experiment::Archive& archive, const CaseResult& then,
                     const ReplayArgs& args, std::ostream& out, std::ostream& err) {
  const auto& rec = then.record;
  out << "case " << rec.case_id << " of " << args.archive << ": family '"
      << (rec.family < archive.header.family_names.size() ? archive.header.family_names[rec.family]
                                                          : "?")
      << "', meshes of " << rec.vertices_a << " + " << rec.vertices_b << " vertices\n";
  if (then.exact)
    out << "exact: intersect " << then.exact->intersect << ", distance "
        << fmt("%.17g", then.exact->distance) << " ("
        << (then.mesh && then.mesh->exact ? then.mesh->exact->contact : "?") << ")\n";
  experiment::ExperimentConfig config = experiment::parse_experiment(
      archive.header.experiment_text, args.archive + " (archived experiment)");
  config.timing = false;
  const CaseResult now = experiment::evaluate_case(config, then.record.case_id);
  const auto& h = archive.header;
  bool all_equal = true, any = false;
  for (std::size_t k = 0; k < h.algorithm_names.size() && k < now.algorithms.size(); ++k) {
    const std::string& label = h.algorithm_names[k];
    if (!args.algorithm.empty() && args.algorithm != label) continue;
    any = true;
    const AlgorithmRecord& r = now.algorithms[k];
    out << label << ": intersect " << r.intersect;
    if (!std::isnan(r.distance)) out << ", distance " << fmt("%.17g", r.distance);
    const experiment::MeshAlgorithmRecord& m = now.mesh->algorithms[k];
    if (m.pieces_a > 0)
      out << ", " << r.iterations << " iterations over " << m.piece_pairs_tested << " of "
          << m.piece_pairs << " piece pairs";
    else
      out << ", on the meshes";
    out << ", " << to_string(r.termination) << ", failure class "
        << to_string(then.algorithms[k].failure) << "\n";
    if (args.trace)
      out << "    (no trace: a non-convex pair's query runs over many pairs of pieces)\n";
    const std::string d = differences(r, then.algorithms[k]);
    out << "  " << (d.empty() ? "equals the archived result" : "DIFFERS from the archive:" + d)
        << "\n";
    all_equal = all_equal && d.empty();
  }
  if (!any) {
    err << "gjklab replay: no algorithm '" << args.algorithm << "' in " << args.archive << "\n";
    return 1;
  }
  return all_equal ? 0 : 1;
}

}  // namespace

CLI::App* add_replay_command(CLI::App& app, ReplayArgs& args) {
  CLI::App* cmd = app.add_subcommand("replay", "rerun an archived case, optionally traced");
  cmd->add_option("archive", args.archive, "HDF5 archive written by `gjklab run`")->required();
  // Checked as text: converted directly, "-1" would wrap to 2^64 − 1.
  cmd->add_option("--case", args.case_id, "case id")
      ->required()
      ->check(CLI::Validator(
          [](std::string& text) {
            std::uint64_t id = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
            return ec == std::errc() && end == text.data() + text.size()
                       ? std::string()
                       : "'" + text + "' is not a case id (an integer from 0 to 2^64 - 1)";
          },
          "CASE_ID"));
  cmd->add_option("--algorithm", args.algorithm,
                  "one result group (e.g. gjk-johnson or gjk-johnson@max_iterations=8)");
  cmd->add_flag("--trace", args.trace, "print every iteration (GJK algorithms)");
  return cmd;
}

int run_replay_command(const ReplayArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const experiment::Archive archive = experiment::read_archive_isolated(args.archive);
    const auto& h = archive.header;
    const CaseResult* found = nullptr;
    for (const CaseResult& r : archive.results)
      if (r.record.case_id == args.case_id) found = &r;
    if (!found) {
      err << "gjklab replay: " << args.archive << ": no case " << args.case_id
          << " (the archive has " << archive.results.size() << " cases)\n";
      return 1;
    }
    if (h.meshes) return replay_mesh_case(archive, *found, args, out, err);
    const experiment::CaseGeometry geometry = case_geometry(archive, *found, args.archive);
    const Polytope a(geometry.a), b(geometry.b);
    const std::vector<SimplexVertex> warm = case_warm_start(archive, *found, args.archive);
    const auto& rec = found->record;
    const SweptRadii radii{rec.radius_a, rec.radius_b};
    out << "case " << rec.case_id << " of " << args.archive << ": family '"
        << (rec.family < h.family_names.size() ? h.family_names[rec.family] : "?") << "', "
        << a.size() << " + " << b.size() << " vertices, size " << fmt("%.17g", rec.size);
    if (radii.any())
      out << ", swept by radii " << fmt("%.17g", radii.a) << " and " << fmt("%.17g", radii.b);
    out << "\n";
    if (found->exact)
      out << "exact: intersect " << found->exact->intersect << ", distance "
          << fmt("%.17g", found->exact->distance)
          << (radii.any() ? ", cores squared " : ", squared ") << found->exact->distance2_num << "/"
          << found->exact->distance2_den << ", " << to_string(found->exact->contact) << "\n";

    bool all_equal = true, any = false;
    for (std::size_t k = 0; k < h.algorithm_names.size(); ++k) {
      const std::string& label = h.algorithm_names[k];
      std::string name = label.substr(0, label.find('@'));
      for (const auto& [key, value] : h.algorithm_options[k])
        if (key == "algorithm") name = value;
      if (!args.algorithm.empty() && args.algorithm != label && args.algorithm != name) continue;
      any = true;
      const experiment::AlgorithmInfo* info = experiment::find_algorithm(name);
      if (!info) {
        err << "gjklab replay: algorithm '" << name << "' is not in this build of gjklab\n";
        all_equal = false;
        continue;
      }
      const experiment::AlgorithmSpec spec =
          experiment::spec_from_description(name, h.algorithm_options[k]);
      TraceRecorder trace;
      const bool traced = args.trace && experiment::can_trace(*info, radii);
      const experiment::Outcome now =
          traced ? experiment::run_algorithm_traced(*info, a, b, radii, spec.options, trace, warm)
                 : experiment::run_algorithm(*info, a, b, radii, spec.options, warm);
      const AlgorithmRecord& then = found->algorithms[k];
      out << label << ": intersect " << now.intersect;
      if (now.distance) out << ", distance " << fmt("%.17g", *now.distance);
      out << ", " << now.iterations << " iterations, " << to_string(now.termination)
          << ", failure class " << to_string(then.failure) << "\n";
      if (traced) print_trace(out, trace, info->kind == experiment::AnswerKind::boolean);
      if (args.trace && !traced) out << "    (no trace: " << name << " is not traceable)\n";
      const std::string d = differences(now, then);
      out << "  " << (d.empty() ? "equals the archived result" : "DIFFERS from the archive:" + d)
          << "\n";
      all_equal = all_equal && d.empty();
    }
    if (!any) {
      err << "gjklab replay: no algorithm '" << args.algorithm << "' in " << args.archive
          << "; it has:";
      for (const auto& l : h.algorithm_names)
        err << " " << l;
      err << "\n";
      return 1;
    }
    return all_equal ? 0 : 1;
  } catch (const std::exception& e) {
    err << "gjklab replay: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjklab::cli
