#include "core/rank_team.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#ifdef GRANJET_HAS_MPI
#include <mpi.h>
#endif

namespace granjet {

int launched_ranks() {
  for (const char* name : kLaunchedRanksVariables)
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

int launched_rank() {
  for (const char* name : kLaunchedRankVariables)
    if (const char* v = std::getenv(name)) return std::max(0, std::atoi(v));
  return 0;
}

namespace {

void check_received(int rank, std::size_t got, std::size_t expected) {
  if (got != expected)
    throw std::logic_error("rank " + std::to_string(rank) + " sent " + std::to_string(got) +
                           " bytes where " + std::to_string(expected) + " were expected");
}

// One rank's message to itself.
void copy_to(std::span<std::byte> to, std::span<const std::byte> from, bool sizes_known = false) {
  if (sizes_known) check_received(0, from.size(), to.size());
  if (!from.empty()) std::memcpy(to.data(), from.data(), from.size());
}

#ifdef GRANJET_HAS_MPI
// MPI counts in int: a message of 2 GiB or more is refused, not cut.
int count_of(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT32_MAX))
    throw std::runtime_error("an MPI message of " + std::to_string(bytes) +
                             " bytes is beyond the 2 GiB one call carries");
  return static_cast<int>(bytes);
}

// Shared-memory transports copy a short message through a buffer that the receiver reads
// straight away (eager), but hand a long one over only after a handshake between the two ranks
// (rendezvous); Open MPI's shared-memory transport switches at 4 KiB, headers included. The
// ghost states that the ranks swap at every step are latency-bound, and a rank that comes late
// to the exchange finds eager pieces waiting where a rendezvous would make it start the
// handshake. So a message up to kPiecewiseUpTo goes as pieces of kPiece bytes (jet3d on two
// ranks of a 2-vCPU AMD EPYC: the shortest exchange of a step 3.1 us against 7.0 us in one
// message). Longer ones go whole: in pieces, a lone exchange of 32 KiB took 1.7 times as long as
// one message (bench/rank_exchange_bench.cpp).
struct Piece {
  std::size_t offset = 0, bytes = 0;
  int rank = 0;
};
constexpr std::size_t kPiece = 4000;  // 4 KiB less room for the transport's headers
constexpr std::size_t kPiecewiseUpTo = 16 * 1024;

// Calls visit(piece) for each piece of a message of `bytes`, in order: full pieces, then one
// shorter piece (possibly empty), so that every message is at least one piece and ends with a
// short one.
template <class Visit>
void for_each_piece(std::size_t bytes, int rank, Visit&& visit) {
  if (bytes > kPiecewiseUpTo) {
    visit(Piece{0, bytes, rank});
    return;
  }
  std::size_t offset = 0;
  for (; bytes - offset >= kPiece; offset += kPiece) visit(Piece{offset, kPiece, rank});
  visit(Piece{offset, bytes - offset, rank});
}

constexpr int kDataTag = 12;  // the exchanges' messages

// Posts each partner's message, cut as for_each_piece cuts it.
void send_pieces(std::span<const std::span<const std::byte>> to, std::span<const int> partners,
                 std::vector<MPI_Request>& requests) {
  for (int r : partners)
    for_each_piece(to[r].size(), r, [&](const Piece& p) {
      requests.emplace_back();
      MPI_Isend(to[r].data() + p.offset, count_of(p.bytes), MPI_BYTE, r, kDataTag, MPI_COMM_WORLD,
                &requests.back());
    });
}

std::vector<int> offsets_of(const std::vector<int>& counts, std::size_t& total) {
  std::vector<int> offsets(counts.size(), 0);
  total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = count_of(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  count_of(total);
  return offsets;
}
#endif

}  // namespace

void RankTeam::check_lists(std::size_t to, std::size_t from) const {
  if (to != static_cast<std::size_t>(size_) || from != static_cast<std::size_t>(size_))
    throw std::invalid_argument("rank team exchange: one list per rank each way, not " +
                                std::to_string(to) + " and " + std::to_string(from));
}

RankTeam RankTeam::world() {
  RankTeam team;
#ifdef GRANJET_HAS_MPI
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised) {
    MPI_Comm_rank(MPI_COMM_WORLD, &team.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &team.size_);
  }
#endif
  return team;
}

#ifdef GRANJET_HAS_MPI

void RankTeam::max(std::span<double> values) const {
  if (alone() || values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX,
                MPI_COMM_WORLD);
}

void RankTeam::min(std::span<double> values) const {
  if (alone() || values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MIN,
                MPI_COMM_WORLD);
}

void RankTeam::sum(std::span<std::int64_t> values) const {
  if (alone() || values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_INT64_T, MPI_SUM,
                MPI_COMM_WORLD);
}

bool RankTeam::any(bool value) const {
  if (alone()) return value;
  int v = value ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return v != 0;
}

void RankTeam::all_gather_bytes(std::span<const std::byte> mine, const Room& joined) const {
  if (alone()) {
    copy_to(joined(mine.size()), mine);
    return;
  }
  std::vector<int> counts(size_);
  const int count = count_of(mine.size());
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::size_t total = 0;
  const std::vector<int> offsets = offsets_of(counts, total);
  MPI_Allgatherv(mine.data(), count, MPI_BYTE, joined(total).data(), counts.data(), offsets.data(),
                 MPI_BYTE, MPI_COMM_WORLD);
}

void RankTeam::gather_bytes(std::span<const std::byte> mine, const Room& joined) const {
  if (alone()) {
    copy_to(joined(mine.size()), mine);
    return;
  }
  std::vector<int> counts(size_);
  const int count = count_of(mine.size());
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::size_t total = 0;
  std::vector<int> offsets(size_, 0);
  if (rank_ == 0) offsets = offsets_of(counts, total);
  MPI_Gatherv(mine.data(), count, MPI_BYTE, joined(total).data(), counts.data(), offsets.data(),
              MPI_BYTE, 0, MPI_COMM_WORLD);
}

void RankTeam::broadcast_bytes(std::span<std::byte> root_bytes, const Room& bytes) const {
  if (alone()) return;
  std::uint64_t size = root_bytes.size();
  MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  const std::span<std::byte> here = rank_ == 0 ? root_bytes : bytes(size);
  MPI_Bcast(here.data(), count_of(size), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void RankTeam::exchange_bytes(std::span<const std::span<const std::byte>> to,
                              std::span<const int> partners, bool sizes_known,
                              const RoomOf& from) const {
  if (alone()) {
    for (int r : partners) copy_to(from(r, to[r].size()), to[r], sizes_known);
    return;
  }
  if (sizes_known)
    exchange_known(to, partners, from);
  else
    exchange_probed(to, partners, from);
}

void RankTeam::exchange_known(std::span<const std::span<const std::byte>> to,
                              std::span<const int> partners, const RoomOf& from) const {
  std::vector<MPI_Request> requests;
  requests.reserve(2 * partners.size());
  std::vector<std::span<std::byte>> inbox(size_);
  std::vector<Piece> pieces;  // the receives, in the order they are posted
  for (int r : partners) {
    inbox[r] = from(r, 0);  // the list as the caller sized it: the length asked for is unused
    for_each_piece(inbox[r].size(), r, [&](const Piece& p) {
      pieces.push_back(p);
      requests.emplace_back();
      MPI_Irecv(inbox[r].data() + p.offset, count_of(p.bytes), MPI_BYTE, r, kDataTag,
                MPI_COMM_WORLD, &requests.back());
    });
  }
  const std::size_t receives = requests.size();
  send_pieces(to, partners, requests);
  // One piece at a time, so that a sender that cut its message otherwise (another length) is
  // caught at the first piece that differs rather than waited for: a longer piece is MPI's
  // truncation error, a shorter one is caught here.
  for (std::size_t k = 0; k < receives; ++k) {
    MPI_Status status;
    MPI_Wait(&requests[k], &status);
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    const Piece& p = pieces[k];
    if (static_cast<std::size_t>(count) == p.bytes) continue;
    // Nothing left posted that a later exchange's message could land in.
    for (std::size_t j = k + 1; j < receives; ++j) {
      MPI_Cancel(&requests[j]);
      MPI_Wait(&requests[j], MPI_STATUS_IGNORE);
    }
    for (std::size_t j = receives; j < requests.size(); ++j) MPI_Request_free(&requests[j]);
    throw std::logic_error(
        "rank " + std::to_string(p.rank) + " sent other than the " +
        std::to_string(inbox[p.rank].size()) + " bytes expected: " + std::to_string(count) +
        " where byte " + std::to_string(p.offset) + " began a piece of " + std::to_string(p.bytes));
  }
  MPI_Waitall(static_cast<int>(requests.size() - receives), requests.data() + receives,
              MPI_STATUSES_IGNORE);
}

// A message of unknown length is read as it comes: each piece is matched (MPI_Mprobe) in the
// order sent until the one that ends it, shorter than a full piece (a whole message is longer
// than any piece), and only then received, into room for them all. No round of lengths first:
// the ghost states of a step change length from step to step, and that round would add a
// latency to every step.
void RankTeam::exchange_probed(std::span<const std::span<const std::byte>> to,
                               std::span<const int> partners, const RoomOf& from) const {
  std::vector<MPI_Request> requests;
  requests.reserve(partners.size());
  send_pieces(to, partners, requests);
  std::vector<MPI_Message> matched;
  std::vector<int> counts;
  for (int r : partners) {
    matched.clear();
    counts.clear();
    std::size_t bytes = 0;
    do {
      MPI_Status status;
      matched.emplace_back();
      MPI_Mprobe(r, kDataTag, MPI_COMM_WORLD, &matched.back(), &status);
      counts.emplace_back();
      MPI_Get_count(&status, MPI_BYTE, &counts.back());
      bytes += static_cast<std::size_t>(counts.back());
    } while (static_cast<std::size_t>(counts.back()) == kPiece);
    const std::span<std::byte> inbox = from(r, bytes);
    std::size_t offset = 0;
    for (std::size_t k = 0; k < matched.size(); ++k) {
      MPI_Mrecv(inbox.data() + offset, counts[k], MPI_BYTE, &matched[k], MPI_STATUS_IGNORE);
      offset += static_cast<std::size_t>(counts[k]);
    }
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

MpiSession::MpiSession() {
  if (launched_ranks() <= 1) return;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) MPI_Init(nullptr, nullptr);
  active_ = true;
}

MpiSession::~MpiSession() {
  if (!active_) return;
  // Rank 0 leads (run/rank_leader.hpp) and releases the others before it fails; another
  // rank that fails alone would leave rank 0 waiting for it.
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (std::uncaught_exceptions() > 0 && rank != 0) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Finalize();
}

#else  // one rank: nothing to combine

void RankTeam::max(std::span<double>) const {}
void RankTeam::min(std::span<double>) const {}
void RankTeam::sum(std::span<std::int64_t>) const {}
bool RankTeam::any(bool value) const { return value; }
void RankTeam::all_gather_bytes(std::span<const std::byte> mine, const Room& joined) const {
  copy_to(joined(mine.size()), mine);
}
void RankTeam::gather_bytes(std::span<const std::byte> mine, const Room& joined) const {
  copy_to(joined(mine.size()), mine);
}
void RankTeam::broadcast_bytes(std::span<std::byte>, const Room&) const {}
void RankTeam::exchange_bytes(std::span<const std::span<const std::byte>> to,
                              std::span<const int> partners, bool sizes_known,
                              const RoomOf& from) const {
  for (int r : partners) copy_to(from(r, to[r].size()), to[r], sizes_known);
}

MpiSession::MpiSession() {
  if (launched_ranks() > 1)
    throw std::runtime_error(
        "started as one of " + std::to_string(launched_ranks()) +
        " MPI ranks, but this granjet was built without MPI. Rebuild with Open MPI "
        "(libopenmpi-dev; scripts/setup.sh installs it) or start one process");
}
MpiSession::~MpiSession() = default;

#endif

}  // namespace granjet
