#include "run/failure_report.hpp"

#include <exception>
#include <ostream>

#include "analysis/file_lock.hpp"
#include "core/errors.hpp"

namespace granjet {

int report_current_exception(std::ostream& err) {
  try {
    throw;
  } catch (const InputError& e) {
    err << "granjet: " << e.what() << "\n";
    return 2;
  } catch (const analysis::FileBusyError& e) {
    err << "granjet: " << e.what() << "; wait for it or name another --out\n";
    return 2;
  } catch (const DiskFullError& e) {
    err << "granjet: " << e.what()
        << "\ngranjet: free space, then go on: `granjet resume RUN.h5.partial` from its last "
           "checkpoint where it holds one (`granjet info` says), else run it again; a campaign: "
           "run it again\n";
    return 4;
  } catch (const BlowUpError& e) {  // while building the grains, before any output
    err << "granjet: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    err << "granjet: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace granjet
