// What a scene run records each frame into the scene archive's tables (gjklab/experiment/
// archive/scene_archive.hpp): frame statistics, poses, contacts, the narrow phase's queries,
// and the broad phases compared on the same boxes.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "gjklab/experiment/archive/scene_archive.hpp"
#include "gjklab/scene/world.hpp"

namespace gjklab::simulation {

/// One row of frames/: the step's statistics; max_penetration relative to `body_size`.
void record_frame(const scene::World& w, const scene::StepStats& st, double body_size,
                  experiment::SceneFrameRows& rows);
/// The dynamic bodies' poses, velocities and touching state at `frame`.
void record_poses(const scene::World& w, std::int64_t frame, experiment::ScenePoseRows& rows);
/// The world's contacts after the step of `frame`.
void record_contacts(const scene::World& w, std::int64_t frame, experiment::SceneContactRows& rows);
/// The step's queries (logged by the world) with the poses the bodies had before it.
void record_queries(const std::vector<Pose>& before, const std::vector<scene::QueryRecord>& log,
                    std::int64_t frame, experiment::SceneQueryRows& rows);

/// The broad phases on the world's current boxes, timed (pair search only): the scene's three
/// and, when Bullet is built in, Bullet's dbvt (each kept between frames).
class BroadPhaseComparison {
 public:
  BroadPhaseComparison();
  ~BroadPhaseComparison();
  BroadPhaseComparison(const BroadPhaseComparison&) = delete;
  BroadPhaseComparison& operator=(const BroadPhaseComparison&) = delete;
  /// Appends the frame's all_pairs_ns, grid_ns, sap_ns (dbvt_ns) and broad_phases_agree.
  void run(const scene::World& w, experiment::SceneFrameRows& rows);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gjklab::simulation
