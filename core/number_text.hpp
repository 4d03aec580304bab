// A number as messages show it: six significant digits, the stream's default.
#pragma once

#include <sstream>
#include <string>

namespace granjet {

inline std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace granjet
