// The measurement mesh of model §6 in the two coordinates every bin geometry shares: a lateral
// coordinate (3D: distance r from the jet axis; 2D: y) and the height h above the height origin
// (3D: z; 2D: x). Bins are a uniform lateral x height grid; for the strain rates each bin is also
// cut into half-cells (half a bin in each direction), on a grid that extends half a bin beyond
// both lateral ends so that bins shifted laterally by half a bin exist at the borders.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace granjet::analysis {

// The mesh sizes, from the scene's [analysis] section.
struct BinSpec {
  double target_radius = 11.0;  // R_tar: 3D rings cover 0..R_tar, 2D bins -R_tar..R_tar
  // Where h = 0 lies on the jet axis (3D z, 2D x). The study does not say whether its "from the
  // wall z = 0" means the target grains' centre plane (0) or their top surface (0.5); the scene
  // key analysis.height_origin chooses (AnalysisConfig::for_scene).
  double height_origin = 0.0;
  int lateral_bins = 5;  // 3D: rings of width R_tar/5; 2D: 10 bins of width 2 R_tar/10
  int layers = 1;        // 3D: one layer 0..5 d; 2D: (a) 0..5 d and (b) 5..10 d
  double layer_height = 5.0;
};

// Bin borders: lateral (r or y) and height above the wall, ascending.
struct MeshEdges {
  std::vector<double> lateral;
  std::vector<double> height;
  double height_origin = 0.0;  // BinSpec::height_origin: where height 0 lies on the jet axis
};

class BinGrid {
 public:
  BinGrid(double lateral_lo, double lateral_hi, int lateral_bins, double layer_height, int layers)
      : lateral_lo_(lateral_lo),
        width_((lateral_hi - lateral_lo) / lateral_bins),
        height_(layer_height),
        lateral_bins_(lateral_bins),
        layers_(layers) {}

  int lateral_bins() const { return lateral_bins_; }
  int layers() const { return layers_; }
  int size() const { return lateral_bins_ * layers_; }
  double lateral_width() const { return width_; }
  double layer_height() const { return height_; }
  double lateral_edge(int k) const { return lateral_lo_ + k * width_; }  // k = 0..lateral_bins
  double normal_edge(int l) const { return l * height_; }                // l = 0..layers
  double top() const { return layers_ * height_; }
  MeshEdges edges() const {
    MeshEdges e;
    for (int k = 0; k <= lateral_bins_; ++k) e.lateral.push_back(lateral_edge(k));
    for (int l = 0; l <= layers_; ++l) e.height.push_back(normal_edge(l));
    return e;
  }

  // Bins are numbered layer by layer: bin = layer * lateral_bins + lateral.
  int bin(int lateral, int layer) const { return layer * lateral_bins_ + lateral; }
  int lateral_of(int bin) const { return bin % lateral_bins_; }
  int layer_of(int bin) const { return bin / lateral_bins_; }
  // The bin holding (lateral, h), or -1 outside the mesh.
  int bin_at(double lateral, double h) const {
    const int k = cell(lateral - lateral_lo_, width_);
    const int l = cell(h, height_);
    return k < 0 || k >= lateral_bins_ || l < 0 || l >= layers_ ? -1 : bin(k, l);
  }

  // The lateral bins [first, last] that the interval [lo, hi] touches, clamped to the mesh;
  // first > last when it misses the mesh. The same for layers.
  std::pair<int, int> lateral_range(double lo, double hi) const {
    return clamped(cell(lo - lateral_lo_, width_), cell(hi - lateral_lo_, width_), lateral_bins_);
  }
  std::pair<int, int> layer_range(double lo, double hi) const {
    return clamped(cell(lo, height_), cell(hi, height_), layers_);
  }

  // Half-cells: lateral index a covers [lateral_edge(0) + (a-1) w/2, ... + a w/2), so bin k holds
  // a = 2k+1 and 2k+2; normal index b covers [b h/2, (b+1) h/2), so layer l holds b = 2l, 2l+1.
  int half_lateral() const { return 2 * lateral_bins_ + 2; }
  int half_normal() const { return 2 * layers_; }
  int half_cells() const { return half_lateral() * half_normal(); }
  int half_cell(int a, int b) const { return b * half_lateral() + a; }
  int half_cell_at(double lateral, double h) const {
    const int a = cell(lateral - lateral_lo_ + 0.5 * width_, 0.5 * width_);
    const int b = cell(h, 0.5 * height_);
    return a < 0 || a >= half_lateral() || b < 0 || b >= half_normal() ? -1 : half_cell(a, b);
  }

 private:
  static std::pair<int, int> clamped(int first, int last, int n) {
    if (last < 0 || first >= n) return {1, 0};
    return {std::max(first, 0), std::min(last, n - 1)};
  }
  static int cell(double offset, double size) {
    const double c = std::floor(offset / size);
    return c < -1.0 ? -1 : c > 1e9 ? 1000000000 : static_cast<int>(c);  // no overflow far away
  }

  double lateral_lo_;
  double width_;
  double height_;
  int lateral_bins_;
  int layers_;
};

}  // namespace granjet::analysis
