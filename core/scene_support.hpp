// What a backend makes of a scene, declared before anything runs (as OpenMM's platforms say
// which systems they can run): the features it cannot run, each refused naming its key; the
// keys it changes to run the rest; and what it ignores or advises. The app refuses, or runs the
// resolved scene and records it beside the requested one (run/backend_factory.hpp).
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"

namespace granjet {

struct SceneSupport {
  // A feature the backend cannot run.
  struct Refusal {
    std::string key;
    std::string reason;
  };
  // A key whose value the backend changes to run the scene, with both values as the scene file
  // spells them.
  struct Adaptation {
    std::string key;
    std::string requested;
    std::string resolved;
    std::string reason;
  };

  Scene resolved;  // the scene as the backend runs it: the requested one with the adaptations
  std::vector<Refusal> unsupported;
  std::vector<Adaptation> adaptations;
  std::vector<std::string> notes;  // what it ignores or advises, one line each
};

}  // namespace granjet
