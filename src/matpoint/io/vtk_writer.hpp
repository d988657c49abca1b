// ParaView output: particles as VTK XML unstructured grids (.vtu, one vertex cell per particle,
// base64 binary data arrays) and the .pvd collection that strings them into a time series.
#pragma once

#include "matpoint/particles/particle_set.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace matpoint {

/// The .vtu text of a particle set. `fields` lists the point data to write (names from
/// io/particle_fields.hpp); empty means all.
template <int D> std::string particles_vtu(const ParticleSet<D>& particles, const std::vector<std::string>& fields);

/// A growing ParaView collection, rewritten atomically after each added file.
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path file) : file_(std::move(file)) {}
  void add(double time, const std::string& dataset_file);

 private:
  std::filesystem::path file_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace matpoint
