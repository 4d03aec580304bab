// `granjet run --profile`: the run loop's wall time split by phase (core/phase_profile.hpp),
// for the summary and the log, with the serial share: the part of the loop that ran on one
// thread while the others waited, which bounds the speed-up at any thread count (Amdahl).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/phase_profile.hpp"

namespace granjet {

// {"loop_seconds", "threads", "phases": [{"name", "kind", "seconds", "calls", "share"}],
//  "untimed_seconds", "serial_seconds", "serial_share", "amdahl_limit"}: shares of the loop's
// wall time; amdahl_limit is the speed-up no thread count exceeds, 1 / serial share. A phase
// with shared-out loops adds "work_seconds" (its threads' mean time on their shares) and
// "slowest_seconds" (the slowest share's), summed over its loops and calls. by_rank: each MPI
// rank's phase seconds (Simulator::phase_seconds_by_rank; the first row is the profile's own);
// over several ranks, "ranks" gives their count and every phase "over_ranks": {"fastest",
// "mean", "slowest"}, the fastest rank's seconds, the mean over ranks and the slowest rank's,
// as LAMMPS's MPI timing breakdown gives them (a rank without the phase counts zero).
nlohmann::json profile_json(const PhaseProfile& profile, double loop_seconds, int threads,
                            const std::vector<std::vector<double>>& by_rank = {});

// The same as a table for the terminal and the log.
std::string profile_text(const nlohmann::json& profile);

}  // namespace granjet
