// The Gmsh SDK (Debian libgmsh-dev, C API of gmshc.h), loaded at run time with dlopen on first use
// instead of linked: libgmsh pulls in OpenCASCADE, FLTK and image libraries whose start-up costs
// about 0.25 s per process (measured: an empty program linked to libgmsh runs 0.28 s, unlinked
// 0.001 s), which every test process and every `matpoint` run would pay otherwise. Only processes
// that read a Gmsh mesh pay it.
//
// Gmsh's state is global: a GmshSession holds a process-wide lock for its lifetime; Gmsh is
// initialised once per process (no user configuration files), with terminal output off
// (General.Terminal = 0) and errors logged instead of thrown (General.AbortOnError = 0, because an
// exception thrown out of gmshOpen leaves Gmsh's file lock set and every later open silently empty);
// it is never finalised.
#pragma once

#include <cstddef>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace matpoint::mesh {

/// Elements of one Gmsh type: their tags and node tags (tags.size() * nodes-per-element).
struct GmshElementBlock {
  int type = 0;
  std::vector<std::size_t> tags, nodes;
};

/// gmshModelMeshGetElementProperties: name, dimension, order, node count, reference coordinates of
/// the nodes (dim values per node, in Gmsh's local order).
struct GmshElementProperties {
  std::string name;
  int dim = 0, order = 0, nodes = 0, primary_nodes = 0;
  std::vector<double> reference;
};

class GmshSession {
 public:
  /// Locks Gmsh for this object's lifetime; loads and initialises it on first use. Throws
  /// std::runtime_error if the library cannot be loaded.
  GmshSession();

  void clear();
  void open(const std::string& file);
  void write(const std::string& file);
  void set_option(const std::string& name, double value);
  void start_log();
  /// The messages logged since start_log() ("Error: ...", "Warning: ...", "Info: ...").
  std::vector<std::string> stop_log();
  void generate(int dim);
  void set_order(int order);

  /// Elements of dimension dim on entity tag (all entities for tag < 0), one block per type.
  std::vector<GmshElementBlock> elements(int dim, int tag = -1);
  GmshElementProperties element_properties(int type);
  /// All nodes: tags and coordinates (3 per node).
  void nodes(std::vector<std::size_t>& tags, std::vector<double>& coordinates);
  std::vector<std::pair<int, int>> physical_groups(int dim);
  std::string physical_name(int dim, int tag);
  std::vector<int> physical_group_entities(int dim, int tag);

 private:
  std::unique_lock<std::mutex> lock_;
};

}  // namespace matpoint::mesh
