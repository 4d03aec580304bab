// Named columns of measured values and their statistics over an ensemble of seeds. One row per
// bin for the fields, per histogram bin for distributions, or a single row for global values.
// Names may hold dots ("stress.rz"); the JSON and HDF5 writers nest on them.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace granjet::analysis {

class Table {
 public:
  explicit Table(std::size_t rows = 0) : rows_(rows) {}

  std::size_t rows() const { return rows_; }
  const std::vector<std::string>& names() const { return names_; }
  bool has(std::string_view name) const { return find(name) >= 0; }
  // Sets one value; the first use of a name adds its column, filled with NaN.
  void set(std::string_view name, std::size_t row, double value);
  // Throws std::out_of_range naming the column when there is none.
  double at(std::size_t row, std::string_view name) const { return column(name).at(row); }
  const std::vector<double>& column(std::string_view name) const;

 private:
  int find(std::string_view name) const;

  std::size_t rows_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
};

// Statistics of one value over the seeds whose value is finite (an empty bin gives NaN).
struct Spread {
  double mean = 0.0;
  double std = 0.0;  // sample standard deviation (n - 1); NaN for fewer than two values
  double sem = 0.0;  // standard error of the mean, std / sqrt(count)
  int count = 0;
};

class EnsembleTable {
 public:
  EnsembleTable() = default;
  // Every table must have the same rows and names (the same scene analysed per seed); throws
  // std::invalid_argument otherwise or when `runs` is empty.
  explicit EnsembleTable(std::span<const Table> runs);

  std::size_t rows() const { return rows_; }
  const std::vector<std::string>& names() const { return names_; }
  bool has(std::string_view name) const { return find(name) >= 0; }
  const Spread& at(std::size_t row, std::string_view name) const;
  std::vector<double> means(std::string_view name) const;

 private:
  int find(std::string_view name) const;

  std::size_t rows_ = 0;
  std::vector<std::string> names_;
  std::vector<std::vector<Spread>> columns_;
};

}  // namespace granjet::analysis
