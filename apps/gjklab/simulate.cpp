#include "gjklab/simulate.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <ostream>

#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/simulation/scene_run.hpp"
#include "gjklab/stop_signals.hpp"

namespace gjklab::cli {

namespace {

/// Runs with the stop signals armed; prints the end of the run; the command's exit status.
int run_and_report(simulation::SceneRun& run, const SimulateArgs& args, std::ostream& out,
                   std::ostream& err) {
  if (args.threads > 0) run.setup.world->set_threads(args.threads);
  run.progress.checkpoint = args.checkpoint;
  run.progress.stop_after = args.stop_after;
  simulation::RunOutcome outcome;
  {
    const StopSignals signals;
    outcome = simulation::run_scene(run, &stop_requested());
  }
  if (outcome == simulation::RunOutcome::stopped) {
    const std::string tmp = simulation::checkpoint_path(run.archive_path);
    err << "gjklab simulate: stopped after frame " << run.progress.done << " of "
        << run.progress.target << ": " << tmp << " (continue with gjklab simulate --resume " << tmp
        << ")\n";
    return stop_requested() ? 130 : 0;
  }
  simulation::print_scene_summary(run, out);
  if (outcome == simulation::RunOutcome::not_finite) {
    err << "gjklab simulate: the state stopped being finite at frame " << run.progress.done << "\n";
    return 1;
  }
  return 0;
}

int start(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  simulation::SceneSetup setup = simulation::load_scene(args.scene);
  for (const std::string& warning : setup.warnings)
    err << "gjklab simulate: warning: " << warning << "\n";
  const std::string path = args.output.empty() ? "results/" + setup.name + ".h5" : args.output;
  if (std::filesystem::exists(path) && !args.force) {
    err << "gjklab simulate: " << path << " exists (use --force to overwrite)\n";
    return 1;
  }
  const std::int64_t target = args.frames > 0 ? args.frames : setup.frames;
  simulation::SceneRun run = simulation::new_scene_run(std::move(setup), args.scene, path, target);
  return run_and_report(run, args, out, err);
}

int resume(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  if (!args.output.empty() || args.frames > 0 || args.force) {
    err << "gjklab simulate: --resume continues the run as it was planned; --out, --frames "
           "and --force do not apply\n";
    return 1;
  }
  simulation::SceneRun run = simulation::resume_scene_run(args.resume);
  return run_and_report(run, args, out, err);
}

}  // namespace

CLI::App* add_simulate_command(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "step a scene of rigid bodies (broad phase, warm-started GJK, contacts) and "
      "write its HDF5 archive");
  cmd->add_option("scene", args.scene, "scene file (TOML)");
  cmd->add_option("--out", args.output, "archive path (default: results/<scene name>.h5)");
  cmd->add_option("--frames", args.frames, "frames to simulate (default: the file's `frames`)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{100'000'000}));
  cmd->add_flag("--force", args.force, "overwrite an existing archive");
  cmd->add_option("--resume", args.resume,
                  "continue an interrupted run (FILE.h5.tmp) from its last checkpoint");
  cmd->add_option(
         "--checkpoint", args.checkpoint,
         "frames between checkpoints (default " + std::to_string(args.checkpoint) + "; 0: none)")
      ->check(CLI::Range(std::int64_t{0}, std::int64_t{100'000'000}));
  cmd->add_option("--stop-after", args.stop_after,
                  "stop after N frames, leaving a checkpoint to --resume (runs in parts)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{100'000'000}));
  cmd->add_option("--threads", args.threads,
                  "narrow-phase threads (default: the file's [narrow_phase] threads, else 1; "
                  "the archive is the same for any count)")
      ->check(CLI::Range(1, 1024));
  return cmd;
}

int run_simulate_command(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  stop_requested() = false;
  try {
    if (args.scene.empty() == args.resume.empty()) {
      err << "gjklab simulate: give a scene file, or --resume FILE (not both)\n";
      return 1;
    }
    return args.resume.empty() ? start(args, out, err) : resume(args, out, err);
  } catch (const experiment::ConfigError& e) {
    err << "gjklab simulate: " << e.what() << "\n";
    return 1;
  } catch (const experiment::ArchiveError& e) {
    err << "gjklab simulate: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gjklab::cli
