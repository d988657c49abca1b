// ParaView output: particles as VTK XML unstructured grids (.vtu, one vertex cell per particle,
// zlib-compressed appended binary data arrays with 64-bit headers) and the .pvd collection that
// strings them into a time series.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

/// The .vtu file of a particle set. `fields` lists the point data to write (names from
/// io/particle_fields.hpp); empty means all. `displacement` writes u = x - X (X: particles.x0);
/// without it none is written. `state_names` name the components of the
/// `state` array (ComponentName attributes, shown by ParaView).
template <int D>
std::string particles_vtu(const ParticleSet<D>& particles, const std::vector<std::string>& fields,
                          bool displacement = false, const std::vector<std::string>& state_names = {});

/// The .vtu text of the particle domains: one cell per particle (VTK_LINE in 1-D, VTK_QUAD in
/// 2-D, VTK_HEXAHEDRON in 3-D) from corners in tensor order, with the cell data `id` and `body`.
template <int D>
std::string domains_vtu(const std::vector<typename ParticleSet<D>::Corners>& domains,
                        const ParticleSet<D>& particles);

/// The .pvtu text (VTK XML PUnstructuredGrid) of a dataset written in pieces, one .vtu per MPI
/// rank (docs/output.md "Runs on several MPI ranks"): it lists `piece_files` (names relative to the
/// .pvtu's folder) and declares the point data, cell data and points arrays of `piece_vtu`, the
/// text of one piece (particles_vtu or domains_vtu), with their names, types, numbers of
/// components and component names. Every piece of one output declares the same arrays (they do
/// not depend on the particles a rank holds, none included).
std::string pvtu_file(const std::string& piece_vtu, const std::vector<std::string>& piece_files);

/// A growing ParaView collection, rewritten atomically after each added file. `writes` false:
/// keeps the entries without writing the file (the MPI ranks other than rank 0).
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path file, bool writes = true)
      : file_(std::move(file)), writes_(writes) {}
  void add(double time, const std::string& dataset_file);
  /// The (time, file) entries so far; restore() replaces them (a restart) and rewrites the file.
  [[nodiscard]] const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  void restore(std::vector<std::pair<double, std::string>> entries);
  /// A dataset that does not change (an implicit run's element mesh): listed as part 1 beside
  /// every entry's part 0, so ParaView shows it at every time.
  void set_static_part(std::string dataset_file);
  /// A dataset written at every output beside the particles (an implicit run's FE bodies): listed
  /// after the others with each entry's file name, its prefix up to the first '_' replaced by `prefix`
  /// ("particles_000012.vtu" -> "fe_bodies_000012.vtu").
  void set_companion_prefix(std::string prefix);

 private:
  void write() const;
  std::filesystem::path file_;
  bool writes_ = true;
  std::vector<std::pair<double, std::string>> entries_;
  std::string static_part_;
  std::string companion_prefix_;
};

}  // namespace matpoint
