#include "run/interrupts.hpp"

#include <unistd.h>

#include <array>
#include <csignal>

namespace granjet {
namespace {

constexpr std::array<int, 3> kSignals = {SIGINT, SIGTERM, SIGHUP};
// A handler may only touch lock-free atomics and sig_atomic_t.
std::atomic<bool> stop{false};
volatile std::sig_atomic_t received = 0;
std::array<struct sigaction, kSignals.size()> earlier{};

extern "C" void on_signal(int signal) {
  if (received != 0) _exit(128 + signal);  // the second: at once
  received = signal;
  stop.store(true, std::memory_order_relaxed);
}

}  // namespace

Interrupts::Interrupts() {
  stop.store(false);
  received = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigset_t wanted;
  sigemptyset(&wanted);
  for (std::size_t k = 0; k < kSignals.size(); ++k) {
    sigaction(kSignals[k], &action, &earlier[k]);
    sigaddset(&wanted, kSignals[k]);
  }
  // A launcher may hand the run its own blocked mask (exec keeps it): the signals must arrive.
  sigprocmask(SIG_UNBLOCK, &wanted, nullptr);
}

Interrupts::~Interrupts() {
  for (std::size_t k = 0; k < kSignals.size(); ++k) sigaction(kSignals[k], &earlier[k], nullptr);
}

const std::atomic<bool>& Interrupts::stop_flag() const { return stop; }

int Interrupts::signal() const { return received; }

}  // namespace granjet
