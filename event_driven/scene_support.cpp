#include "event_driven/scene_support.hpp"

#include <sstream>

namespace granjet::ed {

namespace {

bool touching_jet(const Scene& scene) {
  return scene.kind == SceneKind::kJet && scene.jet.spacing < kMinJetSpacing;
}

}  // namespace

Scene hard_scene(const Scene& scene) {
  Scene hard = scene;
  if (hard.wall.kind == WallKind::kTethered) hard.wall.kind = WallKind::kFixed;
  if (touching_jet(scene)) hard.jet.spacing = kMinJetSpacing;
  return hard;
}

std::string scene_note(const Scene& scene) {
  std::ostringstream note;
  note << "event_driven: ";
  if (scene.frictional())
    note << "contact.friction = " << scene.contact.friction
         << " is ignored (hard grains are frictionless); ";
  if (scene.has_wall() && scene.wall.kind == WallKind::kTethered)
    note << "the tethered target becomes fixed wall grains (wall.kind = fixed, spec §4); ";
  if (touching_jet(scene))
    note << "jet.spacing = " << scene.jet.spacing << " becomes " << kMinJetSpacing
         << " (hard grains in contact have no collision order); ";
  note << "contact.contact_time, run.dt, run.integrator and run.skin have no hard-core meaning "
          "and are ignored";
  return note.str();
}

}  // namespace granjet::ed
