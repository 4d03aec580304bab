#include "run/run_log.hpp"

#include <stdexcept>

namespace granjet {

std::filesystem::path log_path_for(const std::filesystem::path& run_file) {
  std::filesystem::path log = run_file;
  return log.replace_extension(".log");
}

RunLog::RunLog(const std::filesystem::path& file, bool append, std::ostream* terminal)
    : tee_(terminal, file.empty() ? nullptr : &out_),
      report_(&tee_),
      only_file_(file.empty() ? nullptr : out_.rdbuf()) {
  if (file.empty()) return;
  out_.open(file, append ? std::ios::app : std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write the run log " + file.string());
}

RunLog::Tee::int_type RunLog::Tee::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  const char ch = traits_type::to_char_type(c);
  for (std::ostream* s : {a_, b_})
    if (s != nullptr) s->put(ch);
  return c;
}

std::streamsize RunLog::Tee::xsputn(const char* s, std::streamsize n) {
  for (std::ostream* out : {a_, b_})
    if (out != nullptr) out->write(s, n);
  return n;
}

// std::flush on report() flushes both: a long run's log is readable while it runs.
int RunLog::Tee::sync() {
  for (std::ostream* s : {a_, b_})
    if (s != nullptr) s->flush();
  return 0;
}

}  // namespace granjet
