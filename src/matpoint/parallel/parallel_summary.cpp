#include "matpoint/parallel/parallel_summary.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <thread>
#include <vector>

#ifdef __linux__
#include <sched.h>
#endif

namespace matpoint {

int available_cpus() {
#ifdef __linux__
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
#endif
  return static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
}

nlohmann::json parallel_summary(const Communicator& comm, const RankTraffic& mine, long steps) {
  const double per_step = steps > 0 ? 1.0 / static_cast<double>(steps) : 0.0;
  const double wait_cpu = mine.halo.waiting_cpu + mine.migration.waiting_cpu + mine.collectives.waiting_cpu;
  // Each rank's row, gathered on every rank in rank order.
  const std::array<std::pair<const char*, double>, 22> row{{
      {"particles_per_rank", static_cast<double>(mine.particles)},
      {"stored_nodes_per_rank", static_cast<double>(mine.stored_nodes)},
      {"threads_per_rank", static_cast<double>(mine.threads)},
      {"cpus_per_rank", static_cast<double>(available_cpus())},
      {"step_wall_seconds", mine.step_wall},
      {"step_cpu_seconds", mine.step_cpu},
      {"wait_cpu_seconds", wait_cpu},
      {"work_cpu_seconds", mine.step_cpu - wait_cpu},
      {"halo_exchanges_per_step", static_cast<double>(mine.halo.calls) * per_step},
      {"halo_messages_per_step", static_cast<double>(mine.halo.messages) * per_step},
      {"halo_bytes_per_step", static_cast<double>(mine.halo.bytes) * per_step},
      {"halo_seconds", mine.halo.seconds},
      {"halo_wait_seconds", mine.halo.waiting},
      {"halo_own_cpu_seconds", mine.halo.cpu - mine.halo.waiting_cpu},
      {"migrated_particles_per_step", static_cast<double>(mine.migration.particles) * per_step},
      {"migration_messages_per_step", static_cast<double>(mine.migration.messages) * per_step},
      {"migration_bytes_per_step", static_cast<double>(mine.migration.bytes) * per_step},
      {"migration_seconds", mine.migration.seconds},
      {"migration_wait_seconds", mine.migration.waiting},
      {"migration_own_cpu_seconds", mine.migration.cpu - mine.migration.waiting_cpu},
      {"collectives_per_step", static_cast<double>(mine.collectives.calls) * per_step},
      {"collective_seconds", mine.collectives.seconds},
  }};
  std::vector<double> values;
  values.reserve(row.size());
  for (const auto& entry : row) values.push_back(entry.second);
  const std::vector<double> all = comm.all_gather(values);
  const std::size_t n = row.size();
  const auto ranks = static_cast<std::size_t>(comm.size());

  nlohmann::json out;
  out["ranks"] = comm.size();
  out["steps"] = steps;
  for (std::size_t k = 0; k < n; ++k) {
    double lo = all[k], hi = all[k], sum = 0.0;
    for (std::size_t r = 0; r < ranks; ++r) {
      const double v = all[r * n + k];
      lo = std::min(lo, v), hi = std::max(hi, v), sum += v;
    }
    const std::string name = row[k].first;
    if (name == "particles_per_rank") {
      out[name] = {{"min", static_cast<long>(lo)},
                   {"max", static_cast<long>(hi)},
                   {"imbalance", sum > 0 ? hi * static_cast<double>(ranks) / sum : 1.0}};
    } else if (name == "stored_nodes_per_rank") {
      out[name] = {
          {"min", static_cast<long>(lo)}, {"max", static_cast<long>(hi)}, {"sum", static_cast<long>(sum)}};
    } else if (name == "threads_per_rank" || name == "cpus_per_rank") {
      out[name] = {{"min", static_cast<int>(lo)}, {"max", static_cast<int>(hi)}};
    } else if (name == "step_wall_seconds" || name == "step_cpu_seconds" || name == "work_cpu_seconds") {
      out[name] = {{"min", lo}, {"max", hi}};
    } else {
      out[name] = {{"max", hi}, {"sum", sum}};
    }
  }
  return out;
}

}  // namespace matpoint
