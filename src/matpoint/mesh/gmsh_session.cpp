// The Gmsh C API loaded at run time (gmsh_session.hpp).
#include "matpoint/mesh/gmsh_session.hpp"

#include <dlfcn.h>
#include <gmshc.h>  // declarations only: decltype of each function, nothing is linked

#include <array>
#include <cstdlib>
#include <stdexcept>

namespace matpoint::mesh {

namespace {

/// The functions of gmshc.h that matpoint uses, resolved from the loaded library.
struct GmshApi {
  decltype(&gmshFree) free;
  decltype(&gmshInitialize) initialize;
  decltype(&gmshFinalize) finalize;
  decltype(&gmshClear) clear;
  decltype(&gmshOpen) open;
  decltype(&gmshWrite) write;
  decltype(&gmshOptionSetNumber) set_number;
  decltype(&gmshLoggerStart) logger_start;
  decltype(&gmshLoggerGet) logger_get;
  decltype(&gmshLoggerStop) logger_stop;
  decltype(&gmshModelMeshGenerate) generate;
  decltype(&gmshModelMeshSetOrder) set_order;
  decltype(&gmshModelMeshGetElements) get_elements;
  decltype(&gmshModelMeshGetElementProperties) get_element_properties;
  decltype(&gmshModelMeshGetNodes) get_nodes;
  decltype(&gmshModelGetPhysicalGroups) get_physical_groups;
  decltype(&gmshModelGetPhysicalName) get_physical_name;
  decltype(&gmshModelGetEntitiesForPhysicalGroup) get_entities_for_physical_group;
};

#ifndef MATPOINT_GMSH_LIBRARY
#define MATPOINT_GMSH_LIBRARY "libgmsh.so"
#endif

/// dlopen the library found at configure time, else by its usual names.
void* open_library() {
  std::string errors;
  for (const char* name : {MATPOINT_GMSH_LIBRARY, "libgmsh.so", "libgmsh.so.4.8"}) {
    if (void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL)) return handle;
    errors += std::string("\n  ") + dlerror();
  }
  throw std::runtime_error("the Gmsh library (Debian package libgmsh-dev) could not be loaded:" + errors);
}

template <class F>
void resolve(void* handle, const char* name, F& function) {
  function = reinterpret_cast<F>(dlsym(handle, name));
  if (function == nullptr) throw std::runtime_error(std::string("the Gmsh library has no function ") + name);
}

GmshApi load_api() {
  void* h = open_library();
  GmshApi a{};
  resolve(h, "gmshFree", a.free);
  resolve(h, "gmshInitialize", a.initialize);
  resolve(h, "gmshFinalize", a.finalize);
  resolve(h, "gmshClear", a.clear);
  resolve(h, "gmshOpen", a.open);
  resolve(h, "gmshWrite", a.write);
  resolve(h, "gmshOptionSetNumber", a.set_number);
  resolve(h, "gmshLoggerStart", a.logger_start);
  resolve(h, "gmshLoggerGet", a.logger_get);
  resolve(h, "gmshLoggerStop", a.logger_stop);
  resolve(h, "gmshModelMeshGenerate", a.generate);
  resolve(h, "gmshModelMeshSetOrder", a.set_order);
  resolve(h, "gmshModelMeshGetElements", a.get_elements);
  resolve(h, "gmshModelMeshGetElementProperties", a.get_element_properties);
  resolve(h, "gmshModelMeshGetNodes", a.get_nodes);
  resolve(h, "gmshModelGetPhysicalGroups", a.get_physical_groups);
  resolve(h, "gmshModelGetPhysicalName", a.get_physical_name);
  resolve(h, "gmshModelGetEntitiesForPhysicalGroup", a.get_entities_for_physical_group);
  return a;
}

/// Throws if a Gmsh call reported an error code.
void check(int ierr, const char* what) {
  if (ierr != 0)
    throw std::runtime_error(std::string("Gmsh: ") + what + " failed (error " + std::to_string(ierr) + ")");
}

const GmshApi& api();

/// Gmsh's own clean-up at process exit (its caches would otherwise show as leaks under LeakSanitizer,
/// scripts/sanitize.sh). Registered after dlopen, so it runs before the library's destructors.
void finalize_at_exit() {
  int ierr = 0;
  api().finalize(&ierr);
}

/// The loaded and initialised API (first call only; the caller holds the session lock).
const GmshApi& api() {
  static const GmshApi loaded = [] {
    GmshApi a = load_api();
    int ierr = 0;
    a.initialize(0, nullptr, 0, &ierr);  // no user configuration files
    check(ierr, "initialize");
    a.set_number("General.Terminal", 0.0, &ierr);
    a.set_number("General.AbortOnError", 0.0, &ierr);
    check(ierr, "option");
    std::atexit(finalize_at_exit);
    return a;
  }();
  return loaded;
}

/// Copies a Gmsh-allocated array into a vector and frees it.
template <class T>
std::vector<T> take(T* data, std::size_t n) {
  std::vector<T> out(data, data + n);
  api().free(data);
  return out;
}

std::string take_string(char* text) {
  std::string out = text != nullptr ? text : "";
  api().free(text);
  return out;
}

std::mutex& session_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

GmshSession::GmshSession() : lock_(session_mutex()) { api(); }

void GmshSession::clear() {
  int ierr = 0;
  api().clear(&ierr);
  check(ierr, "clear");
}

void GmshSession::open(const std::string& file) {
  int ierr = 0;
  api().open(file.c_str(), &ierr);
  check(ierr, "open");
}

void GmshSession::write(const std::string& file) {
  int ierr = 0;
  api().write(file.c_str(), &ierr);
  check(ierr, "write");
}

void GmshSession::set_option(const std::string& name, double value) {
  int ierr = 0;
  api().set_number(name.c_str(), value, &ierr);
  check(ierr, "set option");
}

void GmshSession::start_log() {
  int ierr = 0;
  api().logger_start(&ierr);
  check(ierr, "logger start");
}

std::vector<std::string> GmshSession::stop_log() {
  int ierr = 0;
  char** log = nullptr;
  std::size_t n = 0;
  api().logger_get(&log, &n, &ierr);
  check(ierr, "logger get");
  std::vector<std::string> out;
  for (char* line : take(log, n)) out.push_back(take_string(line));
  api().logger_stop(&ierr);
  return out;
}

void GmshSession::generate(int dim) {
  int ierr = 0;
  api().generate(dim, &ierr);
  check(ierr, "generate");
}

void GmshSession::set_order(int order) {
  int ierr = 0;
  api().set_order(order, &ierr);
  check(ierr, "set order");
}

std::vector<GmshElementBlock> GmshSession::elements(int dim, int tag) {
  int ierr = 0;
  int* types = nullptr;
  std::size_t **tags = nullptr, **nodes = nullptr, *tags_n = nullptr, *nodes_n = nullptr;
  std::size_t types_n = 0, tags_nn = 0, nodes_nn = 0;
  api().get_elements(&types, &types_n, &tags, &tags_n, &tags_nn, &nodes, &nodes_n, &nodes_nn, dim, tag,
                     &ierr);
  check(ierr, "get elements");
  const auto type_list = take(types, types_n);
  const auto tag_arrays = take(tags, tags_nn), node_arrays = take(nodes, nodes_nn);
  const auto tag_counts = take(tags_n, tags_nn), node_counts = take(nodes_n, nodes_nn);
  std::vector<GmshElementBlock> out;
  for (std::size_t t = 0; t < type_list.size(); ++t)
    out.push_back({type_list[t], take(tag_arrays[t], tag_counts[t]), take(node_arrays[t], node_counts[t])});
  return out;
}

GmshElementProperties GmshSession::element_properties(int type) {
  int ierr = 0;
  char* name = nullptr;
  double* reference = nullptr;
  std::size_t reference_n = 0;
  GmshElementProperties p;
  api().get_element_properties(type, &name, &p.dim, &p.order, &p.nodes, &reference, &reference_n,
                               &p.primary_nodes, &ierr);
  check(ierr, "get element properties");
  p.name = take_string(name);
  p.reference = take(reference, reference_n);
  return p;
}

void GmshSession::nodes(std::vector<std::size_t>& tags, std::vector<double>& coordinates) {
  int ierr = 0;
  std::size_t* tag_data = nullptr;
  double *coord_data = nullptr, *parametric = nullptr;
  std::size_t tag_n = 0, coord_n = 0, parametric_n = 0;
  api().get_nodes(&tag_data, &tag_n, &coord_data, &coord_n, &parametric, &parametric_n, -1, -1, 0, 0, &ierr);
  check(ierr, "get nodes");
  tags = take(tag_data, tag_n);
  coordinates = take(coord_data, coord_n);
  take(parametric, parametric_n);
}

std::vector<std::pair<int, int>> GmshSession::physical_groups(int dim) {
  int ierr = 0;
  int* dim_tags = nullptr;
  std::size_t n = 0;
  api().get_physical_groups(&dim_tags, &n, dim, &ierr);
  check(ierr, "get physical groups");
  const auto flat = take(dim_tags, n);
  std::vector<std::pair<int, int>> out;
  for (std::size_t k = 0; k + 1 < flat.size(); k += 2) out.emplace_back(flat[k], flat[k + 1]);
  return out;
}

std::string GmshSession::physical_name(int dim, int tag) {
  int ierr = 0;
  char* name = nullptr;
  api().get_physical_name(dim, tag, &name, &ierr);
  check(ierr, "get physical name");
  return take_string(name);
}

std::vector<int> GmshSession::physical_group_entities(int dim, int tag) {
  int ierr = 0;
  int* tags = nullptr;
  std::size_t n = 0;
  api().get_entities_for_physical_group(dim, tag, &tags, &n, &ierr);
  check(ierr, "get entities for physical group");
  return take(tags, n);
}

}  // namespace matpoint::mesh
