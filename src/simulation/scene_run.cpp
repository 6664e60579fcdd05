#include "gjklab/simulation/scene_run.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/simulation/recording.hpp"
#include "gjklab/simulation/scene_audit.hpp"
#include "scene_checkpoint.hpp"

namespace gjklab::simulation {

namespace {

/// Frames a run may be asked for (the command line's bound).
constexpr std::int64_t kMaxFrames = 100'000'000;

void write(SceneRun& run, bool finite, bool complete) {
  fill_archive(run, finite, complete);
  const std::string path = complete ? run.archive_path : checkpoint_path(run.archive_path);
  experiment::write_scene_archive(path, run.archive);
  if (complete) {
    std::error_code ec;
    std::filesystem::remove(checkpoint_path(run.archive_path), ec);
  }
}

/// The poses before a step, for the queries it logs.
std::vector<Pose> poses_of(const scene::World& w) {
  std::vector<Pose> out;
  for (const scene::RigidBody& b : w.bodies())
    out.push_back(b.pose);
  return out;
}

/// One frame: the step, with its audit and query log when due, and its rows.
void step_frame(SceneRun& run, std::int64_t frame, SceneAudit& audit,
                BroadPhaseComparison& compare) {
  SceneSetup& s = run.setup;
  experiment::SceneArchive& r = run.archive;
  scene::World& w = *s.world;
  const bool audited = s.audit_every > 0 && frame % s.audit_every == 0;
  const bool logged = s.queries_every > 0 && frame % s.queries_every == 0;
  if (audited) audit.before_step(w);
  std::vector<Pose> before;
  std::vector<scene::QueryRecord> log;
  if (logged) {
    before = poses_of(w);
    w.record_queries(&log);
  }
  const scene::StepStats st = w.step();
  w.record_queries(nullptr);
  if (audited) audit.after_step(w, frame, r.audit);
  if (logged) record_queries(before, log, frame, r.queries);
  record_frame(w, st, s.body_size, r.frames);
  if (s.compare_broad_phases) compare.run(w, r.frames);
  if (frame % s.pose_every == 0) record_poses(w, frame, r.poses);
  if (frame % s.contacts_every == 0) record_contacts(w, frame, r.contacts);
}

RunOutcome step_to_target(SceneRun& run, const std::atomic<bool>* stop) {
  BroadPhaseComparison compare;
  SceneAudit audit(run.setup.audit_depth);
  RunProgress& p = run.progress;
  const scene::World& w = *run.setup.world;
  if (p.done == 0) record_poses(w, 0, run.archive.poses);
  const std::int64_t first = p.done;
  while (p.done < p.target) {
    step_frame(run, p.done + 1, audit, compare);
    ++p.done;
    if (!w.finite()) return RunOutcome::not_finite;
    if (p.done == p.target) break;
    if ((stop && *stop) || (p.stop_after > 0 && p.done - first >= p.stop_after))
      return RunOutcome::stopped;
    if (p.checkpoint > 0 && p.done % p.checkpoint == 0) write(run, true, false);
  }
  return RunOutcome::finished;
}

/// A resumed recording must have the columns the scene records, one row per frame done.
void check_resumable(const SceneRun& run, const std::string& file) {
  const experiment::SceneFrameRows& f = run.archive.frames;
  const auto frames = static_cast<std::size_t>(run.progress.done);
  const bool compared = !run.setup.compare_broad_phases || f.all_pairs_ns.size() == frames;
  if (f.time.size() != frames || !compared)
    throw experiment::ArchiveError("archive " + file + ": frames/ does not hold the " +
                                   std::to_string(frames) + " frames the run reached");
  if (run.progress.target < run.progress.done || run.progress.target > kMaxFrames)
    throw experiment::ArchiveError("archive " + file + ": state/frames_target " +
                                   std::to_string(run.progress.target) + " is out of range");
}

double weighted_mean(const std::vector<double>& v, const std::vector<std::int64_t>& weights) {
  double sum = 0, n = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    sum += v[i] * static_cast<double>(weights[i]);
    n += static_cast<double>(weights[i]);
  }
  return n > 0 ? sum / n : 0;
}

/// The audit in three numbers: pairs, the share certified, and the narrow phase's largest
/// error on the pairs it made contact with (its depth against the exact signed gap).
void print_audit(const experiment::SceneAuditRows& a, std::ostream& out) {
  std::size_t certified = 0, compared = 0;
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    certified += a.certified[k];
    // The exact signed gap: −distance apart, +depth inside (when computed).
    const double exact = a.intersect[k] ? a.depth[k] : -a.distance[k];
    if (std::isnan(a.narrow_depth[k]) || std::isnan(exact)) continue;
    ++compared;
    worst = std::max(worst, std::abs(a.narrow_depth[k] - exact));
  }
  out << "\n  audit: " << a.size() << " pairs exactly, " << certified << " certified; narrow "
      << "phase vs exact on " << compared << " pairs with contacts: largest |error| " << worst;
}

}  // namespace

std::string checkpoint_path(const std::string& archive_path) {
  return archive_path + ".tmp";
}

std::string archive_path_of(const std::string& given) {
  const std::string suffix = ".tmp";
  if (given.size() > suffix.size() &&
      given.compare(given.size() - suffix.size(), suffix.size(), suffix) == 0)
    return given.substr(0, given.size() - suffix.size());
  return given;
}

SceneRun new_scene_run(SceneSetup setup, const std::string& scene_path,
                       const std::string& archive_path, std::int64_t target) {
  SceneRun run;
  run.setup = std::move(setup);
  run.scene_path = scene_path;
  run.archive_path = archive_path;
  run.progress.target = target;
  return run;
}

SceneRun resume_scene_run(const std::string& given) {
  SceneRun run;
  run.archive_path = archive_path_of(given);
  const std::string tmp = checkpoint_path(run.archive_path);
  if (!std::filesystem::exists(tmp))
    throw experiment::ArchiveError("no checkpoint " + tmp + " to resume");
  run.archive = experiment::read_scene_archive(tmp);
  if (!run.archive.state)
    throw experiment::ArchiveError("archive " + tmp + ": no state/ (not a checkpoint)");
  run.scene_path = run.archive.header.scene_file;
  // The scene as the interrupted run read it (the file may have changed since).
  run.setup = parse_scene(run.archive.header.scene_toml, run.scene_path);
  run.progress.done = static_cast<std::int64_t>(
      std::min<std::uint64_t>(run.archive.header.frames, kMaxFrames + 1));
  run.progress.target = restore_state(*run.archive.state, *run.setup.world, tmp);
  check_resumable(run, tmp);
  return run;
}

RunOutcome run_scene(SceneRun& run, const std::atomic<bool>* stop) {
  const RunOutcome outcome = step_to_target(run, stop);
  write(run, run.setup.world->finite(), outcome != RunOutcome::stopped);
  return outcome;
}

void print_scene_summary(const SceneRun& run, std::ostream& out) {
  const SceneSetup& s = run.setup;
  const experiment::SceneFrameRows& f = run.archive.frames;
  double max_pen = 0;
  for (double x : f.max_penetration)
    max_pen = std::max(max_pen, x);
  out << "scene " << s.name << ": " << s.world->bodies().size() << " bodies, " << run.progress.done
      << " frames (" << (f.time.empty() ? 0.0 : f.time.back()) << " s)\n"
      << "  max penetration / body size: " << max_pen << "\n"
      << "  mean GJK iterations: " << weighted_mean(f.iterations_mean, f.narrow_queries);
  if (s.world->settings().measure_cold)
    out << " (cold: " << weighted_mean(f.iterations_cold_mean, f.narrow_queries) << ")";
  if (s.audit_every > 0) print_audit(run.archive.audit, out);
  out << "\n  archive: " << run.archive_path << "\n";
}

}  // namespace gjklab::simulation
