// The error a scene file's text makes the scene parser throw, for tests of its messages.
#pragma once

#include <string>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/simulation/scene_file.hpp"

namespace gjklab::testing {

/// The ConfigError's message for `text` parsed as "bad.toml", or "" when it parses.
inline std::string scene_error_of(const std::string& text) {
  try {
    simulation::parse_scene(text, "bad.toml");
  } catch (const experiment::ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace gjklab::testing
