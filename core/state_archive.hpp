// A run's state as named flat arrays of numbers: what a checkpoint stores (the app writes it
// into the run's .partial file) and a resumed run takes back. Core and the backends know no file
// format. Names are paths ("dem/force_prev"); a vector per grain is stored flat, D numbers each.
// Every number goes in and out unchanged, bit for bit.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/particles.hpp"

namespace granjet {

class StateArchive {
 public:
  using Reals = std::map<std::string, std::vector<double>>;
  using Integers = std::map<std::string, std::vector<std::int64_t>>;

  void put_reals(const std::string& name, std::vector<double> values) {
    reals_[name] = std::move(values);
  }
  void put_integers(const std::string& name, std::vector<std::int64_t> values) {
    integers_[name] = std::move(values);
  }
  void put(const std::string& name, double value) { put_reals(name, {value}); }
  void put(const std::string& name, std::int64_t value) { put_integers(name, {value}); }

  // Rows of doubles: Eigen fixed-size vectors, or double itself (a 2D spin).
  template <class Row>
  void put_rows(const std::string& name, std::span<const Row> rows) {
    std::vector<double> flat;
    flat.reserve(rows.size() * width<Row>());
    for (const Row& row : rows) {
      if constexpr (std::is_arithmetic_v<Row>)
        flat.push_back(row);
      else
        for (int d = 0; d < width<Row>(); ++d) flat.push_back(row.data()[d]);
    }
    put_reals(name, std::move(flat));
  }
  // Integers of any width (ids, indices, enums).
  template <class T>
  void put_values(const std::string& name, std::span<const T> values) {
    std::vector<std::int64_t> wide;
    wide.reserve(values.size());
    for (const T& v : values) wide.push_back(static_cast<std::int64_t>(v));
    put_integers(name, std::move(wide));
  }

  const std::vector<double>& reals(const std::string& name) const { return find(reals_, name); }
  const std::vector<std::int64_t>& integers(const std::string& name) const {
    return find(integers_, name);
  }
  double real(const std::string& name) const { return single(reals(name), name); }
  std::int64_t integer(const std::string& name) const { return single(integers(name), name); }
  bool contains(const std::string& name) const {
    return reals_.contains(name) || integers_.contains(name);
  }

  template <class Row>
  std::vector<Row> rows(const std::string& name) const {
    const std::vector<double>& flat = reals(name);
    constexpr std::size_t w = width<Row>();
    if (flat.size() % w != 0)
      throw std::runtime_error("checkpoint entry " + name + " is not a whole number of rows");
    std::vector<Row> out(flat.size() / w);
    for (std::size_t k = 0; k < out.size(); ++k) {
      if constexpr (std::is_arithmetic_v<Row>)
        out[k] = flat[k];
      else
        for (std::size_t d = 0; d < w; ++d) out[k].data()[d] = flat[k * w + d];
    }
    return out;
  }
  template <class T>
  std::vector<T> values(const std::string& name) const {
    std::vector<T> out;
    for (std::int64_t v : integers(name)) out.push_back(static_cast<T>(v));
    return out;
  }

  const Reals& all_reals() const { return reals_; }
  const Integers& all_integers() const { return integers_; }

  // Over the K ranks of one run each rank's archive holds what all ranks hold alike and its own
  // share of what is per grain and per contact: the entries whose names start with one of
  // `share_prefixes`. A checkpoint stores rank 0's archive and every other rank's share beside
  // it, gathered one rank at a time (analysis/checkpoint_file.hpp); a resume joins the shares it
  // takes (append_share), so no rank ever holds the whole run.
  void split_over(int ranks, const std::vector<std::string>& share_prefixes) {
    ranks_ = ranks;
    share_prefixes_.insert(share_prefixes_.end(), share_prefixes.begin(), share_prefixes.end());
  }
  // Entries under `prefix` are each rank's own too (StateWriter::share).
  void share_also(std::string prefix) { share_prefixes_.push_back(std::move(prefix)); }
  int ranks() const { return ranks_; }  // 1: the archive is whole
  bool in_share(const std::string& name) const {
    for (const std::string& prefix : share_prefixes_)
      if (name.starts_with(prefix)) return true;
    return false;
  }
  // Each entry of `share` after this archive's entry of that name (made when missing).
  void append_share(const StateArchive& share) {
    for (const auto& [name, values] : share.reals_) {
      std::vector<double>& mine = reals_[name];
      mine.insert(mine.end(), values.begin(), values.end());
    }
    for (const auto& [name, values] : share.integers_) {
      std::vector<std::int64_t>& mine = integers_[name];
      mine.insert(mine.end(), values.begin(), values.end());
    }
  }

 private:
  template <class Row>
  static constexpr int width() {
    if constexpr (std::is_arithmetic_v<Row>)
      return 1;
    else
      return Row::SizeAtCompileTime;
  }
  template <class Map>
  static const typename Map::mapped_type& find(const Map& map, const std::string& name) {
    const auto it = map.find(name);
    if (it == map.end()) throw std::runtime_error("checkpoint has no entry " + name);
    return it->second;
  }
  template <class T>
  static T single(const std::vector<T>& values, const std::string& name) {
    if (values.size() != 1)
      throw std::runtime_error("checkpoint entry " + name + " is not one number");
    return values.front();
  }

  Reals reals_;
  Integers integers_;
  int ranks_ = 1;
  std::vector<std::string> share_prefixes_;
};

namespace detail {
template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
}  // namespace detail

// One list of members serves both directions: a class with run state lists it once,
//   template <class Visitor> void visit_state(Visitor& v) { v("samples", samples_); ... }
// and StateWriter stores what StateReader gives back. Members are numbers, bools, enums,
// fixed-size Eigen vectors and matrices, and std::vectors of those; v.each() visits a vector
// of structs item by item, v.nested() a member object under its own name.
class StateWriter {
 public:
  StateWriter(StateArchive& archive, std::string prefix)
      : archive_(archive), prefix_(std::move(prefix)) {}

  template <class T>
  void operator()(const std::string& name, const T& value) {
    const std::string key = prefix_ + "/" + name;
    if constexpr (detail::IsVector<T>::value) {
      using E = typename T::value_type;
      if constexpr (std::is_arithmetic_v<E> && !std::is_floating_point_v<E>) {
        archive_.put_values<std::int64_t>(key,
                                          std::vector<std::int64_t>(value.begin(), value.end()));
      } else if constexpr (std::is_enum_v<E>) {
        archive_.put_values<E>(key, std::span<const E>(value));
      } else {
        archive_.put_rows<E>(key, std::span<const E>(value));
      }
    } else if constexpr (std::is_floating_point_v<T>) {
      archive_.put(key, static_cast<double>(value));
    } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      archive_.put(key, static_cast<std::int64_t>(value));
    } else {
      archive_.put_rows<T>(key, std::span<const T>(&value, 1));
    }
  }
  template <class Item, class Visit>
  void each(const std::string& name, std::vector<Item>& items, Visit&& visit) {
    (*this)(name + "/size", static_cast<std::int64_t>(items.size()));
    for (std::size_t k = 0; k < items.size(); ++k) {
      StateWriter item(archive_, prefix_ + "/" + name + "/" + std::to_string(k));
      visit(item, items[k]);
    }
  }
  StateWriter nested(const std::string& name) const { return {archive_, prefix_ + "/" + name}; }
  // A member object that is each rank's own over MPI ranks: it goes in the rank's share of a
  // checkpoint (StateArchive::split_over), not in rank 0's part that all ranks hold alike.
  StateWriter share(const std::string& name) const {
    archive_.share_also(prefix_ + "/" + name + "/");
    return nested(name);
  }

 private:
  StateArchive& archive_;
  std::string prefix_;
};

class StateReader {
 public:
  StateReader(const StateArchive& archive, std::string prefix)
      : archive_(archive), prefix_(std::move(prefix)) {}

  template <class T>
  void operator()(const std::string& name, T& value) const {
    const std::string key = prefix_ + "/" + name;
    if constexpr (detail::IsVector<T>::value) {
      using E = typename T::value_type;
      if constexpr (std::is_arithmetic_v<E> && !std::is_floating_point_v<E>) {
        const std::vector<std::int64_t>& wide = archive_.integers(key);
        value.assign(wide.begin(), wide.end());
      } else if constexpr (std::is_enum_v<E>) {
        value = archive_.values<E>(key);
      } else {
        value = archive_.rows<E>(key);
      }
    } else if constexpr (std::is_floating_point_v<T>) {
      value = static_cast<T>(archive_.real(key));
    } else if constexpr (std::is_same_v<T, bool>) {
      value = archive_.integer(key) != 0;
    } else if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      value = static_cast<T>(archive_.integer(key));
    } else {
      const std::vector<T> one = archive_.rows<T>(key);
      if (one.size() != 1)
        throw std::runtime_error("checkpoint entry " + key + " is not one value");
      value = one.front();
    }
  }
  // The items of a vector whose length the reader's own configuration fixed must match.
  template <class Item, class Visit>
  void each(const std::string& name, std::vector<Item>& items, Visit&& visit) const {
    const std::int64_t size = archive_.integer(prefix_ + "/" + name + "/size");
    if (size != static_cast<std::int64_t>(items.size()))
      throw std::runtime_error("checkpoint holds " + std::to_string(size) + " " + prefix_ + "/" +
                               name + "; this run has " + std::to_string(items.size()));
    for (std::size_t k = 0; k < items.size(); ++k) {
      StateReader item(archive_, prefix_ + "/" + name + "/" + std::to_string(k));
      visit(item, items[k]);
    }
  }
  StateReader nested(const std::string& name) const { return {archive_, prefix_ + "/" + name}; }
  StateReader share(const std::string& name) const { return nested(name); }
  // Whether the checkpoint holds `name`: an entry added after older checkpoints were written.
  bool contains(const std::string& name) const { return archive_.contains(prefix_ + "/" + name); }
  // Whether `name` came from the ranks' shares of a split checkpoint (read_checkpoint_file),
  // not from the part that every reader takes whole.
  bool in_share(const std::string& name) const { return archive_.in_share(prefix_ + "/" + name); }

 private:
  const StateArchive& archive_;
  std::string prefix_;
};

// Every column of a grain store, in its current order, under `prefix` ("dem/grains").
template <int D>
void put_particles(StateArchive& a, const std::string& prefix, const Particles<D>& p) {
  a.put_values<GrainId>(prefix + "/id", p.id());
  a.put_values<GrainKind>(prefix + "/kind", p.kind());
  a.put_rows<Vec<D>>(prefix + "/position", p.position());
  a.put_rows<Vec<D>>(prefix + "/velocity", p.velocity());
  a.put_rows<Spin<D>>(prefix + "/spin", p.spin());
  a.put_rows<double>(prefix + "/radius", p.radius());
  a.put_rows<double>(prefix + "/mass", p.mass());
}

template <int D>
Particles<D> get_particles(const StateArchive& a, const std::string& prefix) {
  const auto id = a.values<GrainId>(prefix + "/id");
  const auto kind = a.values<GrainKind>(prefix + "/kind");
  const auto position = a.rows<Vec<D>>(prefix + "/position");
  const auto velocity = a.rows<Vec<D>>(prefix + "/velocity");
  const auto spin = a.rows<Spin<D>>(prefix + "/spin");
  const auto radius = a.rows<double>(prefix + "/radius");
  const auto mass = a.rows<double>(prefix + "/mass");
  const std::size_t n = id.size();
  if (kind.size() != n || position.size() != n || velocity.size() != n || spin.size() != n ||
      radius.size() != n || mass.size() != n)
    throw std::runtime_error("checkpoint entries under " + prefix + " differ in length");
  Particles<D> p;
  for (std::size_t i = 0; i < n; ++i) {
    p.add(id[i], kind[i], position[i], velocity[i], radius[i], mass[i]);
    p.spin()[i] = spin[i];
  }
  return p;
}

}  // namespace granjet
