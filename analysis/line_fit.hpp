// A least-squares straight line y = a + b x from running sums, for fits taken sample by sample
// during a run (nothing stored per sample).
#pragma once

#include <cstdint>

namespace granjet::analysis {

class LineFit {
 public:
  void add(double x, double y) {
    ++n_;
    sum_x_ += x;
    sum_y_ += y;
    sum_xx_ += x * x;
    sum_xy_ += x * y;
  }
  std::int64_t size() const { return n_; }
  // NaN below two distinct x.
  double slope() const {
    const double n = static_cast<double>(n_);
    return (n * sum_xy_ - sum_x_ * sum_y_) / (n * sum_xx_ - sum_x_ * sum_x_);
  }
  double intercept() const { return (sum_y_ - slope() * sum_x_) / static_cast<double>(n_); }

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("n", n_);
    v("sum_x", sum_x_);
    v("sum_y", sum_y_);
    v("sum_xx", sum_xx_);
    v("sum_xy", sum_xy_);
  }

 private:
  std::int64_t n_ = 0;
  double sum_x_ = 0.0, sum_y_ = 0.0, sum_xx_ = 0.0, sum_xy_ = 0.0;
};

}  // namespace granjet::analysis
