// The MPI ranks that share one run: a soft-DEM domain decomposition (soft_dem/domain.hpp)
// moves grains and sums between them through this class alone. A team of one rank makes no MPI
// call, so a build without MPI runs it. Every call is collective: all ranks of the team make
// it, in the same order. Values travel as bytes, so only trivially copyable types.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace granjet {

// The world size a launcher (mpirun, srun) announces to this process, from the first of these
// variables that is set (Open MPI's, then PMI's as MPICH and Slurm set it); 1 when not started
// by one. Read from the environment: no MPI call.
inline constexpr std::array<const char*, 2> kLaunchedRanksVariables = {"OMPI_COMM_WORLD_SIZE",
                                                                       "PMI_SIZE"};
int launched_ranks();
// This process's rank among them, from the same launchers' variables; 0 when not started by one.
inline constexpr std::array<const char*, 2> kLaunchedRankVariables = {"OMPI_COMM_WORLD_RANK",
                                                                      "PMI_RANK"};
int launched_rank();

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
  void sum(std::span<std::int64_t> values) const;
  std::int64_t sum(std::int64_t value) const {
    sum(std::span<std::int64_t>(&value, 1));
    return value;
  }
  bool any(bool value) const;

  // Every rank's values, joined in rank order, on every rank: into `joined`, whose memory is
  // kept from call to call, or into a new list.
  template <class T>
  void all_gather_into(std::span<const T> mine, std::vector<T>& joined) const {
    static_assert(std::is_trivially_copyable_v<T>);
    all_gather_bytes(std::as_bytes(mine), [&](std::size_t bytes) { return room(joined, bytes); });
  }
  template <class T>
  std::vector<T> all_gather(std::span<const T> mine) const {
    std::vector<T> joined;
    all_gather_into(mine, joined);
    return joined;
  }
  // Every rank's values, joined in rank order, on rank 0 (empty elsewhere): the same two ways.
  template <class T>
  void gather_into(std::span<const T> mine, std::vector<T>& joined) const {
    static_assert(std::is_trivially_copyable_v<T>);
    gather_bytes(std::as_bytes(mine), [&](std::size_t bytes) { return room(joined, bytes); });
  }
  template <class T>
  std::vector<T> gather(std::span<const T> mine) const {
    std::vector<T> joined;
    gather_into(mine, joined);
    return joined;
  }
  // Rank 0's values, on every rank.
  template <class T>
  void broadcast(std::vector<T>& values) const {
    static_assert(std::is_trivially_copyable_v<T>);
    broadcast_bytes(std::as_writable_bytes(std::span<T>(values)),
                    [&](std::size_t bytes) { return room(values, bytes); });
  }
  template <class T>
  void broadcast(T& value) const {
    std::vector<T> one{value};
    broadcast(one);
    value = one[0];
  }
  // Sends to[r] to each rank r of `partners` and receives what r sends here into from[r]
  // (both of size() lists). The same relation seen from both sides: only those ranks take
  // part, and none at all for no partners. The lists are the caller's, kept from call to call
  // so that their memory is reused. With `sizes_known`, each from[r] already has the length
  // that r sends (another length is an error, raised on the receiving rank); otherwise each
  // from[r] takes the length of what arrives.
  template <class T>
  void exchange_into(const std::vector<std::vector<T>>& to, std::vector<std::vector<T>>& from,
                     std::span<const int> partners, bool sizes_known) const {
    static_assert(std::is_trivially_copyable_v<T>);
    check_lists(to.size(), from.size());
    std::vector<std::span<const std::byte>> out(to.size());
    for (std::size_t r = 0; r < to.size(); ++r) out[r] = std::as_bytes(std::span<const T>(to[r]));
    exchange_bytes(out, partners, sizes_known, [&](int r, std::size_t bytes) {
      return sizes_known ? std::as_writable_bytes(std::span<T>(from[r])) : room(from[r], bytes);
    });
  }
  // The same into new lists, sizes unknown.
  template <class T>
  std::vector<std::vector<T>> exchange_with(const std::vector<std::vector<T>>& to,
                                            std::span<const int> partners) const {
    std::vector<std::vector<T>> from(to.size());
    exchange_into(to, from, partners, false);
    return from;
  }
  // With every rank.
  template <class T>
  std::vector<std::vector<T>> exchange(const std::vector<std::vector<T>>& to) const {
    std::vector<int> all(size_);
    for (int r = 0; r < size_; ++r) all[r] = r;
    return exchange_with(to, all);
  }

 private:
  // Where `bytes` of received values go: `values` resized to hold them.
  template <class T>
  static std::span<std::byte> room(std::vector<T>& values, std::size_t bytes) {
    if (bytes % sizeof(T) != 0)
      throw std::logic_error("rank team: " + std::to_string(bytes) + " bytes are not whole values");
    values.resize(bytes / sizeof(T));
    return std::as_writable_bytes(std::span<T>(values));
  }
  using Room = std::function<std::span<std::byte>(std::size_t bytes)>;
  using RoomOf = std::function<std::span<std::byte>(int rank, std::size_t bytes)>;
  void check_lists(std::size_t to, std::size_t from) const;
  void all_gather_bytes(std::span<const std::byte> mine, const Room& joined) const;
  void gather_bytes(std::span<const std::byte> mine, const Room& joined) const;
  void broadcast_bytes(std::span<std::byte> root_bytes, const Room& bytes) const;
  void exchange_bytes(std::span<const std::span<const std::byte>> to, std::span<const int> partners,
                      bool sizes_known, const RoomOf& from) const;
  void exchange_known(std::span<const std::span<const std::byte>> to, std::span<const int> partners,
                      const RoomOf& from) const;
  void exchange_probed(std::span<const std::span<const std::byte>> to,
                       std::span<const int> partners, const RoomOf& from) const;

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
