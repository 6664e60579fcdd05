#include "rounds.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>

#include "gjklab/experiment/run/driver.hpp"
#include "result_codec.hpp"

namespace gjklab::experiment {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class LocalRounds final : public RoundSource {
 public:
  LocalRounds(const ExperimentConfig& config, int threads, StopCheck stopping)
      : config_(config), threads_(threads), stopping_(std::move(stopping)) {}

  Round next(std::uint64_t first, std::uint64_t count) override {
    Round round{evaluate_range(config_, threads_, first, count, stopping_), false};
    round.stop = stopping_();
    return round;
  }

 private:
  const ExperimentConfig& config_;
  int threads_;
  StopCheck stopping_;
};

/// What one rank sends rank 0 after its share of a round: a header, then its results.
struct ShareReport {
  bool stop = false;           ///< its stop flag was set
  std::uint64_t planned = 0;   ///< cases in its share
  std::uint64_t finished = 0;  ///< cases finished, the first of its share
  double seconds = 0;          ///< time spent evaluating them
  std::string error;           ///< non-empty when a case failed
  std::size_t results_at = 0;  ///< where its results start in the message
};

/// Rank 0 sends no results: it keeps its own.
std::string encode_share(const ShareReport& s, std::span<const CaseResult> done) {
  codec::ByteWriter out;
  out.put<std::uint8_t>(s.stop);
  out.put<std::uint64_t>(s.planned);
  out.put<std::uint64_t>(s.finished);
  out.put<double>(s.seconds);
  out.put_string(s.error);
  codec::encode_results(out, done);
  return out.take();
}

/// The header alone: rank 0 decides on it and tells the other ranks before it decodes the
/// results, so that they start the next round without waiting for that.
ShareReport decode_share_header(const std::string& bytes) {
  codec::ByteReader in(bytes);
  ShareReport s;
  s.stop = in.get<std::uint8_t>() != 0;
  s.planned = in.get<std::uint64_t>();
  s.finished = in.get<std::uint64_t>();
  s.seconds = in.get<double>();
  s.error = in.get_string();
  s.results_at = in.position();
  if (s.finished > s.planned)
    throw std::runtime_error("malformed result message: more cases finished than planned");
  return s;
}

std::vector<CaseResult> decode_share_results(const std::string& bytes, const ShareReport& s) {
  codec::ByteReader in(std::string_view(bytes).substr(s.results_at));
  std::vector<CaseResult> done = codec::decode_results(in);
  if (!in.done() || done.size() != s.finished)
    throw std::runtime_error("malformed result message: " + std::to_string(done.size()) +
                             " results for " + std::to_string(s.finished) + " finished cases");
  return done;
}

/// Rank 0's decision after a round, sent to every rank.
struct Decision {
  enum Kind : std::uint8_t { go, stop, failed } kind = go;
  double rank0_fraction = 0;  ///< rank 0's share of the next round
  std::string error;
};

/// Splits rounds over the ranks: contiguous ranges in rank order, so the round's finished
/// prefix is the ranks' finished cases concatenated up to the first rank that stopped early.
/// Rank 0 writes while the others evaluate the next round, so its own share is sized each round
/// for it to finish its writing and its cases when the others finish theirs.
class DistributedRounds final : public RoundSource {
 public:
  DistributedRounds(const ExperimentConfig& config, int threads, Ranks& ranks, StopCheck stopping)
      : config_(config), threads_(threads), ranks_(ranks), stopping_(std::move(stopping)) {
    rank0_fraction_ = 1.0 / ranks_.size();
  }

  double decoding_seconds() const override { return decoding_seconds_; }

  Round next(std::uint64_t first, std::uint64_t count) override {
    // On rank 0 the time since the last round is what it spent writing that round.
    const double writing = last_return_ ? seconds_since(*last_return_) : 0.0;
    const auto [begin, size] = share(ranks_.rank(), first, count);
    ShareReport mine{false, size, 0, 0, {}, 0};
    std::vector<CaseResult> done;
    const auto start = Clock::now();
    try {
      done = evaluate_range(config_, threads_, begin, size, stopping_);
    } catch (const std::exception& e) {
      mine.error = e.what();
    }
    mine.seconds = seconds_since(start);
    mine.finished = done.size();
    mine.stop = stopping_();
    const bool writes = ranks_.rank() == 0;
    const std::vector<std::string> parts =
        ranks_.gather(encode_share(mine, writes ? std::span<const CaseResult>() : done));
    const auto decoding = Clock::now();
    std::vector<ShareReport> shares;
    Decision decision;
    if (writes) decision = decide(parts, shares, count, writing);
    apply(ranks_.broadcast(encode_decision(decision)));
    Round round;
    round.stop = decision_.kind == Decision::stop;
    if (writes) {
      round.results = std::move(done);
      collect(parts, shares, round.results);
      decoding_seconds_ += seconds_since(decoding);
    }
    last_return_ = Clock::now();
    return round;
  }

 private:
  /// Rank r's cases of the round [first, first + count): its begin and count.
  std::pair<std::uint64_t, std::uint64_t> share(int r, std::uint64_t first,
                                                std::uint64_t count) const {
    const auto n = static_cast<std::uint64_t>(ranks_.size());
    const std::uint64_t own =
        n == 1 ? count
               : std::min(count, static_cast<std::uint64_t>(
                                     std::llround(rank0_fraction_ * static_cast<double>(count))));
    if (r == 0) return {first, own};
    const std::uint64_t rest = count - own, base = rest / (n - 1), extra = rest % (n - 1);
    const auto k = static_cast<std::uint64_t>(r - 1);
    const std::uint64_t begin = first + own + k * base + std::min(k, extra);
    return {begin, base + (k < extra ? 1 : 0)};
  }

  Decision decide(const std::vector<std::string>& parts, std::vector<ShareReport>& shares,
                  std::uint64_t count, double writing);
  void collect(const std::vector<std::string>& parts, const std::vector<ShareReport>& shares,
               std::vector<CaseResult>& results) const;
  void rebalance(const std::vector<ShareReport>& shares, std::uint64_t count, double writing);

  static std::string encode_decision(const Decision& d) {
    codec::ByteWriter out;
    out.put<std::uint8_t>(d.kind);
    out.put<double>(d.rank0_fraction);
    out.put_string(d.error);
    return out.take();
  }

  void apply(const std::string& bytes) {
    codec::ByteReader in(bytes);
    decision_.kind = static_cast<Decision::Kind>(in.get<std::uint8_t>());
    decision_.rank0_fraction = in.get<double>();
    decision_.error = in.get_string();
    rank0_fraction_ = decision_.rank0_fraction;
    if (decision_.kind != Decision::failed) return;
    ranks_.failure_shared = true;
    if (ranks_.rank() == 0) throw std::runtime_error(decision_.error);
    throw PeerFailure(decision_.error);
  }

  const ExperimentConfig& config_;
  int threads_;
  Ranks& ranks_;
  StopCheck stopping_;
  double rank0_fraction_;
  Decision decision_;
  std::optional<Clock::time_point> last_return_;
  double decoding_seconds_ = 0;
  // Seconds per case on rank 0 and on the others, from the last round that measured them.
  double rank0_case_seconds_ = 0, other_case_seconds_ = 0;
};

Decision DistributedRounds::decide(const std::vector<std::string>& parts,
                                   std::vector<ShareReport>& shares, std::uint64_t count,
                                   double writing) {
  Decision d;
  try {
    for (const std::string& part : parts)
      shares.push_back(decode_share_header(part));
  } catch (const std::exception& e) {
    return {Decision::failed, 0, e.what()};
  }
  for (std::size_t r = 0; r < shares.size(); ++r) {
    if (!shares[r].error.empty())
      return {Decision::failed, 0,
              (r == 0 ? "" : "rank " + std::to_string(r) + ": ") + shares[r].error};
    if (shares[r].stop) d.kind = Decision::stop;
  }
  rebalance(shares, count, writing);
  d.rank0_fraction = rank0_fraction_;
  return d;
}

/// Appends the other ranks' finished cases to rank 0's, in rank order up to the first rank
/// that did not finish its share: the round's finished prefix.
void DistributedRounds::collect(const std::vector<std::string>& parts,
                                const std::vector<ShareReport>& shares,
                                std::vector<CaseResult>& results) const {
  if (shares.empty() || shares[0].finished < shares[0].planned) return;
  for (std::size_t r = 1; r < shares.size(); ++r) {
    std::vector<CaseResult> done = decode_share_results(parts[r], shares[r]);
    std::move(done.begin(), done.end(), std::back_inserter(results));
    if (shares[r].finished < shares[r].planned) return;
  }
}

/// Sizes rank 0's next share so that its cases plus its writing take as long as another
/// rank's cases: s·c0 + w = (R − s)·c1/(n − 1), halfway from the current share (the times of
/// one round are noisy).
void DistributedRounds::rebalance(const std::vector<ShareReport>& shares, std::uint64_t count,
                                  double writing) {
  const auto n = static_cast<double>(shares.size());
  if (shares.size() < 2 || count == 0) return;
  if (shares[0].planned > 0)
    rank0_case_seconds_ = shares[0].seconds / static_cast<double>(shares[0].planned);
  double seconds = 0, planned = 0;
  for (std::size_t r = 1; r < shares.size(); ++r) {
    seconds += shares[r].seconds;
    planned += static_cast<double>(shares[r].planned);
  }
  if (planned > 0) other_case_seconds_ = seconds / planned;
  if (rank0_case_seconds_ <= 0 || other_case_seconds_ <= 0) return;
  const double R = static_cast<double>(count), c1 = other_case_seconds_ / (n - 1);
  const double target =
      std::clamp((R * c1 - writing) / (rank0_case_seconds_ + c1) / R, 0.0, 1.0 / n);
  rank0_fraction_ = 0.5 * (rank0_fraction_ + target);
}

}  // namespace

std::vector<CaseResult> evaluate_range(const ExperimentConfig& config, int threads,
                                       std::uint64_t first, std::uint64_t count,
                                       const StopCheck& stopping) {
  std::vector<CaseResult> batch(count);
  std::atomic<std::uint64_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    // The stop flag is read before an index is taken, so every taken case is finished and
    // the finished cases of the batch are exactly its first min(next, count).
    while (!stopping()) {
      const std::uint64_t i = next++;
      if (i >= count) break;
      try {
        batch[i] = evaluate_case(config, first + i);
      } catch (const std::exception& e) {
        const std::lock_guard lock(failure_mutex);
        if (!failure)
          failure = std::make_exception_ptr(
              std::runtime_error("case " + std::to_string(first + i) + ": " + e.what()));
        next = count;  // stop the other workers early
      }
    }
  };
  std::vector<std::jthread> pool;
  for (int t = 1; t < threads; ++t)
    pool.emplace_back(worker);
  worker();
  pool.clear();  // joins
  if (failure) std::rethrow_exception(failure);
  batch.resize(std::min<std::uint64_t>(next.load(), count));
  return batch;
}

std::unique_ptr<RoundSource> make_rounds(const ExperimentConfig& config, int threads, Ranks* ranks,
                                         StopCheck stopping) {
  if (!ranks) return std::make_unique<LocalRounds>(config, threads, std::move(stopping));
  return std::make_unique<DistributedRounds>(config, threads, *ranks, std::move(stopping));
}

}  // namespace gjklab::experiment
