// A rank's share of a checkpoint split over the ranks of one run (StateArchive::split_over)
// travels to rank 0 as bytes, one rank at a time, so that rank 0 stores the shares without
// ever holding more than one of them besides its own. A rank makes its bytes as soon as it has
// its share, while rank 0 stores its own, and keeps only them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/rank_team.hpp"
#include "core/state_archive.hpp"

namespace granjet {

namespace detail {

enum class EntryKind : std::uint8_t { kReals, kIntegers };

inline void append_bytes(std::vector<std::byte>& out, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const std::byte*>(data);
  out.insert(out.end(), bytes, bytes + size);
}

template <class T>
void put_entry(std::vector<std::byte>& out, EntryKind kind, const std::string& name,
               const std::vector<T>& values) {
  const std::uint64_t name_size = name.size(), count = values.size();
  append_bytes(out, &kind, sizeof kind);
  append_bytes(out, &name_size, sizeof name_size);
  append_bytes(out, name.data(), name.size());
  append_bytes(out, &count, sizeof count);
  append_bytes(out, values.data(), values.size() * sizeof(T));
}

}  // namespace detail

// The share's entries of `archive` (StateArchive::in_share), bit for bit: kind, name and
// values, one after another.
inline std::vector<std::byte> share_bytes(const StateArchive& archive) {
  std::vector<std::byte> out;
  for (const auto& [name, values] : archive.all_reals())
    if (archive.in_share(name)) detail::put_entry(out, detail::EntryKind::kReals, name, values);
  for (const auto& [name, values] : archive.all_integers())
    if (archive.in_share(name)) detail::put_entry(out, detail::EntryKind::kIntegers, name, values);
  return out;
}

inline StateArchive archive_from_bytes(std::span<const std::byte> bytes) {
  std::size_t at = 0;
  const auto take = [&](void* out, std::size_t size) {
    if (size > bytes.size() - at)
      throw std::runtime_error("a checkpoint share arrived cut short (" +
                               std::to_string(bytes.size()) + " bytes)");
    std::memcpy(out, bytes.data() + at, size);
    at += size;
  };
  StateArchive archive;
  while (at < bytes.size()) {
    detail::EntryKind kind{};
    std::uint64_t name_size = 0, count = 0;
    take(&kind, sizeof kind);
    take(&name_size, sizeof name_size);
    std::string name(name_size, '\0');
    take(name.data(), name_size);
    take(&count, sizeof count);
    if (kind == detail::EntryKind::kReals) {
      std::vector<double> values(count);
      take(values.data(), count * sizeof(double));
      archive.put_reals(name, std::move(values));
    } else {
      std::vector<std::int64_t> values(count);
      take(values.data(), count * sizeof(std::int64_t));
      archive.put_integers(name, std::move(values));
    }
  }
  return archive;
}

// Rank `rank`'s share, the share_bytes() it passes as `mine`, on rank 0; an empty archive on
// the other ranks, whose `mine` is not sent. Collective over `team`.
inline StateArchive share_on_rank0(const RankTeam& team, int rank,
                                   std::span<const std::byte> mine) {
  const std::vector<std::byte> arrived =
      team.gather<std::byte>(team.rank() == rank ? mine : std::span<const std::byte>());
  if (team.rank() != 0) return {};
  return archive_from_bytes(arrived);
}

}  // namespace granjet
