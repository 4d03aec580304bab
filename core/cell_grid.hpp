// Cell binning for neighbour search: grains are counting-sorted by cell over their bounding
// box (or a periodic box), so after reordering by order() every cell is a contiguous index range.
// Within a cell grains come in the order of their ids where ids are given, so that the order
// depends on the positions and ids alone, not on the order the grains came in: any part of the
// grains (a rank's own and its neighbours', under a domain decomposition) is ordered as in the
// whole, and so are its pairs, its contacts and the order of each grain's sums.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/cell_sizing.hpp"
#include "core/dim.hpp"
#include "core/omp_team.hpp"

namespace granjet {

template <int D>
class CellGrid {
 public:
  // Where the cells lie: their origin, the inverse of their edge and how many there are across.
  // build() takes it from the grains' bounding box; the ranks of a domain decomposition take
  // one frame from the box and count of all grains and each bins its own in a window of it
  // (build_in), so that their cells, and the order of their grains, are those of the whole.
  struct Frame {
    Vec<D> lo = Vec<D>::Zero();
    Vec<D> inv_edge = Vec<D>::Ones();
    std::array<int, D> dims{};
  };
  // The frame over [lo, hi] for `grains` grains, with edges of at least `min_edge`, grown when
  // the box would need more than kMaxCellsPerGrain cells per grain (core/cell_sizing.hpp).
  static Frame frame_of(const Vec<D>& lo, const Vec<D>& hi, double min_edge, std::size_t grains) {
    const Vec<D> extent = (hi - lo).cwiseMax(min_edge);
    const double edge = capped_cell_edge<D>(extent, min_edge, max_cells(grains), CellFit::kTile);
    Frame f;
    f.lo = lo;
    for (int d = 0; d < D; ++d) {
      f.inv_edge[d] = 1.0 / edge;
      // Cells are at least `edge` wide: dims rounds down.
      f.dims[d] = std::max(1, static_cast<int>(extent[d] * f.inv_edge[d]));
    }
    return f;
  }

  // Bins `positions` into the cells of the frame of their bounding box. `threads` share the
  // passes over the grains (the same grid for any count). `id`: each grain's id, which orders
  // the grains of a cell (empty: their index does).
  void build(std::span<const Vec<D>> positions, double min_edge, int threads = 1,
             std::span<const std::int64_t> id = {}) {
    const auto [lo, hi] = bounding_box(positions, threads);
    bin_in(frame_of(lo, hi, min_edge, positions.size()), lo, hi, positions, id, threads);
  }

  // Bins `positions` into the cells of `frame` that their bounding box covers (the window);
  // the cell indices of this grid are the window's, frame_cell() turns them into the frame's.
  void build_in(const Frame& frame, std::span<const Vec<D>> positions, int threads = 1,
                std::span<const std::int64_t> id = {}) {
    const auto [lo, hi] = bounding_box(positions, threads);
    bin_in(frame, lo, hi, positions, id, threads);
  }

  // The frame's index of window cell c (the same as c for a grid of build()).
  std::uint64_t frame_cell(std::size_t c) const {
    const std::array<int, D> q = coords(c);
    std::uint64_t linear = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      linear += static_cast<std::uint64_t>(q[d] + offset_[d]) * stride;
      stride *= static_cast<std::uint64_t>(frame_dims_[d]);
    }
    return linear;
  }
  // The window cell of grain i (an index of the positions binned, before the reordering).
  std::uint32_t cell_of(std::size_t i) const { return cell_of_[i]; }

  // Tiles the periodic box [0, box) (positions wrapped into it) with cells of at least
  // `min_edge`; neighbour cells wrap around. Three cells per axis at least, so that a cell's
  // neighbours are distinct cells and each pair of cells is visited once. A dilute box gets
  // larger cells rather than a huge empty grid, as in build().
  void build_periodic(std::span<const Vec<D>> positions, const Vec<D>& box, double min_edge,
                      int threads = 1, std::span<const std::int64_t> id = {}) {
    periodic_ = true;
    lo_.setZero();
    offset_.fill(0);
    const double edge =
        capped_cell_edge<D>(box, min_edge, max_cells(positions.size()), CellFit::kTile);
    for (int d = 0; d < D; ++d) {
      dims_[d] = static_cast<int>(box[d] / edge);
      if (dims_[d] < 3)
        throw std::invalid_argument("periodic box narrower than three neighbour cells");
      inv_edge_[d] = dims_[d] / box[d];
    }
    frame_dims_ = dims_;
    bin(positions, id, threads);
  }

  // Grain indices sorted by cell (within a cell by id, or by index without ids).
  std::span<const std::uint32_t> order() const { return order_; }
  // Grains of cell c are order()[start(c)] .. order()[start(c+1)-1].
  std::uint32_t start(std::size_t c) const { return start_[c]; }
  std::size_t cells() const { return total_; }
  const std::array<int, D>& dims() const { return dims_; }

  std::array<int, D> coords(std::size_t c) const {
    std::array<int, D> q;
    for (int d = 0; d < D; ++d) {
      q[d] = static_cast<int>(c % dims_[d]);
      c /= dims_[d];
    }
    return q;
  }

  // The coordinates of the cell after the one at q (coords(c + 1) from coords(c), without
  // the divisions: the pair loop walks every cell).
  void next_coords(std::array<int, D>& q) const {
    for (int d = 0; d < D && ++q[d] == dims_[d]; ++d)
      if (d + 1 < D) q[d] = 0;
  }

  // The neighbour cells that come after cell c (at coordinates q) in the half stencil, each
  // cell pair once: the next cell along the first axis, then each row of three cells along it
  // whose offset in the other axes ends in +1, in the order of those offsets. visit(first, end)
  // gets them as runs of cells consecutive in memory: a row is one run, cut where the grid
  // ends, or split where it wraps around a periodic box.
  template <class Visit>
  void for_each_forward_run(std::size_t c, const std::array<int, D>& q, Visit&& visit) const {
    visit_row(c - q[0], q[0] + 1, q[0] + 1, visit);
    for (const auto& offset : forward_rows()) {
      std::size_t row = 0, stride = dims_[0];
      bool inside = true;
      for (int d = 1; d < D; ++d) {
        int k = q[d] + offset[d - 1];
        if (periodic_) k = (k + dims_[d]) % dims_[d];
        inside = inside && k >= 0 && k < dims_[d];
        row += static_cast<std::size_t>(k) * stride;
        stride *= dims_[d];
      }
      if (inside) visit_row(row, q[0] - 1, q[0] + 1, visit);
    }
  }

 private:
  // Every rebuild walks every cell (the counting sort, the pair loop): a few per grain.
  static constexpr double kMaxCellsPerGrain = 16.0;
  static double max_cells(std::size_t grains) {
    return kMaxCellsPerGrain * static_cast<double>(std::max<std::size_t>(grains, 1));
  }

  static std::pair<Vec<D>, Vec<D>> bounding_box(std::span<const Vec<D>> positions, int threads) {
    Vec<D> lo = Vec<D>::Constant(0.0), hi = Vec<D>::Constant(0.0);
    if (!positions.empty()) lo = hi = positions[0];
    const auto n = static_cast<std::int64_t>(positions.size());
    std::vector<Vec<D>> thread_lo(threads, lo), thread_hi(threads, hi);
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
      Vec<D> my_lo = lo, my_hi = hi;  // locals: the threads' slots share cache lines
#pragma omp for schedule(static) nowait
      for (std::int64_t i = 0; i < n; ++i) {
        my_lo = my_lo.cwiseMin(positions[i]);
        my_hi = my_hi.cwiseMax(positions[i]);
      }
      thread_lo[team_index()] = my_lo;
      thread_hi[team_index()] = my_hi;
    }
    for (int t = 0; t < threads; ++t) {  // minima and maxima are exact: any order
      lo = lo.cwiseMin(thread_lo[t]);
      hi = hi.cwiseMax(thread_hi[t]);
    }
    return {lo, hi};
  }

  // The window of `frame` over the grains' box [lo, hi], then the sort.
  void bin_in(const Frame& frame, const Vec<D>& lo, const Vec<D>& hi,
              std::span<const Vec<D>> positions, std::span<const std::int64_t> id, int threads) {
    periodic_ = false;
    lo_ = frame.lo;
    inv_edge_ = frame.inv_edge;
    frame_dims_ = frame.dims;
    offset_.fill(0);  // frame_coordinate is taken against the whole frame first
    for (int d = 0; d < D; ++d) {
      offset_[d] = frame_coordinate(lo, d);
      dims_[d] = positions.empty() ? 1 : frame_coordinate(hi, d) - offset_[d] + 1;
    }
    bin(positions, id, threads);
  }

  // The frame's cell coordinate of x along axis d (clamped into the frame).
  int frame_coordinate(const Vec<D>& x, int d) const {
    return std::clamp(static_cast<int>((x[d] - lo_[d]) * inv_edge_[d]), 0, frame_dims_[d] - 1);
  }

  // A counting sort by cell, stable (index order within a cell), shared among threads without
  // atomics: each thread owns a run of cells and sweeps all the grains for those in it, counting
  // then placing them, then orders each of its cells by id (a handful of grains: insertion).
  // The runs split the grains evenly when they come nearly in cell order, as they do after the
  // last rebuild's sort.
  void bin(std::span<const Vec<D>> positions, std::span<const std::int64_t> id, int threads) {
    total_ = 1;
    for (int d = 0; d < D; ++d) total_ *= dims_[d];
    const auto n = static_cast<std::int64_t>(positions.size());
    cell_of_.resize(n);
    start_.resize(total_ + 1);
    start_[0] = 0;
    order_.resize(n);
    run_count_.resize(threads);
    std::vector<std::size_t> run_begin(threads + 1, 0), run_grains(threads, 0);
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
#pragma omp for schedule(static)
      for (std::int64_t i = 0; i < n; ++i) cell_of_[i] = cell_index(positions[i]);
      const int t = team_index(), team = team_size();
#pragma omp single
      {
        run_begin[team] = total_;
        for (int s = 1; s < team; ++s)
          run_begin[s] =
              std::max(run_begin[s - 1], n > 0 ? std::size_t{cell_of_[n * s / team]} : 0);
      }
      const std::size_t lo = run_begin[t], cells = run_begin[t + 1] - lo;
      std::vector<std::uint32_t>& count = run_count_[t];
      count.assign(cells, 0);
      for (std::int64_t i = 0; i < n; ++i) {
        const std::size_t c = cell_of_[i] - lo;  // wraps for a cell below the run
        if (c < cells) ++count[c];
      }
      std::uint32_t grains = 0;
      for (std::uint32_t& c : count) grains += std::exchange(c, grains);  // exclusive sums
      run_grains[t] = grains;
#pragma omp barrier
      std::uint32_t offset = 0;
      for (int s = 0; s < t; ++s) offset += run_grains[s];
      for (std::size_t c = 0; c < cells; ++c) start_[lo + c] = count[c] += offset;
      if (t == team - 1) start_[total_] = offset + grains;
      for (std::int64_t i = 0; i < n; ++i) {
        const std::size_t c = cell_of_[i] - lo;
        if (c < cells) order_[count[c]++] = static_cast<std::uint32_t>(i);
      }
      if (!id.empty())  // count[c] is now where cell lo + c ends
        for (std::size_t c = 0; c < cells; ++c) {
          const std::uint32_t begin = start_[lo + c];
          for (std::uint32_t k = begin + 1; k < count[c]; ++k)
            for (std::uint32_t m = k; m > begin && id[order_[m]] < id[order_[m - 1]]; --m)
              std::swap(order_[m], order_[m - 1]);
        }
    }
  }

  std::uint32_t cell_index(const Vec<D>& x) const {
    std::size_t linear = 0, stride = 1;
    for (int d = 0; d < D; ++d) {
      const int k = frame_coordinate(x, d) - offset_[d];
      linear += static_cast<std::size_t>(k) * stride;
      stride *= dims_[d];
    }
    return static_cast<std::uint32_t>(linear);
  }

  // Cells first..last (inclusive) along the first axis of the row whose first cell is `row`:
  // the part inside the grid, or each wrapped around a periodic box, in that order.
  template <class Visit>
  void visit_row(std::size_t row, int first, int last, Visit& visit) const {
    if (!periodic_) {
      first = std::max(first, 0);
      last = std::min(last, dims_[0] - 1);
      if (first <= last) visit(row + first, row + last + 1);
      return;
    }
    for (int x = first; x <= last;) {
      const int begin = (x + dims_[0]) % dims_[0];
      int end = begin + 1;
      for (++x; x <= last && (x + dims_[0]) % dims_[0] == end; ++x) ++end;
      visit(row + begin, row + end);
    }
  }

  // Offsets in {-1,0,1}^(D-1) of the other axes whose last non-zero component is +1, with the
  // first component varying fastest: the forward rows of the half stencil.
  static const std::vector<std::array<int, D - 1>>& forward_rows() {
    static const std::vector<std::array<int, D - 1>> rows = [] {
      std::vector<std::array<int, D - 1>> out;
      std::array<int, D - 1> o;
      for (int n = 0; n < static_cast<int>(std::pow(3, D - 1)); ++n) {
        int rest = n, last_nonzero = 0;
        for (int d = 0; d < D - 1; ++d) {
          o[d] = rest % 3 - 1;
          rest /= 3;
          if (o[d] != 0) last_nonzero = o[d];
        }
        if (last_nonzero == 1) out.push_back(o);
      }
      return out;
    }();
    return rows;
  }

  Vec<D> lo_ = Vec<D>::Zero();
  Vec<D> inv_edge_ = Vec<D>::Ones();
  bool periodic_ = false;
  std::array<int, D> dims_{};        // the window's cells across
  std::array<int, D> offset_{};      // the frame coordinates of the window's first cell
  std::array<int, D> frame_dims_{};  // the frame's cells across
  std::size_t total_ = 0;
  std::vector<std::uint32_t> cell_of_;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> order_;
  std::vector<std::vector<std::uint32_t>> run_count_;  // bin's scratch: per thread, per cell
};

}  // namespace granjet
