// libFuzzer target for the input reader and validator (issue 8, "input safety").
//
// Every byte string must either be accepted (then the simulation is set up: grid, particles,
// materials) or be refused with InputError, which `matpoint` turns into exit 2. Anything else —
// another exception, a crash, a hang, a sanitizer report — is a finding. Run by scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/io/memory_estimate.hpp"

namespace {

// Set-up of accepted inputs is skipped above these sizes so that one input stays fast; the
// validator itself (the target) always runs.
constexpr double kMaxSetupParticles = 2e4;
constexpr double kMaxSetupNodes = 2e5;

template <int D>
void set_up(const matpoint::Spec& spec) {
  (void)matpoint::build_simulation<D>(spec);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const matpoint::Spec spec = matpoint::parse_spec(text);
    const matpoint::MemoryEstimate estimate = matpoint::estimate_memory(spec);
    if (estimate.particles > kMaxSetupParticles || estimate.nodes > kMaxSetupNodes) return 0;
    switch (spec.grid.dim) {
      case 1:
        set_up<1>(spec);
        break;
      case 3:
        set_up<3>(spec);
        break;
      default:
        set_up<2>(spec);
        break;
    }
  } catch (const matpoint::InputError&) {
    // refused with a message: what exit 2 reports
  }
  return 0;
}
