#include "matpoint/core/interrupt.hpp"

#include <csignal>

namespace matpoint {

namespace {

volatile std::sig_atomic_t received = 0;  // written by the handler: the only thing it does

extern "C" void on_interrupt(int signal) { received = signal; }

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;  // a second Ctrl-C kills at once; writes are not cut
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() { return received; }

void request_interrupt(int signal) { received = signal; }

}  // namespace matpoint
