#include "app/info_command.hpp"

#include <algorithm>
#include <ostream>
#include <string>

#include "analysis/h5md_reader.hpp"
#include "run/crash_guard.hpp"

namespace granjet {
namespace {

void print_summary(const analysis::FileSummary& summary, std::ostream& out) {
  out << summary.creator << ' ' << summary.creator_version << ", " << summary.backend
      << " backend, " << summary.dimension << "D (H5MD " << summary.h5md_version[0] << '.'
      << summary.h5md_version[1] << ")\n"
      << "status: " << summary.status << '\n'
      << "frames: " << summary.frames << ", up to " << summary.max_grains << " grains";
  if (summary.frames > 0) {
    out << ", t = " << summary.first_time << " .. " << summary.last_time << " (last step "
        << summary.last_step << ')';
  }
  out << "\nobservables: " << summary.observable_rows << " rows\n"
      << "scene: " << std::count(summary.scene_ini.begin(), summary.scene_ini.end(), '\n')
      << " lines of INI stored\n";
  if (!summary.requested_scene_ini.empty())
    out << "requested scene: stored too (the backend adapted it: /parameters/granjet/"
           "requested_scene)\n";
  if (summary.checkpoint)
    out << "checkpoint at t = " << summary.checkpoint_time
        << ": granjet resume continues from it\n";
  if (!summary.members.empty()) {
    out << "ensemble of " << summary.members.size() << " runs (/fields and /analysis combined):";
    for (const std::string& member : summary.members) out << ' ' << member;
    out << '\n';
  }
}

}  // namespace

int info_command(const InfoOptions& options, std::ostream& out) {
  return run_guarded(
      [&] {
        const analysis::FileSummary summary = analysis::read_summary(options.file);
        if (options.scene_only)
          out << summary.scene_ini;
        else
          print_summary(summary, out);
        return 0;
      },
      options.file);
}

}  // namespace granjet
