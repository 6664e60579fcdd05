// The `stream` family: the narrow-phase queries a scene run recorded (`[scene] queries_every`)
// as experiment cases, bit for bit the pairs the scene's GJK queried.
#include <unistd.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/cli.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/scene_stream.hpp"
#include "gjklab/simulation/scene_file.hpp"

namespace fs = std::filesystem;
using namespace gjklab;

using gjklab::testing::run_cli;

namespace {

const std::string kScene = R"([scene]
name = "stream-source"
frames = 30
queries_every = 10

[physics]
dt = 0.01

[[static]]
shape = "box"
size = [10, 10, 1]
position = [0, 0, -0.5]

[[bodies]]
shape = "cone"
count = 3
placement = "stack"
position = [0, 0, 0.6]
spacing = 1.1

[[bodies]]
shape = "uv_sphere"
count = 2
placement = "stack"
position = [2, 0, 0.6]
spacing = 1.05
)";

}  // namespace

TEST_CASE("stream family: a scene's recorded queries become cases, as the scene queried them",
          "[unit][scene]") {
  const fs::path dir =
      fs::temp_directory_path() / ("gjklab-scene-stream-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string scene = (dir / "source.toml").string();
  const std::string archive = (dir / "source.h5").string();
  std::ofstream(scene) << kScene;
  std::string out, err;
  REQUIRE(run_cli({"simulate", scene, "--out", archive}, out, err) == 0);
  const std::vector<experiment::StoredPair> pairs = experiment::read_scene_stream(archive);

  // The same scene stepped here, logging the same frames' queries: every recorded pair is
  // the two world hulls GJK saw, bit for bit, in the order the step queried them.
  simulation::SceneSetup s = simulation::parse_scene(kScene, "source.toml");
  std::vector<scene::QueryRecord> log;
  std::vector<int> scene_iterations;  // warm-started, as the scene ran them
  std::size_t warm_queries = 0;
  std::size_t k = 0;
  for (int frame = 1; frame <= 30; ++frame) {
    std::vector<Pose> before;
    for (const scene::RigidBody& b : s.world->bodies())
      before.push_back(b.pose);
    log.clear();
    s.world->record_queries(frame % 10 == 0 ? &log : nullptr);
    s.world->step();
    for (const scene::QueryRecord& q : log) {
      REQUIRE(k < pairs.size());
      INFO("query " << k << ": " << pairs[k].id);
      std::ostringstream id;
      id << 'f' << frame << ':' << q.a << '-' << q.b;
      CHECK(pairs[k].id == id.str());
      const auto& bodies = s.world->bodies();
      const Polytope a = bodies[q.a].shape->polytope.transformed(before[q.a]);
      const Polytope b = bodies[q.b].shape->polytope.transformed(before[q.b]);
      CHECK(std::vector<Vec3>(a.vertices().begin(), a.vertices().end()) == pairs[k].a);
      CHECK(std::vector<Vec3>(b.vertices().begin(), b.vertices().end()) == pairs[k].b);
      // The warm start comes with the pair: the same vertex indices, at those vertices.
      REQUIRE(pairs[k].warm.size() == static_cast<std::size_t>(q.warm_size));
      for (int v = 0; v < q.warm_size; ++v) {
        CHECK(pairs[k].warm[v].index_a == q.warm_index_a[v]);
        CHECK(pairs[k].warm[v].index_b == q.warm_index_b[v]);
        CHECK(pairs[k].warm[v].a == pairs[k].a[q.warm_index_a[v]]);
      }
      warm_queries += q.warm_size > 0;
      scene_iterations.push_back(q.iterations);
      ++k;
    }
  }
  CHECK(k == pairs.size());
  CHECK(k >= 3);  // the bodies rest on the ground and on each other: pairs in every frame
  CHECK(warm_queries >= 3);  // the same pairs as the frame before: warm-started

  // An experiment with a stream family runs every recorded query, cold, and with
  // warm_start = true from the recorded simplex: then in the scene's own iterations.
  const std::string experiment = (dir / "stream.toml").string();
  std::ofstream(experiment) << "name = \"stream\"\nseed = 1\ncases = " << pairs.size()
                            << "\nthreads = 2\n\n[oracle]\nenabled = true\n\n[[family]]\n"
                            << "name = \"scene\"\nshape = \"stream\"\npath = \"source.h5\"\n\n"
                            << "[[algorithm]]\nname = \"gjk-johnson\"\n\n"
                            << "[[algorithm]]\nname = \"gjk-sv\"\n\n"
                            << "[[algorithm]]\nname = \"gjk-johnson\"\nlabel = \"warm\"\n"
                            << "warm_start = true\n";
  const experiment::ExperimentConfig config = experiment::load_experiment(experiment);
  REQUIRE(config.families.size() == 1);
  CHECK(config.families[0].stored.size() == pairs.size());
  CHECK(run_cli({"run", experiment, "--out", (dir / "stream.h5").string()}, out, err) == 0);
  REQUIRE(fs::exists(dir / "stream.h5"));
  const experiment::Archive run = experiment::read_archive(dir / "stream.h5");
  REQUIRE(run.results.size() == pairs.size());
  long cold_total = 0, warm_total = 0;
  for (std::size_t i = 0; i < run.results.size(); ++i) {
    INFO("case " << i);
    CHECK(run.results[i].algorithms[2].iterations == scene_iterations[i]);
    cold_total += run.results[i].algorithms[0].iterations;
    warm_total += run.results[i].algorithms[2].iterations;
  }
  CHECK(warm_total < cold_total);

  // A scene archive without recorded queries is a configuration error naming the cure.
  REQUIRE(run_cli({"simulate", scene, "--out", (dir / "plain.h5").string(), "--frames", "2"}, out,
                  err) == 0);
  std::ofstream(experiment)
      << "name = \"stream\"\nseed = 1\ncases = 4\n\n[[family]]\nshape = \"stream\"\n"
      << "path = \"plain.h5\"\n\n[[algorithm]]\nname = \"gjk-johnson\"\n";
  try {
    experiment::load_experiment(experiment);
    FAIL("a scene archive without queries was accepted");
  } catch (const experiment::ConfigError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("queries_every") != std::string::npos);
  }
  fs::remove_all(dir);
}
