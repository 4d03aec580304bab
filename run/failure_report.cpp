#include "run/failure_report.hpp"

#include <exception>
#include <ostream>
#include <vector>

#include "analysis/file_lock.hpp"
#include "core/errors.hpp"
#include "core/rank_team.hpp"

namespace granjet {

int report_current_exception(std::ostream& err) {
  try {
    throw;
  } catch (const RefusedElsewhere& e) {
    return e.code;
  } catch (const InputError& e) {
    err << "granjet: " << e.what() << "\n";
    return 2;
  } catch (const analysis::FileBusyError& e) {
    err << "granjet: " << e.what() << "; wait for it or name another --out\n";
    return 2;
  } catch (const DiskFullError& e) {
    err << "granjet: " << e.what()
        << "\ngranjet: free space, then go on: `granjet resume RUN.h5.partial` from its last "
           "checkpoint where it holds one (`granjet info` says), else run it again; a campaign: "
           "run it again\n";
    return 4;
  } catch (const BlowUpError& e) {  // while building the grains, before any output
    err << "granjet: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    err << "granjet: " << e.what() << "\n";
    return 1;
  }
}

std::optional<int> check_on_every_rank(const std::function<void()>& check, std::ostream& err) {
  const RankTeam team = RankTeam::world();
  if (team.alone()) {
    check();
    return std::nullopt;
  }
  std::exception_ptr failure;
  try {
    check();
  } catch (...) {
    failure = std::current_exception();
  }
  std::vector<double> first{static_cast<double>(failure ? team.rank() : team.size())};
  team.min(first);
  if (first[0] == team.size()) return std::nullopt;
  std::vector<double> code{0.0};
  if (first[0] == team.rank()) {
    try {
      std::rethrow_exception(failure);
    } catch (...) {
      code[0] = report_current_exception(err);
    }
  }
  team.max(code);
  return static_cast<int>(code[0]);
}

}  // namespace granjet
