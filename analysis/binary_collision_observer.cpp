#include "analysis/binary_collision_observer.hpp"

#include <optional>
#include <vector>

namespace granjet::analysis {
namespace {

template <int D>
std::optional<double> hard_binary_restitution(const Particles<D>& before, const Particles<D>& after,
                                              const std::vector<PairImpulse<D>>& collisions) {
  if (collisions.size() != 1 || before.size() != 2 || after.size() != 2) return std::nullopt;
  const PairImpulse<D>& c = collisions.front();
  const Vec<D> n = (c.position_j - c.position_i).normalized();
  const auto v_ij = [&](const Particles<D>& p) {
    const std::size_t i = p.id()[0] == c.i ? 0 : 1;
    return Vec<D>(p.velocity()[i] - p.velocity()[1 - i]);
  };
  return -n.dot(v_ij(after)) / n.dot(v_ij(before));
}

}  // namespace

template <int D>
BinaryCollisionObserver<D>::BinaryCollisionObserver(const Scene& scene, Simulator<D>& sim)
    : step_(scene.dt()),
      restitution_(scene.contact.restitution),
      contact_time_(scene.contact.contact_time),
      initial_(sim.particles()) {
  sim.record_transfers(true);  // the hard collision's impulse
  observe(sim);
}

template <int D>
void BinaryCollisionObserver<D>::summarize(Simulator<D>& sim, nlohmann::json& summary) {
  if (tracker_.complete()) {
    summary["measured"] = {{"restitution", tracker_.restitution()},
                           {"contact_time", tracker_.contact_time()}};
    summary["requested"] = {{"restitution", restitution_}, {"contact_time", contact_time_}};
    return;
  }
  std::vector<PairImpulse<D>> collisions;
  sim.collect_transfers(collisions);
  if (const auto e = hard_binary_restitution(initial_, sim.particles(), collisions)) {
    summary["measured"] = {{"restitution", *e}};
    summary["requested"] = {{"restitution", restitution_}};
  }
}

template class BinaryCollisionObserver<2>;
template class BinaryCollisionObserver<3>;

}  // namespace granjet::analysis
