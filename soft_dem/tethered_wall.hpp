// The tethered target [model §4]: each wall grain is tied to its initial position and to its
// neighbouring wall grains (lattice neighbours, those within `bond_range`) by springs k_w (rest
// length = initial distance) with dashpots eta_w = damping_ratio * eta_n. Bonds are kept by grain
// id, so reordering is harmless.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/particles.hpp"
#include "core/state_archive.hpp"

namespace granjet::dem {

template <int D>
class TetheredWall {
 public:
  TetheredWall() = default;
  // `spring` is k_w, `damping` the dashpot rate eta_w (force = m eta_w * velocity, m = 1);
  // wall grains at most `bond_range` apart are neighbours.
  TetheredWall(const Particles<D>& p, double spring, double damping, double bond_range)
      : spring_(spring), damping_(damping) {
    std::vector<std::size_t> walls;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.kind()[i] == GrainKind::kWall) walls.push_back(i);
    for (std::size_t a : walls) anchors_.push_back({p.id()[a], p.position()[a]});
    for (std::size_t a = 0; a < walls.size(); ++a)
      for (std::size_t b = a + 1; b < walls.size(); ++b) {
        const std::size_t i = walls[a], j = walls[b];
        const double rest = (p.position()[i] - p.position()[j]).norm();
        if (rest <= bond_range) bonds_.push_back({p.id()[i], p.id()[j], rest});
      }
    index_bonds();
    std::unordered_map<GrainId, std::size_t> index;
    for (std::size_t i : walls) index[p.id()[i]] = i;
    locate([&](GrainId id) { return index.at(id); }, p.size());
  }

  std::size_t bonds() const { return bonds_.size(); }

  // Where the springs' grains lie among the `grains` held here: index_of maps a grain id to
  // its index (`grains` or more for one not held). Called after every reordering of the grains
  // (a neighbour rebuild), so that the springs, visited every step, look up no id. Over ranks
  // only the springs of the grains held here are visited, so that no rank visits the whole
  // target's; the order of the sums stays that of all springs.
  template <class IndexOf>
  void locate(IndexOf&& index_of, std::size_t grains) {
    const auto at = [&](GrainId id) {
      const std::size_t i = index_of(id);
      return i < grains ? static_cast<std::uint32_t>(i) : kAway;
    };
    held_bonds_.clear();
    held_anchors_.clear();
    for (std::uint32_t k = 0; k < bonds_.size(); ++k) {
      const HeldBond b{k, at(bonds_[k].i), at(bonds_[k].j)};
      if (b.i != kAway || b.j != kAway) held_bonds_.push_back(b);
    }
    for (std::uint32_t a = 0; a < anchors_.size(); ++a)
      if (const std::uint32_t i = at(anchors_[a].id); i != kAway) held_anchors_.push_back({a, i});
  }

  // Adds the tether forces to the grains where locate() last found them (a bond to a grain
  // held by another rank gives NaN, and a grain held elsewhere is skipped). `threads` share the
  // bonds, then the grains; each grain adds its anchor's force, then its bonds' in bond order,
  // the same sums for any thread count.
  void add_forces(const Particles<D>& p, std::span<Vec<D>> force, int threads = 1) const {
#pragma omp parallel num_threads(threads) if (threads > 1)
    add_forces_share(p, force);
  }

  // The same from inside a parallel region, on every thread of its team (two worksharing
  // loops, each ending in a barrier).
  void add_forces_share(const Particles<D>& p, std::span<Vec<D>> force) const {
    const auto x = p.position();
    const auto v = p.velocity();
    const auto bonds = static_cast<std::int64_t>(held_bonds_.size());
    const auto anchors = static_cast<std::int64_t>(held_anchors_.size());
#pragma omp for schedule(static)
    for (std::int64_t held = 0; held < bonds; ++held) {  // the force on the bond's first grain
      const auto [k, i, j] = held_bonds_[held];
      if (i == kAway || j == kAway) {  // a grain only another rank holds: unknown here
        bond_force_[k].setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      const Vec<D> r = x[i] - x[j];
      const double dist = r.norm();
      const Vec<D> n = r / dist;
      const double f = -spring_ * (dist - bonds_[k].rest) - damping_ * (v[i] - v[j]).dot(n);
      bond_force_[k] = f * n;
    }
#pragma omp for schedule(static)
    for (std::int64_t held = 0; held < anchors; ++held) {  // a held grain's bonds are all held
      const auto [a, i] = held_anchors_[held];
      Vec<D> sum = force[i] - (spring_ * (x[i] - anchors_[a].position) + damping_ * v[i]);
      for (std::uint32_t m = bonds_of_first_[a]; m < bonds_of_first_[a + 1]; ++m) {
        const std::int64_t signed_bond = bonds_of_[m];  // k + 1 for a first grain, -(k + 1)
        if (signed_bond > 0)
          sum += bond_force_[signed_bond - 1];
        else
          sum -= bond_force_[-signed_bond - 1];
      }
      force[i] = sum;
    }
  }

  // Calls visit(term, i, energy) for each spring's elastic energy: the anchors', then the
  // bonds' (term counts both); i is the grain whose rank adds the term (the anchored grain, a
  // bond's first grain). Springs with a grain not held here are left out.
  template <class Visit>
  void for_each_energy_term(const Particles<D>& p, Visit&& visit) const {
    const auto x = p.position();
    for (const auto [a, i] : held_anchors_)
      visit(a, i, 0.5 * spring_ * (x[i] - anchors_[a].position).squaredNorm());
    for (const auto [k, i, j] : held_bonds_) {
      if (i == kAway || j == kAway) continue;
      const double stretch = (x[i] - x[j]).norm() - bonds_[k].rest;
      visit(anchors_.size() + k, i, 0.5 * spring_ * stretch * stretch);
    }
  }

  // The longest rest length of a bond (a ghost must be held that far from a rank's part).
  double longest_bond() const {
    double longest = 0.0;
    for (const Bond& b : bonds_) longest = std::max(longest, b.rest);
    return longest;
  }

 private:
  // Each anchor's bonds in bond order (bonds_of_first_ is by anchor, as prefix offsets), signed
  // by the grain's end: from the anchors' and bonds' ids.
  void index_bonds() {
    std::unordered_map<GrainId, std::uint32_t> anchor_of;
    for (std::size_t a = 0; a < anchors_.size(); ++a)
      anchor_of[anchors_[a].id] = static_cast<std::uint32_t>(a);
    std::vector<std::vector<std::int64_t>> of(anchors_.size());
    for (std::size_t k = 0; k < bonds_.size(); ++k) {
      const auto i = anchor_of.find(bonds_[k].i), j = anchor_of.find(bonds_[k].j);
      if (i == anchor_of.end() || j == anchor_of.end())
        throw std::runtime_error("a tether bond joins a grain that has no anchor");
      of[i->second].push_back(static_cast<std::int64_t>(k) + 1);
      of[j->second].push_back(-static_cast<std::int64_t>(k) - 1);
    }
    bonds_of_first_.assign(1, 0);
    bonds_of_.clear();
    for (const std::vector<std::int64_t>& list : of) {
      bonds_of_.insert(bonds_of_.end(), list.begin(), list.end());
      bonds_of_first_.push_back(static_cast<std::uint32_t>(bonds_of_.size()));
    }
    bond_force_.resize(bonds_.size());
    held_bonds_.clear();  // until locate()
    held_anchors_.clear();
  }

  struct Anchor {
    GrainId id;
    Vec<D> position;
  };
  struct Bond {
    GrainId i, j;
    double rest;
  };
  // A spring visited here, with where its grains lie (kAway: held by another rank only).
  static constexpr std::uint32_t kAway = std::numeric_limits<std::uint32_t>::max();
  struct HeldBond {
    std::uint32_t bond, i, j;
  };
  struct HeldAnchor {
    std::uint32_t anchor, i;
  };
  double spring_ = 0.0;
  double damping_ = 0.0;

 public:
  // Checkpoints: the anchors and bonds by grain id.
  void save(StateArchive& a, const std::string& prefix) const {
    std::vector<GrainId> anchor_id, bond_ids;
    std::vector<Vec<D>> anchor_position;
    std::vector<double> rest;
    for (const Anchor& anchor : anchors_) {
      anchor_id.push_back(anchor.id);
      anchor_position.push_back(anchor.position);
    }
    for (const Bond& b : bonds_) {
      bond_ids.insert(bond_ids.end(), {b.i, b.j});
      rest.push_back(b.rest);
    }
    a.put_values<GrainId>(prefix + "/anchor_id", anchor_id);
    a.put_rows<Vec<D>>(prefix + "/anchor_position", anchor_position);
    a.put_values<GrainId>(prefix + "/bond_ids", bond_ids);
    a.put_rows<double>(prefix + "/bond_rest", rest);
  }
  void restore(const StateArchive& a, const std::string& prefix) {
    const auto anchor_id = a.values<GrainId>(prefix + "/anchor_id");
    const auto anchor_position = a.rows<Vec<D>>(prefix + "/anchor_position");
    const auto bond_ids = a.values<GrainId>(prefix + "/bond_ids");
    const auto rest = a.rows<double>(prefix + "/bond_rest");
    if (anchor_position.size() != anchor_id.size() || bond_ids.size() != 2 * rest.size())
      throw std::runtime_error("checkpoint entries under " + prefix + " differ in length");
    anchors_.clear();
    bonds_.clear();
    for (std::size_t k = 0; k < anchor_id.size(); ++k)
      anchors_.push_back({anchor_id[k], anchor_position[k]});
    for (std::size_t k = 0; k < rest.size(); ++k)
      bonds_.push_back({bond_ids[2 * k], bond_ids[2 * k + 1], rest[k]});
    index_bonds();
  }

 private:
  std::vector<Anchor> anchors_;
  std::vector<Bond> bonds_;
  std::vector<std::uint32_t> bonds_of_first_{0};
  std::vector<std::int64_t> bonds_of_;
  std::vector<HeldBond> held_bonds_;  // the springs visited (locate)
  std::vector<HeldAnchor> held_anchors_;
  mutable std::vector<Vec<D>>
      bond_force_;  // add_forces_share's scratch: each bond's force on its first grain
};

}  // namespace granjet::dem
