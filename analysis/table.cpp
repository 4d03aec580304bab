#include "analysis/table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace granjet::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int index_of(const std::vector<std::string>& names, std::string_view name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

Spread spread_of(const std::vector<double>& values) {
  Spread s;
  double sum = 0.0;
  for (double v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++s.count;
    }
  if (s.count == 0) return {kNaN, kNaN, kNaN, 0};
  s.mean = sum / s.count;
  double squares = 0.0;
  for (double v : values)
    if (std::isfinite(v)) squares += (v - s.mean) * (v - s.mean);
  s.std = s.count > 1 ? std::sqrt(squares / (s.count - 1)) : kNaN;
  s.sem = s.std / std::sqrt(static_cast<double>(s.count));
  return s;
}

}  // namespace

int Table::find(std::string_view name) const { return index_of(names_, name); }

void Table::set(std::string_view name, std::size_t row, double value) {
  if (row >= rows_) throw std::out_of_range("table row " + std::to_string(row) + " out of range");
  int k = find(name);
  if (k < 0) {
    names_.emplace_back(name);
    columns_.emplace_back(rows_, kNaN);
    k = static_cast<int>(names_.size()) - 1;
  }
  columns_[k][row] = value;
}

const std::vector<double>& Table::column(std::string_view name) const {
  const int k = find(name);
  if (k < 0) throw std::out_of_range("no column '" + std::string(name) + "'");
  return columns_[k];
}

EnsembleTable::EnsembleTable(std::span<const Table> runs) {
  if (runs.empty()) throw std::invalid_argument("ensemble of no runs");
  rows_ = runs.front().rows();
  names_ = runs.front().names();
  for (const Table& run : runs)
    if (run.rows() != rows_ || run.names() != names_)
      throw std::invalid_argument("ensemble runs differ in their bins or quantities");
  std::vector<double> values(runs.size());
  for (const std::string& name : names_) {
    std::vector<Spread>& column = columns_.emplace_back();
    for (std::size_t row = 0; row < rows_; ++row) {
      for (std::size_t r = 0; r < runs.size(); ++r) values[r] = runs[r].at(row, name);
      column.push_back(spread_of(values));
    }
  }
}

int EnsembleTable::find(std::string_view name) const { return index_of(names_, name); }

const Spread& EnsembleTable::at(std::size_t row, std::string_view name) const {
  const int k = find(name);
  if (k < 0) throw std::out_of_range("no column '" + std::string(name) + "'");
  return columns_[k].at(row);
}

std::vector<double> EnsembleTable::means(std::string_view name) const {
  std::vector<double> out;
  for (std::size_t row = 0; row < rows_; ++row) out.push_back(at(row, name).mean);
  return out;
}

}  // namespace granjet::analysis
