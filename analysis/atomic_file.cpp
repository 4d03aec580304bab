#include "analysis/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

namespace granjet::analysis {

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  std::filesystem::path partial = path;
  partial += ".partial";
  {
    errno = 0;
    std::ofstream out(partial);
    if (out) write(out);
    out.close();
    if (!out) {
      // The stream keeps no reason; errno holds the failed call's (a full disk: ENOSPC).
      const int error = errno;
      std::error_code ignored;
      std::filesystem::remove(partial, ignored);
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "'" + std::string.
      std::string what = "'";
      what.append(path.string()).append("': cannot write");
      if (error != 0) what.append(": ").append(std::strerror(error));
      if (error == ENOSPC || error == EDQUOT) throw DiskFullError(what);
      throw std::runtime_error(what);
    }
  }
  std::filesystem::rename(partial, path);
}

}  // namespace granjet::analysis
