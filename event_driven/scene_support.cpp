#include "event_driven/scene_support.hpp"

#include "core/number_text.hpp"

namespace granjet::ed {

SceneSupport scene_support(const Scene& scene) {
  SceneSupport support;
  support.resolved = scene;
  Scene& hard = support.resolved;
  if (scene.output.force || scene.output.contacts)
    support.unsupported.push_back(
        {"output.fields",
         "force and contacts need contact forces; the event_driven backend's hard spheres "
         "exchange impulses only (use --backend soft_dem, or drop them)"});
  if (scene.output.omega)
    support.unsupported.push_back(
        {"output.fields",
         "omega: the grains of this run do not turn (smooth hard spheres); drop it"});
  if (scene.has_wall() && !scene.has_plate() && scene.wall.spacing < 1.0)
    support.unsupported.push_back(
        {"wall.spacing",
         "below 1 the target grains overlap, which hard grains cannot (use "
         "--backend soft_dem, or wall.spacing >= 1)"});
  if (scene.has_tethered_wall()) {
    hard.wall.kind = WallKind::kFixed;
    support.adaptations.push_back({"wall.kind", "tethered", "fixed",
                                   "hard grains have no springs: the tethered target becomes "
                                   "fixed wall grains, docs/model.md §4"});
  }
  if (scene.kind == SceneKind::kJet && scene.jet.spacing < kMinJetSpacing) {
    hard.jet.spacing = kMinJetSpacing;
    support.adaptations.push_back({"jet.spacing", number_text(scene.jet.spacing),
                                   number_text(kMinJetSpacing),
                                   "hard grains in contact have no collision order"});
  }
  if (scene.frictional())
    support.notes.push_back("contact.friction = " + number_text(scene.contact.friction) +
                            " is ignored (hard grains are frictionless)");
  if (scene.contact.rolling_friction > 0.0)
    support.notes.push_back(
        "contact.rolling_friction = " + number_text(scene.contact.rolling_friction) +
        " is ignored (hard grains do not turn)");
  if (scene.contact.adhesion > 0.0)
    support.notes.push_back("contact.adhesion = " + number_text(scene.contact.adhesion) +
                            " is ignored (hard grains touch for no time)");
  support.notes.push_back(
      "contact.model, contact.contact_time, run.dt, run.integrator and run.skin have no "
      "hard-core meaning and are ignored");
  return support;
}

Scene hard_scene(const Scene& scene) { return scene_support(scene).resolved; }

}  // namespace granjet::ed
