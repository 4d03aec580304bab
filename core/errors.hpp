// Error types shared by every layer; the app maps them to exit codes.
#pragma once

#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/particles.hpp"

namespace granjet {

// Bad user input: names the key (or file) and what is allowed. Exit code 2.
class InputError : public std::runtime_error {
 public:
  InputError(std::string key, const std::string& message)
      : std::runtime_error(key + ": " + message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// A write that found no space left (ENOSPC, or a quota: EDQUOT). Exit code 4: the run's
// .partial keeps its last checkpoint, and `granjet resume` goes on from it once space is free.
class DiskFullError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that went numerically wrong (NaN, overlap beyond the allowed fraction).
class BlowUpError : public std::runtime_error {
 public:
  BlowUpError(const std::string& what, std::int64_t step, double time, std::vector<GrainId> ids)
      : std::runtime_error(message(what, step, time, ids)),
        reason_(what),
        step_(step),
        time_(time),
        ids_(std::move(ids)) {}
  // What went wrong, without the step, time and grains.
  const std::string& reason() const { return reason_; }
  std::int64_t step() const { return step_; }
  double time() const { return time_; }
  const std::vector<GrainId>& grain_ids() const { return ids_; }

 private:
  static std::string message(const std::string& what, std::int64_t step, double time,
                             const std::vector<GrainId>& ids) {
    std::ostringstream s;
    s << "blow-up at step " << step << " (t = " << time << "): " << what << "; grains";
    for (GrainId id : ids) s << " " << id;
    return s.str();
  }
  std::string reason_;
  std::int64_t step_;
  double time_;
  std::vector<GrainId> ids_;
};

}  // namespace granjet
