// The MPI ranks that share one run: a soft-DEM domain decomposition (soft_dem/domain.hpp)
// moves grains and sums between them through this class alone. A team of one rank makes no MPI
// call, so a build without MPI runs it. Every call is collective: all ranks of the team make
// it, in the same order. Values travel as bytes, so only trivially copyable types.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace granjet {

// The world size a launcher (mpirun, srun) announces to this process, from the first of these
// variables that is set (Open MPI's, then PMI's as MPICH and Slurm set it); 1 when not started
// by one. Read from the environment: no MPI call.
inline constexpr std::array<const char*, 2> kLaunchedRanksVariables = {"OMPI_COMM_WORLD_SIZE",
                                                                       "PMI_SIZE"};
int launched_ranks();

class RankTeam {
 public:
  // One rank alone.
  RankTeam() = default;
  // All ranks mpirun started (MPI_COMM_WORLD); MpiSession must be alive.
  static RankTeam world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool alone() const { return size_ == 1; }

  // Element by element over the ranks, in place: exact in any order.
  void max(std::span<double> values) const;
  void min(std::span<double> values) const;
  std::int64_t sum(std::int64_t value) const;
  bool any(bool value) const;

  // Every rank's values, joined in rank order, on every rank.
  template <class T>
  std::vector<T> all_gather(std::span<const T> mine) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::byte> joined = all_gather_bytes(as_bytes(mine));
    return from_bytes<T>(joined);
  }
  // Every rank's values, joined in rank order, on rank 0 (empty elsewhere).
  template <class T>
  std::vector<T> gather(std::span<const T> mine) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::byte> joined = gather_bytes(as_bytes(mine));
    return from_bytes<T>(joined);
  }
  // Rank 0's values, on every rank.
  template <class T>
  void broadcast(std::vector<T>& values) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::byte> bytes = as_bytes(std::span<const T>(values));
    broadcast_bytes(bytes);
    values = from_bytes<T>(bytes);
  }
  template <class T>
  void broadcast(T& value) const {
    std::vector<T> one{value};
    broadcast(one);
    value = one[0];
  }
  // Sends to[r] to rank r and returns what each rank sent here, by rank (to.size() == size()):
  // with every rank.
  template <class T>
  std::vector<std::vector<T>> exchange(const std::vector<std::vector<T>>& to) const {
    std::vector<int> all(size_);
    for (int r = 0; r < size_; ++r) all[r] = r;
    return exchange_with(to, all);
  }
  // The same with `partners` only (empty sends included), the same relation seen from both
  // sides: only those ranks take part, and none at all for no partners.
  template <class T>
  std::vector<std::vector<T>> exchange_with(const std::vector<std::vector<T>>& to,
                                            std::span<const int> partners) const {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::vector<std::byte>> bytes(to.size());
    for (std::size_t r = 0; r < to.size(); ++r) bytes[r] = as_bytes(std::span<const T>(to[r]));
    std::vector<std::vector<std::byte>> got = exchange_bytes(bytes, partners);
    std::vector<std::vector<T>> out(got.size());
    for (std::size_t r = 0; r < got.size(); ++r) out[r] = from_bytes<T>(got[r]);
    return out;
  }

 private:
  template <class T>
  static std::vector<std::byte> as_bytes(std::span<const T> values) {
    std::vector<std::byte> bytes(values.size_bytes());
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
  }
  template <class T>
  static std::vector<T> from_bytes(const std::vector<std::byte>& bytes) {
    std::vector<T> values(bytes.size() / sizeof(T));
    if (!values.empty()) std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
    return values;
  }
  std::vector<std::byte> all_gather_bytes(std::vector<std::byte> mine) const;
  std::vector<std::byte> gather_bytes(std::vector<std::byte> mine) const;
  void broadcast_bytes(std::vector<std::byte>& bytes) const;
  std::vector<std::vector<std::byte>> exchange_bytes(const std::vector<std::vector<std::byte>>& to,
                                                     std::span<const int> partners) const;

  int rank_ = 0;
  int size_ = 1;
};

// MPI from MPI_Init to MPI_Finalize, for a run started as several ranks (launched_ranks() > 1);
// nothing otherwise. A rank other than 0 left by an exception aborts every rank: rank 0 would
// wait for it in a collective call forever.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  bool active() const { return active_; }

 private:
  bool active_ = false;
};

}  // namespace granjet
