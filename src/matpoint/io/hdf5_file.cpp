#include "matpoint/io/hdf5_file.hpp"

#include <sstream>

namespace matpoint {

namespace {

constexpr const char* kChecksum = "fnv1a64";

/// HDF5 prints its error stack on stderr by default; we report errors ourselves.
void silence_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

/// File access without HDF5's file locks, which fail on file systems without flock (NFS on many
/// clusters); a checkpoint is written by one process under a temporary name, so no lock is needed.
Hdf5Handle unlocked_access() {
  Hdf5Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (access.valid()) H5Pset_file_locking(access.get(), false, true);
  return access;
}

std::string shape_text(const std::vector<hsize_t>& shape) {
  std::ostringstream out;
  out << '(';
  for (std::size_t i = 0; i < shape.size(); ++i) out << (i > 0 ? ", " : "") << shape[i];
  out << ')';
  return out.str();
}

std::size_t element_count(const std::vector<hsize_t>& shape) {
  std::size_t n = 1;
  for (auto extent : shape) n *= static_cast<std::size_t>(extent);
  return n;
}

}  // namespace

Hdf5Handle& Hdf5Handle::operator=(Hdf5Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    close_ = other.close_;
    other.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Hdf5Handle::reset() {
  if (id_ >= 0 && close_ != nullptr) close_(id_);
  id_ = H5I_INVALID_HID;
}

std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t seed) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint64_t h = seed;
  for (std::size_t i = 0; i < bytes; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ULL;
  }
  return h;
}

// ---------------------------------------------------------------------------------------------

Hdf5Writer::Hdf5Writer(const std::filesystem::path& file) : path_(file) {
  silence_hdf5();
  const Hdf5Handle access = unlocked_access();
  file_ = Hdf5Handle(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), H5Fclose);
  if (!file_.valid()) throw Hdf5Error("cannot create the HDF5 file " + file.string());
}

void Hdf5Writer::write_raw(const std::string& name, hid_t type, const void* data, std::size_t bytes,
                           const std::vector<hsize_t>& shape) {
  const auto fail = [&] { throw Hdf5Error("cannot write dataset " + name + " to " + path_.string()); };
  const Hdf5Handle links(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  if (!links.valid() || H5Pset_create_intermediate_group(links.get(), 1) < 0) fail();
  const Hdf5Handle space(shape.empty()
                             ? H5Screate(H5S_SCALAR)
                             : H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr),
                         H5Sclose);
  if (!space.valid()) fail();
  const Hdf5Handle set(
      H5Dcreate2(file_.get(), name.c_str(), type, space.get(), links.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!set.valid()) fail();
  if (bytes > 0 && H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) fail();
  const std::uint64_t sum = fnv1a64(data, bytes);
  const Hdf5Handle scalar(H5Screate(H5S_SCALAR), H5Sclose);
  const Hdf5Handle attribute(
      H5Acreate2(set.get(), kChecksum, H5T_STD_U64LE, scalar.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid() || H5Awrite(attribute.get(), H5T_NATIVE_UINT64, &sum) < 0) fail();
}

void Hdf5Writer::write(const std::string& name, const std::vector<double>& data,
                       const std::vector<hsize_t>& shape) {
  write_raw(name, H5T_NATIVE_DOUBLE, data.data(), data.size() * sizeof(double), shape);
}

void Hdf5Writer::write(const std::string& name, const std::vector<std::int64_t>& data,
                       const std::vector<hsize_t>& shape) {
  write_raw(name, H5T_NATIVE_INT64, data.data(), data.size() * sizeof(std::int64_t), shape);
}

void Hdf5Writer::write(const std::string& name, const std::vector<std::int32_t>& data,
                       const std::vector<hsize_t>& shape) {
  write_raw(name, H5T_NATIVE_INT32, data.data(), data.size() * sizeof(std::int32_t), shape);
}

void Hdf5Writer::write(const std::string& name, const std::string& text) {
  // A fixed-length, null-padded string of at least one byte (HDF5 has no zero-length strings).
  const Hdf5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  std::string padded = text.empty() ? std::string(1, '\0') : text;
  if (!type.valid() || H5Tset_size(type.get(), padded.size()) < 0 ||
      H5Tset_strpad(type.get(), H5T_STR_NULLPAD) < 0)
    throw Hdf5Error("cannot write dataset " + name + " to " + path_.string());
  write_raw(name, type.get(), padded.data(), padded.size(), {});
}

void Hdf5Writer::close() {
  if (!file_.valid()) return;
  const bool flushed = H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) >= 0;
  const bool closed = H5Fclose(file_.get()) >= 0;
  file_ = Hdf5Handle();  // already closed
  if (!flushed || !closed) throw Hdf5Error("cannot complete the HDF5 file " + path_.string());
}

// ---------------------------------------------------------------------------------------------

Hdf5Reader::Hdf5Reader(const std::filesystem::path& file) : path_(file) {
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw Hdf5Error("no such file");
  const Hdf5Handle access = unlocked_access();
  file_ = Hdf5Handle(H5Fopen(file.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose);
  if (!file_.valid()) throw Hdf5Error("not a readable HDF5 file (truncated or damaged)");
}

bool Hdf5Reader::has(const std::string& name) const {
  // H5Lexists needs every group on the way to exist: check each prefix in turn.
  for (std::size_t end = name.find('/');; end = name.find('/', end + 1)) {
    const std::string prefix = name.substr(0, end);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (end == std::string::npos) return true;
  }
}

std::vector<hsize_t> Hdf5Reader::shape(const std::string& name) const {
  if (!has(name)) throw Hdf5Error("dataset " + name + " is missing");
  const Hdf5Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  const Hdf5Handle space(set.valid() ? H5Dget_space(set.get()) : H5I_INVALID_HID, H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (rank < 0) throw Hdf5Error("dataset " + name + " cannot be read (damaged)");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

void Hdf5Reader::read_raw(const std::string& name, hid_t type, void* data, std::size_t bytes,
                          const std::vector<hsize_t>& expected) const {
  const auto got = shape(name);
  if (got != expected)
    throw Hdf5Error("dataset " + name + " has the shape " + shape_text(got) + ", expected " +
                    shape_text(expected));
  const auto damaged = [&](const char* what) {
    throw Hdf5Error("dataset " + name + " " + what + " (the file is damaged)");
  };
  const Hdf5Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  const Hdf5Handle stored(set.valid() ? H5Dget_type(set.get()) : H5I_INVALID_HID, H5Tclose);
  if (!stored.valid() || H5Tget_class(stored.get()) != H5Tget_class(type) ||
      H5Tget_size(stored.get()) != H5Tget_size(type))
    throw Hdf5Error("dataset " + name + " has another element type than expected");
  if (bytes > 0 && H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    damaged("cannot be read");
  std::uint64_t sum = 0;
  const Hdf5Handle attribute(H5Aopen(set.get(), kChecksum, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid() || H5Aread(attribute.get(), H5T_NATIVE_UINT64, &sum) < 0) damaged("has no checksum");
  if (sum != fnv1a64(data, bytes)) damaged("does not match its checksum");
}

std::vector<double> Hdf5Reader::doubles(const std::string& name, const std::vector<hsize_t>& shape) const {
  std::vector<double> out(element_count(shape));
  read_raw(name, H5T_NATIVE_DOUBLE, out.data(), out.size() * sizeof(double), shape);
  return out;
}

std::vector<std::int64_t> Hdf5Reader::int64s(const std::string& name,
                                             const std::vector<hsize_t>& shape) const {
  std::vector<std::int64_t> out(element_count(shape));
  read_raw(name, H5T_NATIVE_INT64, out.data(), out.size() * sizeof(std::int64_t), shape);
  return out;
}

std::vector<std::int32_t> Hdf5Reader::int32s(const std::string& name,
                                             const std::vector<hsize_t>& shape) const {
  std::vector<std::int32_t> out(element_count(shape));
  read_raw(name, H5T_NATIVE_INT32, out.data(), out.size() * sizeof(std::int32_t), shape);
  return out;
}

std::string Hdf5Reader::text(const std::string& name) const {
  if (!has(name)) throw Hdf5Error("dataset " + name + " is missing");
  std::size_t size = 0;
  {
    const Hdf5Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    const Hdf5Handle stored(set.valid() ? H5Dget_type(set.get()) : H5I_INVALID_HID, H5Tclose);
    if (!stored.valid() || H5Tget_class(stored.get()) != H5T_STRING || H5Tis_variable_str(stored.get()) != 0)
      throw Hdf5Error("dataset " + name + " is not a fixed-length string");
    size = H5Tget_size(stored.get());
  }
  const Hdf5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), size);
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  std::string out(size, '\0');
  read_raw(name, type.get(), out.data(), out.size(), {});
  while (!out.empty() && out.back() == '\0') out.pop_back();
  return out;
}

}  // namespace matpoint
