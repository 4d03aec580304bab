// The list centres of the neighbour shells (event_driven/neighbour_shells.hpp) binned in the
// cells of a periodic box, each cell's centres side by side in slots of their own: a renewal
// reads its 3^D cells as a few contiguous runs instead of walking linked lists grain by grain,
// and takes each candidate's centre and radius from the slot, where the test needs them. A
// grain's slot is kept by grain (back-index), so that it leaves its cell without a search.
//
// Cells are at least `reach` wide, three or more per axis: every centre within reach of a
// point lies in the point's cell or a neighbouring one, in the image the stencil gives it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/space.hpp"

namespace granjet::ed {

template <int D>
class CentreGrid {
 public:
  static constexpr int kStencilCells = D == 3 ? 27 : 9;

  CentreGrid(const Vec<D>& box, double reach, std::size_t grains)
      : box_(box), where_(grains, kAbsent) {
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) {
      n_[a] = static_cast<int>(std::floor(box[a] / reach));
      if (n_[a] < 3) throw std::invalid_argument("periodic box narrower than three cells");
      edge_[a] = box[a] / n_[a];
      stride_[a] = total;
      total *= static_cast<std::size_t>(n_[a]);
    }
    count_.assign(total, 0);
    slot_.resize(total * room_);
    grain_.resize(total * room_);
  }

  // Empties every cell.
  void clear() {
    std::fill(count_.begin(), count_.end(), 0);
    std::fill(where_.begin(), where_.end(), kAbsent);
  }

  // x in the box.
  void insert(std::uint32_t grain, const Vec<D>& x, double radius) {
    const std::size_t cell = cell_of(x);
    if (count_[cell] == room_) widen();
    const std::size_t at = cell * room_ + count_[cell]++;
    slot_[at] = {x, radius};
    grain_[at] = grain;
    where_[grain] = at;
  }

  // The last centre of the cell takes the grain's slot (order within a cell is not kept).
  void remove(std::uint32_t grain) {
    const std::size_t at = where_[grain];
    const std::size_t cell = at / room_;
    const std::size_t last = cell * room_ + --count_[cell];
    slot_[at] = slot_[last];
    grain_[at] = grain_[last];
    where_[grain_[at]] = at;
    where_[grain] = kAbsent;
  }

  const Vec<D>& centre(std::uint32_t grain) const { return slot_[where_[grain]].x; }
  double radius(std::uint32_t grain) const { return slot_[where_[grain]].radius; }

  // Writes to out[0, n) the n grains whose centres (nearest image) lie closer than
  // shell (radius + r_k) to x (in the box), in the order of the cells, and returns n. A grain
  // at x itself is among them. The candidates are written all and kept by a count, without a
  // branch on the test: most fail it, as good as at random.
  std::size_t gather_within(const Vec<D>& x, double radius, double shell,
                            std::vector<std::uint32_t>& out) const {
    std::array<std::array<std::size_t, 3>, D> index;
    std::array<std::array<double, 3>, D> shift;
    for (int a = 0; a < D; ++a) {
      const int c = std::clamp(static_cast<int>(std::floor(x[a] / edge_[a])), 0, n_[a] - 1);
      for (int o = 0; o < 3; ++o) {
        int k = c + o - 1;
        double s = 0.0;
        if (k < 0) {
          k += n_[a];
          s = -box_[a];
        } else if (k >= n_[a]) {
          k -= n_[a];
          s = box_[a];
        }
        index[a][o] = static_cast<std::size_t>(k) * stride_[a];
        shift[a][o] = s;
      }
    }
    std::size_t found = 0;
    for (int m = 0; m < kStencilCells; ++m) {
      std::size_t cell = 0;
      Vec<D> s;
      for (int a = 0, rest = m; a < D; ++a, rest /= 3) {
        cell += index[a][rest % 3];
        s[a] = shift[a][rest % 3];
      }
      const std::uint32_t count = count_[cell];
      if (out.size() < found + count) out.resize(2 * (found + count) + 64);
      const Slot* slot = slot_.data() + cell * room_;
      const std::uint32_t* grain = grain_.data() + cell * room_;
      std::uint32_t* o = out.data();
      for (std::uint32_t j = 0; j < count; ++j) {
        const double reach = shell * (radius + slot[j].radius);
        const Vec<D> dr = slot[j].x + s - x;
        o[found] = grain[j];
        found += dr.squaredNorm() < reach * reach;
      }
    }
    return found;
  }

 private:
  static constexpr std::size_t kAbsent = ~std::size_t{0};

  std::size_t cell_of(const Vec<D>& x) const {
    std::size_t cell = 0;
    for (int a = 0; a < D; ++a)
      cell += static_cast<std::size_t>(
                  std::clamp(static_cast<int>(std::floor(x[a] / edge_[a])), 0, n_[a] - 1)) *
              stride_[a];
    return cell;
  }

  // A cell is full: every cell gets twice the room (rare after the first renewals).
  void widen() {
    std::vector<Slot> wider(slot_.size() * 2);
    std::vector<std::uint32_t> wider_grain(wider.size());
    for (std::size_t c = 0; c < count_.size(); ++c)
      for (std::uint32_t j = 0; j < count_[c]; ++j) {
        wider[c * 2 * room_ + j] = slot_[c * room_ + j];
        wider_grain[c * 2 * room_ + j] = grain_[c * room_ + j];
        where_[grain_[c * room_ + j]] = c * 2 * room_ + j;
      }
    slot_ = std::move(wider);
    grain_ = std::move(wider_grain);
    room_ *= 2;
  }

  // What a candidate's test reads, two to a cache line (3D); the grains kept are in grain_.
  struct Slot {
    Vec<D> x = Vec<D>::Zero();
    double radius = 0.0;
  };

  Vec<D> box_;
  std::array<int, D> n_{};
  std::array<std::size_t, D> stride_{};
  Vec<D> edge_ = Vec<D>::Zero();
  std::uint32_t room_ = 8;
  std::vector<std::uint32_t> count_;
  std::vector<Slot> slot_;            // cell c's centres at [c * room_, + count_[c])
  std::vector<std::uint32_t> grain_;  // and whose they are
  std::vector<std::size_t> where_;    // each grain's slot
};

}  // namespace granjet::ed
