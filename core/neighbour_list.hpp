// Verlet half neighbour list built from a cell grid: every pair closer than
// R_i + R_j + skin, stored once (i < j) in compressed rows. It stays valid until some grain has
// moved more than skin/2 since the build (DisplacementWatch), not rebuilt every step.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/cell_grid.hpp"
#include "core/space.hpp"

namespace granjet {

struct PairList {
  std::vector<std::uint32_t> first;    // partners of i: partner[first[i] .. first[i+1])
  std::vector<std::uint32_t> partner;  // always > i
  std::size_t size() const { return partner.size(); }
};

namespace detail {

// Adds pairs (i, j), i > j, found after row j was closed (across a periodic boundary the
// forward cells can come earlier in memory) at the end of row j.
inline void merge_late_pairs(std::vector<std::pair<std::uint32_t, std::uint32_t>>& late,
                             PairList& out) {
  if (late.empty()) return;
  const std::size_t n = out.first.size() - 1;
  std::vector<std::uint32_t> first(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) first[i + 1] = out.first[i + 1] - out.first[i];
  for (const auto& [row, j] : late) ++first[row + 1];
  for (std::size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  std::vector<std::uint32_t> partner(first[n]);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = out.first[i]; k < out.first[i + 1]; ++k)
      partner[fill[i]++] = out.partner[k];
  for (const auto& [row, j] : late) partner[fill[row]++] = j;
  out.first = std::move(first);
  out.partner = std::move(partner);
}

}  // namespace detail

// `positions` must already be in grid order (cell c holds indices start(c)..start(c+1)-1).
// `excluded(i, j)` drops pairs that never interact (e.g. two wall grains); `space` gives the
// separation (plain or minimum image). With `threads` > 1 contiguous runs of cells are scanned
// in parallel and joined in order: the same list as one thread, entry for entry. kUniform: all
// grains have radius[0], so every pair has one cut-off and no radius is read per candidate
// (2 R + skin is R + R + skin exactly: the same list).
template <int D, bool kUniform = false, class Excluded, class Space = OpenSpace<D>>
void build_half_pairs(const CellGrid<D>& grid, std::span<const Vec<D>> positions,
                      std::span<const double> radius, double skin, Excluded&& excluded,
                      PairList& out, const Space& space = {}, int threads = 1) {
  using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  const std::size_t n = positions.size();
  out.first.assign(n + 1, 0);
  const double uniform_cut = kUniform && n > 0 ? radius[0] + radius[0] + skin : 0.0;
  // Chunk t holds cells [cell_begin[t], cell_begin[t+1]), about n / threads grains each.
  std::vector<std::size_t> cell_begin(threads + 1, grid.cells());
  std::size_t c = 0;
  for (int t = 0; t < threads; ++t) {
    while (c < grid.cells() && std::size_t{grid.start(c)} * threads < t * n) ++c;
    cell_begin[t] = c;
  }
  // Each chunk's pairs, in lists kept from build to build: fresh memory costs a page fault per
  // 4 kB, and a rebuild's lists are about as long as the last's. The calling thread's lists:
  // each thread of the team below has its own `chunk_lists`.
  static thread_local std::vector<std::vector<std::uint32_t>> chunk_lists;
  chunk_lists.resize(std::max<std::size_t>(chunk_lists.size(), threads));
  std::vector<std::uint32_t>* partners = chunk_lists.data();
  std::vector<Pairs> late(threads);  // (row, partner) found after the row was closed
#pragma omp parallel for num_threads(threads) schedule(static, 1) if (threads > 1)
  for (int t = 0; t < threads; ++t) {
    std::vector<std::uint32_t>& partner = partners[t];
    partner.clear();
    std::size_t count = 0;  // partner[0 .. count) are this chunk's pairs
    Pairs ranges;           // the forward cells' grains
    std::array<int, D> q = grid.coords(cell_begin[t]);
    for (std::size_t c = cell_begin[t]; c < cell_begin[t + 1]; ++c, grid.next_coords(q)) {
      const std::uint32_t begin = grid.start(c), end = grid.start(c + 1);
      if (begin == end) continue;
      ranges.clear();
      std::size_t forward_grains = 0;
      grid.for_each_forward_run(c, q, [&](std::size_t first, std::size_t last) {
        const std::uint32_t from = grid.start(first), to = grid.start(last);
        if (from == to) return;
        forward_grains += to - from;
        // Runs that follow each other in memory hold consecutive grains: one range, one loop
        // (the end of each short loop is a likely misprediction).
        if (!ranges.empty() && ranges.back().second == from)
          ranges.back().second = to;
        else
          ranges.emplace_back(from, to);
      });
      // The cell's own grains and the next cell's run on into each other too.
      const bool joined = !ranges.empty() && ranges.front().first == end;
      const std::uint32_t own_end = joined ? ranges.front().second : end;
      const auto others = std::span(ranges).subspan(joined ? 1 : 0);
      for (std::uint32_t i = begin; i < end; ++i) {
        // Room for every candidate: each is written, and kept only if it is a neighbour, with
        // no branch (about one candidate in ten is, in no order a predictor could learn).
        const std::size_t room = count + (end - i - 1) + forward_grains;
        if (partner.size() < room) partner.resize(2 * room);
        std::uint32_t* slot = partner.data();
        const Vec<D> x_i = positions[i];
        auto consider = [&](std::uint32_t j) {
          const double cut = kUniform ? uniform_cut : radius[i] + radius[j] + skin;
          const bool near =
              (space.separation(x_i, positions[j]).squaredNorm() < cut * cut) & !excluded(i, j);
          slot[count] = j;
          count += near;
        };
        for (std::uint32_t j = i + 1; j < own_end; ++j) consider(j);
        for (const auto& [first, last] : others)
          for (std::uint32_t j = first; j < last; ++j) consider(j);
        out.first[i + 1] = static_cast<std::uint32_t>(count);  // within the chunk
      }
    }
    partner.resize(count);
    if constexpr (Space::kPeriodic) {
      // Across the boundary a forward cell can come earlier in memory: its pairs (j < i) move
      // out, to be added at the end of row j.
      std::size_t kept = 0, row_begin = 0;
      const std::uint32_t chunk_end = grid.start(cell_begin[t + 1]);
      for (std::uint32_t i = grid.start(cell_begin[t]); i < chunk_end; ++i) {
        const std::size_t row_end = out.first[i + 1];
        for (std::size_t k = row_begin; k < row_end; ++k) {
          if (partner[k] > i)
            partner[kept++] = partner[k];
          else
            late[t].emplace_back(partner[k], i);
        }
        row_begin = row_end;
        out.first[i + 1] = static_cast<std::uint32_t>(kept);
      }
      partner.resize(kept);
    }
  }
  out.partner.clear();
  Pairs all_late;
  for (int t = 0; t < threads; ++t) {
    const auto base = static_cast<std::uint32_t>(out.partner.size());
    for (std::size_t i = grid.start(cell_begin[t]); i < grid.start(cell_begin[t + 1]); ++i)
      out.first[i + 1] += base;
    out.partner.insert(out.partner.end(), partners[t].begin(), partners[t].end());
    all_late.insert(all_late.end(), late[t].begin(), late[t].end());
  }
  detail::merge_late_pairs(all_late, out);
}

}  // namespace granjet
