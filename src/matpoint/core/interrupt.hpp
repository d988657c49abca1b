// SIGINT / SIGTERM as a request to stop: the handler only records the signal (async-signal-safe);
// the run loop polls it between steps, finishes the current step, writes a checkpoint and the last
// output, and exits with 128 + the signal number (docs/output.md "Exit codes").
#pragma once

namespace matpoint {

/// Installs the handlers for SIGINT and SIGTERM. A second signal of the same kind ends the process
/// at once (the handler is reset to the default after the first).
void install_interrupt_handlers();

/// The number of the signal received (the last one, if several), or 0.
[[nodiscard]] int interrupt_signal();

/// Records `signal` as if it had been received (tests), or clears the record with 0.
void request_interrupt(int signal);

}  // namespace matpoint
