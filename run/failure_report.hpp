// What granjet prints and returns for an error that ends a command. Exit codes: 0 done,
// 1 failure (I/O and other errors), 2 bad input, 3 numerical blow-up (output kept as .partial),
// 4 no space left on the disk (the .partial keeps its last checkpoint; resume once space is
// free).
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>

namespace granjet {

// Called inside a catch block: names the error on `err` ("granjet: ...") and returns its exit
// code.
int report_current_exception(std::ostream& err);

// An error that every rank mpirun started met alike and that rank 0 names: this rank ends with
// the same exit code and says nothing (report_current_exception returns `code`).
struct RefusedElsewhere {
  int code;
};

// Runs `check`, the reading and checking of a command's inputs, on every rank that mpirun
// started, and lets no rank go on until all have passed it: some checks run on rank 0 alone
// (the outputs it will write), and a rank that fails alone would leave the others waiting for
// it, or end them through MPI_Abort before any could name the error. When `check` fails on
// some rank, the lowest such rank names its error on `err` and every rank returns that
// error's exit code, to end as usual. Without mpirun the error is thrown on. MpiSession must be
// alive.
std::optional<int> check_on_every_rank(const std::function<void()>& check, std::ostream& err);

}  // namespace granjet
