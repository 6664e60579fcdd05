#include "gjklab/experiment/run/driver.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <thread>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithm_options.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/registry/certified.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/meshes/mesh_cases.hpp"
#include "gjklab/experiment/run/judging.hpp"
#include "gjklab/experiment/run/provenance.hpp"
#include "gjklab/experiment/run/ranks.hpp"
#include "result_codec.hpp"
#include "rounds.hpp"

namespace gjklab::experiment {

namespace {

using Clock = std::chrono::steady_clock;

/// Cases evaluated in parallel before the batch is written in case order.
constexpr std::uint64_t kBatchCases = 512;

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Median wall time of `repetitions` runs of one query, in ns.
double time_query(const AlgorithmInfo& algorithm, const Polytope& a, const Polytope& b,
                  const SweptRadii& radii, const AlgorithmOptions& options, int repetitions,
                  std::span<const SimplexVertex> warm) {
  std::vector<double> ns;
  ns.reserve(repetitions);
  for (int r = 0; r < repetitions; ++r) {
    const auto start = Clock::now();
    const Outcome o = run_algorithm(algorithm, a, b, radii, options, warm);
    const auto stop = Clock::now();
    if (o.iterations < 0) break;  // keeps the call from being optimised away
    ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count());
  }
  return median(std::move(ns));
}

/// A value rounded to the precision and back to double (exact both ways for float; long
/// double holds every double, so that precision changes nothing).
double rounded_to(ScalarPrecision p, double x) {
  return p == ScalarPrecision::single_float ? static_cast<double>(static_cast<float>(x)) : x;
}

/// The exact answers of a case's pair as the queries in other precisions see it (clouds and
/// radii rounded to the precision): long double holds every double, so its inputs are the
/// case's own; float's are computed once per case through the certificates (an O(n) check of
/// gjk-johnson's and EPA's answers, the QP only where none holds).
class RoundedExact {
 public:
  /// Distance and depth (NaN where the pair does not intersect or when not computed).
  struct Answer {
    double distance = std::numeric_limits<double>::quiet_NaN();
    double depth = std::numeric_limits<double>::quiet_NaN();
  };

  RoundedExact(const ExperimentConfig& config, std::span<const Vec3> a, std::span<const Vec3> b,
               const SweptRadii& radii, const std::optional<exact::OracleAnswer>& exact)
      : config_(config), a_(a), b_(b), radii_(radii), exact_(exact) {}

  /// NaN where the rounded clouds are not valid polytopes (coordinates beyond float's range).
  Answer answer(ScalarPrecision p) {
    if (p != ScalarPrecision::single_float) {
      if (exact_ && !(exact_->intersect && !exact_->depth))
        return {exact_->distance, exact_->depth.value_or(std::numeric_limits<double>::quiet_NaN())};
      if (!same_inputs_) same_inputs_ = solve(ScalarPrecision::long_double);
      return *same_inputs_;
    }
    if (!in_float_) in_float_ = solve(ScalarPrecision::single_float);
    return *in_float_;
  }

 private:
  /// The exact answer, with the depth of an intersecting pair, of the inputs rounded to p.
  Answer solve(ScalarPrecision p) const {
    auto rounded = [&](std::span<const Vec3> cloud) {
      std::vector<Vec3> out;
      out.reserve(cloud.size());
      for (const Vec3& x : cloud)
        out.emplace_back(rounded_to(p, x.x()), rounded_to(p, x.y()), rounded_to(p, x.z()));
      return out;
    };
    const std::vector<Vec3> ra = rounded(a_), rb = rounded(b_);
    if (!describe_invalid_cloud(ra).empty() || !describe_invalid_cloud(rb).empty()) return {};
    const SweptRadii r{rounded_to(p, radii_.a), rounded_to(p, radii_.b)};
    const exact::OracleAnswer e =
        solve_certified(Polytope(ra), Polytope(rb), r, config_.oracle_options(true)).answer;
    return {e.distance, e.depth.value_or(std::numeric_limits<double>::quiet_NaN())};
  }

  const ExperimentConfig& config_;
  std::span<const Vec3> a_, b_;
  SweptRadii radii_;
  const std::optional<exact::OracleAnswer>& exact_;
  std::optional<Answer> same_inputs_, in_float_;
};

class Progress {
 public:
  Progress(std::ostream* out, bool live, std::uint64_t total)
      : out_(out), live_(live), total_(total), start_(Clock::now()), last_(start_) {}

  void update(std::uint64_t done, bool final = false) {
    if (!out_) return;
    const auto now = Clock::now();
    const double since_last = std::chrono::duration<double>(now - last_).count();
    if (!final && since_last < (live_ ? 0.25 : 10.0)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0;
    const double left = rate > 0 ? static_cast<double>(total_ - done) / rate : 0;
    char line[160];
    std::snprintf(line, sizeof line, "%llu/%llu cases (%.1f%%), %.0f cases/s, %.0f s left",
                  static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                  total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0,
                  rate, left);
    if (live_) {
      *out_ << "\r" << line << "\x1b[K" << (final ? "\n" : "") << std::flush;
    } else {
      *out_ << line << "\n" << std::flush;
    }
  }

 private:
  std::ostream* out_;
  bool live_;
  std::uint64_t total_;
  Clock::time_point start_, last_;
};

ArchiveHeader archive_header(const ExperimentConfig& config, std::uint64_t cases) {
  ArchiveHeader h;
  h.experiment_name = config.name;
  h.experiment_text = config.text;
  h.seed = config.seed;
  h.cases_planned = cases;
  h.start_time = utc_now();
  h.provenance = build_provenance();
  h.family_names = config.result_family_names();
  for (const AlgorithmSpec& a : config.algorithms) {
    h.algorithm_names.push_back(a.label);
    // The registry name first: a label need not contain it.
    auto options = describe_options(a);
    options.insert(options.begin(), {"algorithm", a.name});
    if (a.decomposition) {
      const auto decomposition = describe_decomposition(*a.decomposition, a.decomposition_options);
      options.insert(options.end(), decomposition.begin(), decomposition.end());
    }
    h.algorithm_options.push_back(std::move(options));
  }
  h.oracle = config.oracle;
  h.touching_band = config.touching_band;
  h.trace_mode = config.trace;
  h.meshes = config.has_nonconvex_families();
  return h;
}

}  // namespace

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

CaseResult evaluate_case(const ExperimentConfig& config, std::uint64_t case_id) {
  GeneratedCase generated = generate_case(config, case_id);
  if (generated.mesh_a) return evaluate_mesh_case(config, std::move(generated));
  CaseResult result;
  result.record = generated.record;
  const Polytope a(generated.a), b(generated.b);
  const SweptRadii radii{generated.record.radius_a, generated.record.radius_b};
  const double size = generated.record.size;
  const double band = config.touching_band * size;

  std::optional<exact::OracleAnswer> answer;
  if (config.oracle) {
    // A penetration-depth algorithm is judged against the exact depth, so it is computed for
    // every pair when one is listed.
    const bool depth_algorithm =
        std::any_of(config.algorithms.begin(), config.algorithms.end(),
                    [](const AlgorithmSpec& s) { return find_algorithm(s.name)->depth; });
    answer =
        solve_certified(a, b, radii, config.oracle_options(config.depth || depth_algorithm)).answer;
    result.exact = exact_record(*answer, band);
  }
  std::vector<Outcome> outcomes;
  RoundedExact rounded_exact(config, generated.a, generated.b, radii, answer);
  for (const AlgorithmSpec& spec : config.algorithms) {
    const AlgorithmInfo& algorithm = *find_algorithm(spec.name);
    outcomes.push_back(run_algorithm(algorithm, a, b, radii, spec.options, generated.warm));
    result.algorithms.push_back(algorithm_record(outcomes.back()));
    if (result.exact) judge(result.algorithms.back(), outcomes.back(), *result.exact, size);
    if (result.exact && spec.options.precision != ScalarPrecision::double_float) {
      const RoundedExact::Answer rounded = rounded_exact.answer(spec.options.precision);
      result.algorithms.back().rounded_exact_distance = rounded.distance;
      result.algorithms.back().rounded_exact_depth = rounded.depth;
    }
    add_witnesses(result.algorithms.back(), outcomes.back(), answer ? &*answer : nullptr,
                  generated.a, generated.b);
    if (config.timing)
      result.algorithms.back().time_ns =
          time_query(algorithm, a, b, radii, spec.options, config.repetitions, generated.warm);
  }
  if (answer && needs_exact_depth(*answer, result.algorithms)) {
    answer = solve_certified(a, b, radii, config.oracle_options(true)).answer;
    result.exact = exact_record(*answer, band);
    for (std::size_t i = 0; i < outcomes.size(); ++i)
      judge(result.algorithms[i], outcomes[i], *result.exact, size);
  }
  for (AlgorithmRecord& r : result.algorithms)
    r.failure = classify_failure(r, result.exact ? &*result.exact : nullptr, config.touching_band);
  if (config.trace != TraceMode::none) {
    // Tracing runs the same arithmetic, so the traced rerun repeats the recorded answer.
    result.traces.resize(config.algorithms.size());
    for (std::size_t i = 0; i < config.algorithms.size(); ++i) {
      const AlgorithmInfo& algorithm = *find_algorithm(config.algorithms[i].name);
      const bool wanted =
          config.trace == TraceMode::all || result.algorithms[i].failure != FailureClass::none;
      if (!wanted || !can_trace(algorithm, radii)) continue;
      TraceRecorder recorder;
      run_algorithm_traced(algorithm, a, b, radii, config.algorithms[i].options, recorder,
                           generated.warm);
      result.traces[i] = std::move(recorder.iterations);
    }
  }
  if (worth_keeping(result, config.touching_band)) {
    result.geometry.emplace();
    result.geometry->a = std::move(generated.a);
    result.geometry->b = std::move(generated.b);
  }
  return result;
}

namespace {

/// The run loop shared by a fresh run and a resumed one, on one process or on every rank of a
/// distributed run: evaluates cases [first, total) in rounds of options.checkpoint_cases,
/// appends each round in case order and checkpoints the archive (writer and prior: rank 0
/// only). Stops early (archive incomplete) on a stop request or at options.stop_after.
RunReport run_cases(const ExperimentConfig& config, const RunOptions& options,
                    ArchiveWriter* writer, std::span<const CaseResult> prior, std::uint64_t first,
                    std::uint64_t total) {
  RunReport report;
  const int threads = std::max(1, options.threads.value_or(config.threads));
  const std::uint64_t batch_cases = std::max<std::uint64_t>(1, options.checkpoint_cases);
  std::vector<std::string> names;
  for (const AlgorithmSpec& a : config.algorithms)
    names.push_back(a.label);
  SummaryBuilder summary(names);
  FamilySummaryBuilder by_family(config.result_family_names(), names);
  Progress progress(writer ? options.progress : nullptr, options.live_progress, total);
  const auto start = Clock::now();
  const auto rounds =
      make_rounds(config, threads, options.ranks, [stop = options.stop] { return stop && *stop; });
  const std::uint64_t first_written = first;

  double writing = 0;  // seconds spent appending rounds
  auto record = [&](std::span<const CaseResult> results) {
    if (!writer) return;
    const auto started = Clock::now();
    writer->append(results);
    writing += std::chrono::duration<double>(Clock::now() - started).count();
    for (const CaseResult& r : results) {
      summary.add(r);
      by_family.add(r);
    }
  };
  auto finish = [&](std::uint64_t written, bool complete) {
    progress.update(written, true);
    if (writer) writer->finish(utc_now(), complete);
    if (options.ranks && writer && options.progress && written > first_written) {
      // The job's serial part: no number of ranks delivers cases faster than rank 0 takes them.
      const double serial = std::max(rounds->decoding_seconds() + writing, 1e-9);
      *options.progress << "rank 0 took " << written - first_written << " cases in " << serial
                        << " s (" << rounds->decoding_seconds() << " s decoding the other ranks' "
                        << "results, " << writing << " s writing): at most "
                        << static_cast<double>(written - first_written) / serial
                        << " cases/s for any number of ranks\n";
    }
    report.output = complete || !writer
                        ? std::filesystem::path(options.output.value_or(config.output))
                        : writer->temporary_path();
    report.cases = written;
    report.complete = complete;
    report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    report.summary = summary.build();
    if (config.result_family_names().size() > 1) report.families = by_family.build();
    return report;
  };

  for (std::size_t i = 0; i < prior.size(); i += batch_cases)
    record(prior.subspan(i, std::min<std::size_t>(batch_cases, prior.size() - i)));
  writing = 0;  // the rewrite of a resumed run's cases is not the rounds' cost

  // The archive keeps its temporary name when a round throws: nothing that looks complete is
  // left behind.
  for (; first < total; first += batch_cases) {
    const std::uint64_t count = std::min(batch_cases, total - first);
    Round round = rounds->next(first, count);
    record(round.results);
    if (round.stop) return finish(first + round.results.size(), false);
    progress.update(first + count);
    if (options.stop_after && first + count >= *options.stop_after && first + count < total)
      return finish(first + count, false);
  }
  return finish(total, true);
}

}  // namespace

namespace {

/// Rank 0's setup in a distributed run (creating or reading the archive), made collective: its
/// outcome is sent to every rank, so that a failure there (an existing archive, say) ends every
/// rank with rank 0's message instead of leaving them waiting. `setup` runs on rank 0 and
/// returns the bytes the other ranks need; they receive them.
std::string shared_setup(Ranks* ranks, const std::function<std::string()>& setup) {
  if (!ranks) return setup();
  std::exception_ptr failure;
  std::string message;
  if (ranks->rank() == 0) {
    try {
      message = "+" + setup();
    } catch (const std::exception& e) {
      failure = std::current_exception();
      message = "-";
      message += e.what();
    }
  }
  message = ranks->broadcast(message);
  ranks->failure_shared = message.empty() || message.front() != '+';
  if (failure) std::rethrow_exception(failure);
  if (message.empty() || message.front() != '+') throw PeerFailure(message.substr(1));
  return message.substr(1);
}

}  // namespace

RunReport run_experiment(const ExperimentConfig& config, const RunOptions& options) {
  const std::uint64_t n_values =
      config.geometry_sweep ? config.geometry_sweep->values.size() : std::uint64_t{1};
  const std::uint64_t total = options.cases ? *options.cases * n_values : config.total_cases();
  RunOptions resolved = options;
  resolved.output = options.output.value_or(config.output);
  std::optional<ArchiveWriter> writer;
  shared_setup(options.ranks, [&] {
    ArchiveHeader header = archive_header(config, total);
    if (options.ranks)
      header.provenance.emplace_back("mpi_ranks", std::to_string(options.ranks->size()));
    writer.emplace(*resolved.output, header, options.force);
    return std::string();
  });
  return run_cases(config, resolved, writer ? &*writer : nullptr, {}, 0, total);
}

namespace {

/// The interrupted run's archive: FILE.tmp, or, when a kill left it unreadable (a write cut
/// short), the copy taken at a checkpoint.
Archive read_interrupted(const std::filesystem::path& temporary) {
  try {
    return read_archive_isolated(temporary);
  } catch (const std::exception& unreadable) {
    const std::filesystem::path copy = snapshot_path(temporary);
    if (!std::filesystem::exists(copy)) throw;
    try {
      return read_archive_isolated(copy);
    } catch (const std::exception& also) {
      throw std::runtime_error(std::string(unreadable.what()) +
                               "; its checkpoint copy too: " + also.what());
    }
  }
}

/// A resume's state on the writing process: the interrupted run read back and moved aside,
/// and a fresh archive under the temporary name to rewrite it into.
struct Resumption {
  Archive prior;
  std::filesystem::path final_path, aside, copy_aside;
  std::optional<ArchiveWriter> writer;
};

void prepare_resume(const std::filesystem::path& path, Resumption& r, const Ranks* ranks) {
  // The interrupted archive: FILE.tmp, named either way.
  std::filesystem::path temporary = path;
  if (temporary.extension() != ".tmp") temporary += ".tmp";
  if (!std::filesystem::exists(temporary))
    throw std::runtime_error(
        temporary.string() + ": no interrupted run to resume" +
        (std::filesystem::exists(path) ? " (" + path.string() + " is a finished archive)" : ""));
  r.prior = read_interrupted(temporary);
  if (r.prior.complete) throw std::runtime_error(temporary.string() + " is already complete");
  // Checked before anything is moved: a bad archived experiment leaves the files as they were.
  (void)parse_experiment(r.prior.header.experiment_text,
                         temporary.string() + " (archived experiment)");
  r.final_path = temporary;
  r.final_path.replace_extension();  // drops ".tmp"
  // The finished cases are rewritten into a fresh temporary file (identical to what an
  // uninterrupted run writes); the interrupted file is kept aside until that succeeds.
  r.aside = temporary.string() + ".partial";
  r.copy_aside = r.aside.string() + ".checkpoint";
  std::filesystem::rename(temporary, r.aside);
  if (std::filesystem::exists(snapshot_path(temporary)))
    std::filesystem::rename(snapshot_path(temporary), r.copy_aside);
  ArchiveHeader header = r.prior.header;
  header.provenance = build_provenance();
  if (ranks) header.provenance.emplace_back("mpi_ranks", std::to_string(ranks->size()));
  r.writer.emplace(r.final_path, header, /*overwrite=*/false);
}

/// A run killed after its archive was marked complete and before the rename to the final name
/// (ArchiveWriter::finish) left a complete FILE.tmp: that file is the finished archive, so the
/// resume only renames it. Single process only; nullopt when there is no such file.
std::optional<RunReport> finish_complete_temporary(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  if (temporary.extension() != ".tmp") temporary += ".tmp";
  if (!std::filesystem::exists(temporary)) return std::nullopt;
  Archive prior = read_interrupted(temporary);
  if (!prior.complete) return std::nullopt;
  std::filesystem::path final_path = temporary;
  final_path.replace_extension();
  if (std::filesystem::exists(final_path))
    throw std::runtime_error(temporary.string() + " is already complete, and " +
                             final_path.string() + " exists: keep one of them");
  std::filesystem::rename(temporary, final_path);
  std::filesystem::remove(snapshot_path(temporary));
  const ExperimentConfig config = parse_experiment(prior.header.experiment_text,
                                                   final_path.string() + " (archived experiment)");
  std::vector<std::string> names;
  for (const AlgorithmSpec& a : config.algorithms)
    names.push_back(a.label);
  SummaryBuilder summary(names);
  for (const CaseResult& result : prior.results)
    summary.add(result);
  RunReport report;
  report.output = final_path;
  report.summary = summary.build();
  report.cases = report.resumed_cases = prior.results.size();
  report.complete = true;
  return report;
}

}  // namespace

RunReport resume_experiment(const std::filesystem::path& path, const RunOptions& options) {
  if (!options.ranks)
    if (std::optional<RunReport> done = finish_complete_temporary(path)) return *done;
  Resumption r;
  // Rank 0 reads the archive; every rank needs its experiment, first case and planned total.
  const std::string plan = shared_setup(options.ranks, [&] {
    prepare_resume(path, r, options.ranks);
    codec::ByteWriter out;
    out.put<std::uint64_t>(r.prior.results.size());
    out.put<std::uint64_t>(r.prior.header.cases_planned);
    out.put_string(r.final_path.string());
    out.put_string(r.prior.header.experiment_text);
    return out.take();
  });
  codec::ByteReader in(plan);
  const auto first = in.get<std::uint64_t>();
  const auto total = in.get<std::uint64_t>();
  const std::string output = in.get_string();
  const ExperimentConfig config =
      parse_experiment(in.get_string(), output + ".tmp (archived experiment)");
  RunOptions resolved = options;
  resolved.output = output;
  const std::vector<CaseResult> finished = std::move(r.prior.results);
  RunReport report =
      run_cases(config, resolved, r.writer ? &*r.writer : nullptr, finished, first, total);
  report.resumed_cases = first;
  if (r.writer) {
    r.writer.reset();
    std::filesystem::remove(r.aside);
    std::filesystem::remove(r.copy_aside);
  }
  return report;
}

}  // namespace gjklab::experiment
