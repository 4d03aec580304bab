// SIGINT, SIGTERM and SIGHUP while a run goes: the first asks it to stop after the current step
// or event, after which it writes a checkpoint and its sidecars, says how to resume and exits
// 128 + the signal (130, 143, 129); a second one exits at once.
#pragma once

#include <atomic>

namespace granjet {

class Interrupts {
 public:
  Interrupts();   // installs the handlers
  ~Interrupts();  // and puts the earlier ones back
  Interrupts(const Interrupts&) = delete;
  Interrupts& operator=(const Interrupts&) = delete;

  // Set by the first signal: what Simulator::stop_when watches.
  const std::atomic<bool>& stop_flag() const;
  // The signal that asked to stop; 0 if none did.
  int signal() const;
};

}  // namespace granjet
