// Bench configs: `gjklab bench --config FILE` reads them with bench::load_bench_config.
//
// Input: the config's text. Properties: loading gives a BenchConfig or a BenchError, nothing
// else; an accepted config has sane settings (at least one suite, samples and configurations
// >= 1, a batch time in [0, 10] s, finite published figures), so that the benchmark cannot
// start with a value it would wrap, truncate or divide by.
#include <cmath>
#include <cstdint>
#include <span>

#include "gjklab/experiment/bench/bench.hpp"
#include "support.hpp"

namespace {

namespace bench = gjklab::experiment::bench;
using gjklab::fuzz::violated;

/// The largest batch time the loader accepts, s.
constexpr double kMaxBatchSeconds = 10;

void check_config(const bench::BenchConfig& c) {
  if (c.suites.empty()) violated("an accepted bench config without suites");
  if (c.samples < 1) violated("an accepted bench config with samples < 1");
  if (c.configurations < 1) violated("an accepted bench config with configurations < 1");
  // 0 is allowed: one repetition per batch.
  if (!(c.batch_seconds >= 0 && c.batch_seconds <= kMaxBatchSeconds))
    violated("an accepted bench config with a batch time outside [0, 10] s");
  for (const auto& [pair, us] : c.published_pair_us)
    if (!std::isfinite(us)) violated("an accepted bench config with a non-finite published figure");
  for (const auto& [objects, ms] : c.published_scene_ms)
    if (!std::isfinite(ms)) violated("an accepted bench config with a non-finite published figure");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = gjklab::fuzz::write_scratch_file("bench.toml", std::span(data, size));
  try {
    check_config(bench::load_bench_config(path.string()));
  } catch (const bench::BenchError&) {
  }
  return 0;
}
