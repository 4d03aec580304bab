// What granjet prints and returns for an error that ends a command. Exit codes: 0 done,
// 1 failure (I/O and other errors), 2 bad input, 3 numerical blow-up (output kept as .partial),
// 4 no space left on the disk (the .partial keeps its last checkpoint; resume once space is
// free).
#pragma once

#include <iosfwd>

namespace granjet {

// Called inside a catch block: names the error on `err` ("granjet: ...") and returns its exit
// code.
int report_current_exception(std::ostream& err);

}  // namespace granjet
