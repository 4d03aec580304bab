// Cells of the event-driven backend. Every grain belongs to one cell and can only touch grains of
// its own and the 3^D - 1 neighbouring cells, so a prediction scans those, and a grain that
// leaves its cell (a cell-crossing event) only has to scan the layer that came into reach.
//
// Cells are at least one largest diameter d plus twice a hysteresis h, and a grain leaves its
// cell only once it is h beyond a face: a grain sitting on a face does not cross back and forth,
// each time an event. (Grains of cells two apart are then more than edge - 2h >= d apart.)
// Periodic boxes are tiled exactly (h is the slack the tiling leaves); open scenes cover a given
// box whose outermost cells reach to infinity: clamping keeps grains that touch within one cell
// of each other, and grains far outside only cost scans of crowded outer cells.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/cell_sizing.hpp"
#include "core/space.hpp"
#include "event_driven/flight.hpp"

namespace granjet::ed {

template <int D>
class CellList {
 public:
  static constexpr int kStencilCells = D == 3 ? 27 : 9;

  // Leaving the cell: in `delay` from the grain's time, across the face `direction` (+-1) of
  // `axis`.
  struct Exit {
    double delay = kNever;
    int axis = 0;
    int direction = 0;
  };

  // The grains in reach of one grain, gathered before any prediction so that the pair loop runs
  // over a flat array: grain[n] has its image near the grain at x + shift[image[n]] when
  // `shifted`, else at x (the shifts and images are then not written). It holds the grain itself: callers
  // skip it or let it fall out (it never approaches itself).
  struct Neighbourhood {
    std::vector<std::uint32_t> grain;
    std::vector<std::uint8_t> image;
    std::array<Vec<D>, kStencilCells> shift;
    std::size_t size = 0;
    bool shifted = false;  // some shift is not zero (the stencil wraps around a periodic box)
  };

  // Tiles [0, box) with at least 3 cells per axis; a dilute box gets larger cells rather than a
  // huge empty grid, as open() does.
  static CellList periodic(const Vec<D>& box, double diameter, std::size_t grains) {
    CellList cells(grains);
    cells.periodic_ = true;
    cells.space_.emplace(box);
    cells.lo_ = Vec<D>::Zero();
    cells.box_ = box;
    const double edge = capped_cell_edge<D>(box, diameter, max_cells(grains), CellFit::kTile);
    for (int a = 0; a < D; ++a) {
      cells.n_[a] = static_cast<int>(std::floor(box[a] / edge));
      if (cells.n_[a] < 3)
        throw std::invalid_argument("periodic box narrower than three grain diameters");
      cells.edge_[a] = box[a] / cells.n_[a];
      cells.hysteresis_[a] = 0.5 * (cells.edge_[a] - diameter);
    }
    cells.allocate();
    return cells;
  }

  // Covers [lo, hi]; grains may leave it.
  static CellList open(const Vec<D>& lo, const Vec<D>& hi, double diameter, std::size_t grains) {
    CellList cells(grains);
    cells.lo_ = lo;
    cells.box_ = hi - lo;
    const double edge = capped_cell_edge<D>(cells.box_, diameter * (1.0 + 2.0 * kOpenHysteresis),
                                            max_cells(grains), CellFit::kCover);
    for (int a = 0; a < D; ++a) {
      cells.n_[a] = std::max(1, static_cast<int>(std::ceil(cells.box_[a] / edge)));
      cells.edge_[a] = edge;
      cells.hysteresis_[a] = 0.5 * (edge - diameter);
    }
    cells.allocate();
    return cells;
  }

  void insert(std::uint32_t grain, const Vec<D>& x) {
    for (int a = 0; a < D; ++a)
      coords_[grain][a] =
          std::clamp(static_cast<int>(std::floor((x[a] - lo_[a]) / edge_[a])), 0, n_[a] - 1);
    link(grain);
  }

  void remove(std::uint32_t grain) {
    const std::uint32_t before = prev_[grain], after = next_[grain];
    if (before == none_)
      head_[linear(coords_[grain])] = after;
    else
      next_[before] = after;
    if (after != none_) prev_[after] = before;
  }

  // Moves the grain into the next cell across its exit face; returns what to add to its position
  // (a box length when it wraps around a periodic box, else zero).
  Vec<D> move(std::uint32_t grain, int axis, int direction) {
    remove(grain);
    int& c = coords_[grain][axis];
    c += direction;
    Vec<D> wrap = Vec<D>::Zero();
    if (c < 0) {
      c += n_[axis];
      wrap[axis] = box_[axis];
    } else if (c >= n_[axis]) {
      c -= n_[axis];
      wrap[axis] = -box_[axis];
    }
    link(grain);
    return wrap;
  }

  // When the grain at position x (at its own time) with velocity v leaves its cell.
  Exit next_exit(std::uint32_t grain, const Vec<D>& x, const Vec<D>& v) const {
    Exit exit;
    const std::array<int, D>& c = coords_[grain];
    for (int a = 0; a < D; ++a) {
      double face;
      int direction;
      if (v[a] > 0.0 && (periodic_ || c[a] < n_[a] - 1)) {
        face = lo_[a] + (c[a] + 1) * edge_[a] + hysteresis_[a];
        direction = 1;
      } else if (v[a] < 0.0 && (periodic_ || c[a] > 0)) {
        face = lo_[a] + c[a] * edge_[a] - hysteresis_[a];
        direction = -1;
      } else {
        continue;
      }
      const double delay = (face - x[a]) / v[a];
      if (delay < exit.delay) exit = {delay, a, direction};
    }
    exit.delay = std::max(exit.delay, 0.0);
    return exit;
  }

  // The periodic image of a separation vector with the shortest components.
  Vec<D> minimum_image(const Vec<D>& dr) const {
    return periodic_ ? space_->minimum_image(dr) : dr;
  }

  // The periodic box itself (periodic lists only), for loops that take many minimum images.
  const PeriodicBox<D>& space() const { return *space_; }

  // The image of a position inside a periodic box, [0, box) per axis.
  Vec<D> wrap(Vec<D> x) const {
    if (periodic_) space_->wrap(x);
    return x;
  }

  // Every grain in reach of `grain`, itself included.
  void gather(std::uint32_t grain, Neighbourhood& out) const {
    Stencil s;
    for (int a = 0; a < D; ++a) add_offsets(s, a, coords_[grain][a], -1, 1);
    if (s.wraps)
      gather_stencil<3, true>(s, out);
    else
      gather_stencil<3, false>(s, out);
  }

  // Only the layer of cells that came into reach when the grain moved across a face of `axis`
  // in `direction`.
  void gather_new_layer(std::uint32_t grain, int axis, int direction, Neighbourhood& out) const {
    Stencil s;
    for (int a = 0; a < D; ++a)
      if (a == axis)
        add_offsets(s, a, coords_[grain][a], direction, direction);
      else
        add_offsets(s, a, coords_[grain][a], -1, 1);
    if (s.wraps)
      gather_stencil<0, true>(s, out);
    else
      gather_stencil<0, false>(s, out);
  }

 private:
  static constexpr double kOpenHysteresis = 0.05;  // in diameters
  // Empty cells cost memory only (an event touches the cells around it), and narrow cells
  // keep every prediction's scan short: many per grain (core/cell_sizing.hpp).
  static constexpr double kMaxCellsPerGrain = 128.0;
  static double max_cells(std::size_t grains) {
    return kMaxCellsPerGrain * static_cast<double>(grains) + 4096.0;
  }

  // Grain index `none_` (one past the last grain) ends every cell's list, and its own next is
  // itself, so that walking on past the end of a list stays at the end.
  explicit CellList(std::size_t grains)
      : none_(static_cast<std::uint32_t>(grains)),
        coords_(grains),
        next_(grains + 1, none_),
        prev_(grains, none_) {}

  // One cell more than the grid: the always empty stand-in for neighbours beyond an open edge.
  void allocate() {
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) total *= static_cast<std::size_t>(n_[a]);
    head_.assign(total + 1, none_);
    outside_cell_ = total;
  }

  std::size_t linear(const std::array<int, D>& c) const {
    std::size_t index = 0;
    for (int a = D - 1; a >= 0; --a) index = index * n_[a] + c[a];
    return index;
  }

  void link(std::uint32_t grain) {
    std::uint32_t& first = head_[linear(coords_[grain])];
    prev_[grain] = none_;
    next_[grain] = first;
    if (first != none_) prev_[first] = grain;
    first = grain;
  }

  // Per axis, the cell coordinates in reach and the image shift of their grains; kOutside for
  // a neighbour beyond the edge of an open grid. A linear index with any kOutside coordinate is
  // negative (the grid has fewer than 2^31 cells) and stands for an empty cell.
  static constexpr std::int64_t kOutside = -(std::int64_t{1} << 31);
  struct Stencil {
    std::array<std::array<std::int64_t, 3>, D> index;
    std::array<std::array<double, 3>, D> shift;
    std::array<int, D> count{};
    bool wraps = false;
  };

  void add_offsets(Stencil& s, int a, int c, int first, int last) const {
    for (int o = first; o <= last; ++o) {
      std::int64_t k = c + o;
      double shift = 0.0;
      if (k < 0 || k >= n_[a]) {
        if (periodic_) {
          shift = k < 0 ? -box_[a] : box_[a];
          k = k < 0 ? k + n_[a] : k - n_[a];
        } else {
          k = kOutside;
        }
      }
      s.index[a][s.count[a]] = k;
      s.shift[a][s.count[a]] = shift;
      s.wraps |= shift != 0.0;
      ++s.count[a];
    }
  }

  // kCount 3: the full stencil, with loops of fixed length that the compiler unrolls; 0: the
  // counts of the stencil (a layer). The cells are listed first, then read in one loop whose
  // count and pointers are locals: the image bytes written may alias any member, which would
  // force them through memory, the count a loop-carried store and reload per cell. kWraps: the
  // stencil wraps around the box (Stencil::wraps); else no image is read, and none is written.
  template <int kCount, bool kWraps>
  void gather_stencil(const Stencil& s, Neighbourhood& out) const {
    std::array<std::size_t, kStencilCells> cells;
    std::uint8_t m = 0;
    std::array<int, D> pick{};
    walk<D - 1, kCount>(s, 0, pick, out, cells, m);
    // Room for two slots per cell up front; only the rare longer lists check again.
    if (out.grain.size() < 2 * kStencilCells + 2) {
      out.grain.resize(2 * kStencilCells + 2);
      out.image.resize(2 * kStencilCells + 2);
    }
    const std::uint32_t* const head = head_.data();
    const std::uint32_t* const next = next_.data();
    const std::uint32_t none = none_;
    std::uint32_t* slot = out.grain.data();
    std::uint8_t* slot_image = out.image.data();
    std::size_t n = 0;
    for (std::uint8_t c = 0; c < m; ++c) {
      // Cells hold 0, 1 or 2 grains most of the time, and which is as good as random: the
      // first two are taken without a data-dependent branch (a slot is written always and kept
      // only for a real grain), the rare rest by a loop. The grain itself is gathered too: a
      // pair of a grain with itself never approaches, which costs less than a test per slot.
      const std::uint32_t k0 = head[cells[c]];
      const std::uint32_t k1 = next[k0];
      slot[n] = k0;
      slot[n + 1] = k1;
      if constexpr (kWraps) {
        slot_image[n] = c;
        slot_image[n + 1] = c;
      }
      n += (k0 != none) + (k1 != none);
      for (std::uint32_t k = next[k1]; k != none; k = next[k]) {
        // Keep two slots of room for each cell still to come.
        if (out.grain.size() < n + 2 * kStencilCells + 2) {
          out.grain.resize(2 * out.grain.size() + 2 * kStencilCells);
          out.image.resize(out.grain.size());
          slot = out.grain.data();
          slot_image = out.image.data();
        }
        if constexpr (kWraps) slot_image[n] = c;
        slot[n++] = k;
      }
    }
    out.size = n;
    out.shifted = kWraps;
  }

  // Lists the cells of the stencil, the m-th with image m; pick[a] is the stencil entry taken
  // on axis a. (The image shift is written a component at a time: building it in a stack
  // vector a component at a time and storing it whole stalls on store forwarding.)
  template <int A, int kCount>
  void walk(const Stencil& s, std::int64_t base, std::array<int, D>& pick, Neighbourhood& out,
            std::array<std::size_t, kStencilCells>& cells, std::uint8_t& m) const {
    const int count = kCount > 0 ? kCount : s.count[A];
    for (int o = 0; o < count; ++o) {
      pick[A] = o;
      const std::int64_t cell = base * n_[A] + s.index[A][o];
      if constexpr (A == 0) {
        if (s.wraps)
          for (int a = 0; a < D; ++a) out.shift[m][a] = s.shift[a][pick[a]];
        cells[m++] = cell < 0 ? outside_cell_ : static_cast<std::size_t>(cell);
      } else {
        walk<A - 1, kCount>(s, cell, pick, out, cells, m);
      }
    }
  }

  std::uint32_t none_;
  bool periodic_ = false;
  Vec<D> lo_ = Vec<D>::Zero();
  Vec<D> box_ = Vec<D>::Zero();          // periodic: the box lengths
  std::optional<PeriodicBox<D>> space_;  // periodic: the minimum image and the wrap
  std::array<int, D> n_{};
  Vec<D> edge_ = Vec<D>::Zero();
  Vec<D> hysteresis_ = Vec<D>::Zero();
  std::vector<std::uint32_t> head_;  // first grain of each cell
  std::size_t outside_cell_ = 0;
  std::vector<std::array<int, D>> coords_;
  std::vector<std::uint32_t> next_, prev_;  // doubly linked grains of a cell
};

}  // namespace granjet::ed
