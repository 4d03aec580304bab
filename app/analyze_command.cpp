#include "app/analyze_command.hpp"

#include <ostream>

#include "analysis/analysis_json.hpp"
#include "analysis/field_writer.hpp"
#include "core/errors.hpp"
#include "run/crash_guard.hpp"
#include "run/ensemble_output.hpp"
#include "run/frame_replay.hpp"

namespace granjet {

int analyze_command(const AnalyzeOptions& options, std::ostream& out) {
  if (options.window && !(options.window->second > options.window->first))
    throw InputError("--window", "expected t0:t1 with t1 > t0");
  const auto analyse = [&] {
    const Reanalysis done = reanalyse_frames(options.file, options.window);
    out << "analysed " << done.frames << " frames of " << done.runs
        << " run(s); wrote /fields and /analysis into " << options.file.string() << " and "
        << analysis::fields_sidecar(options.file).string() << "\n";
    if (!options.summary.empty())
      write_json_atomically(options.summary, analysis::to_json(done.result));
    return 0;
  };
  return run_guarded(analyse, options.file, reanalysis_copy(options.file));
}

}  // namespace granjet
