// `<out stem>.log` beside a run's output, as LAMMPS's log.lammps: what the terminal shows of
// the run (progress rows, warnings, timings), plus the command, the resolved scene and the
// summary, so that a run's folder tells its story without the terminal. A resume appends.
#pragma once

#include <filesystem>
#include <fstream>
#include <ostream>
#include <streambuf>

namespace granjet {

// The log beside a run file: run.h5 -> run.log.
std::filesystem::path log_path_for(const std::filesystem::path& run_file);

class RunLog {
 public:
  // No file when `file` is empty; no terminal when `terminal` is null (--quiet). Throws
  // std::runtime_error naming the file when it cannot be opened.
  RunLog(const std::filesystem::path& file, bool append, std::ostream* terminal);
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;

  // Both the terminal and the log.
  std::ostream& report() { return report_; }
  // The log alone (discards when there is none).
  std::ostream& file() { return only_file_; }

 private:
  // Writes every character to up to two streams.
  class Tee : public std::streambuf {
   public:
    Tee(std::ostream* a, std::ostream* b) : a_(a), b_(b) {}

   protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;
    int sync() override;

   private:
    std::ostream* a_;
    std::ostream* b_;
  };

  std::ofstream out_;
  Tee tee_;
  std::ostream report_;
  std::ostream only_file_;
};

}  // namespace granjet
