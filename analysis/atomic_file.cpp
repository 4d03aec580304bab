#include "analysis/atomic_file.hpp"

#include <fstream>
#include <stdexcept>

namespace granjet::analysis {

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  std::filesystem::path partial = path;
  partial += ".partial";
  {
    std::ofstream out(partial);
    if (out) write(out);
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(partial, ignored);
      throw std::runtime_error("'" + path.string() + "': cannot write");
    }
  }
  std::filesystem::rename(partial, path);
}

}  // namespace granjet::analysis
