// A small HDF5 file of named arrays (C API behind RAII handles), the storage of checkpoints.
// Every dataset carries an FNV-1a checksum of its bytes as the attribute "fnv1a64", so a file
// whose data were damaged after HDF5 wrote them is refused on reading, not silently used.
// Names may contain groups ("particles/x"); the groups are created as needed.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace matpoint {

/// A file that is not a readable HDF5 file, or lacks or has a damaged dataset: what() says which.
class Hdf5Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One HDF5 identifier, closed by its own close function when the handle goes out of scope.
class Hdf5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Hdf5Handle() = default;
  Hdf5Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Hdf5Handle(Hdf5Handle&& other) noexcept : id_(other.id_), close_(other.close_) {
    other.id_ = H5I_INVALID_HID;
  }
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept;
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  ~Hdf5Handle() { reset(); }

  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool valid() const { return id_ >= 0; }
  void reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

/// 64-bit FNV-1a hash of a byte range (http://www.isthe.com/chongo/tech/comp/fnv/).
std::uint64_t fnv1a64(const void* data, std::size_t bytes, std::uint64_t seed = 0xcbf29ce484222325ULL);

/// Writes a new HDF5 file (truncating any file of that name).
class Hdf5Writer {
 public:
  explicit Hdf5Writer(const std::filesystem::path& file);

  void write(const std::string& name, const std::vector<double>& data, const std::vector<hsize_t>& shape);
  void write(const std::string& name, const std::vector<std::int64_t>& data,
             const std::vector<hsize_t>& shape);
  void write(const std::string& name, const std::vector<std::int32_t>& data,
             const std::vector<hsize_t>& shape);
  void write(const std::string& name, const std::string& text);
  void write(const std::string& name, double value) { write(name, std::vector<double>{value}, {1}); }
  void write(const std::string& name, std::int64_t value) {
    write(name, std::vector<std::int64_t>{value}, {1});
  }

  /// Flushes and closes the file; throws when HDF5 reports an error. The destructor closes too.
  void close();

 private:
  void write_raw(const std::string& name, hid_t type, const void* data, std::size_t bytes,
                 const std::vector<hsize_t>& shape);
  std::filesystem::path path_;
  Hdf5Handle file_;
};

/// Reads an HDF5 file written by Hdf5Writer; every read checks the shape and the checksum.
class Hdf5Reader {
 public:
  explicit Hdf5Reader(const std::filesystem::path& file);

  [[nodiscard]] bool has(const std::string& name) const;
  /// The shape of a dataset (throws when it is missing).
  [[nodiscard]] std::vector<hsize_t> shape(const std::string& name) const;
  /// The data of a dataset with exactly this shape (throws when missing, of another shape or damaged).
  [[nodiscard]] std::vector<double> doubles(const std::string& name, const std::vector<hsize_t>& shape) const;
  [[nodiscard]] std::vector<std::int64_t> int64s(const std::string& name,
                                                 const std::vector<hsize_t>& shape) const;
  [[nodiscard]] std::vector<std::int32_t> int32s(const std::string& name,
                                                 const std::vector<hsize_t>& shape) const;
  [[nodiscard]] std::string text(const std::string& name) const;
  [[nodiscard]] double number(const std::string& name) const { return doubles(name, {1})[0]; }
  [[nodiscard]] std::int64_t integer(const std::string& name) const { return int64s(name, {1})[0]; }

 private:
  void read_raw(const std::string& name, hid_t type, void* data, std::size_t bytes,
                const std::vector<hsize_t>& shape) const;
  std::filesystem::path path_;
  Hdf5Handle file_;
};

}  // namespace matpoint
