// Plain values packed into and read back from a message's bytes (particle migration, the seen
// particles of the logistic contact normals): the sender and the receiver run the same program,
// so a value is its bytes.
#pragma once

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace matpoint::bytes {

/// Appends value's bytes. Eigen's fixed-size vectors and matrices are plain arrays of doubles,
/// though not formally trivially copyable (they declare copy constructors): standard layout is
/// what is asked.
template <class T>
void append(std::vector<char>& out, const T& value) {
  static_assert(std::is_standard_layout_v<T>);
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

/// Reads the value at `at` and moves `at` past it; `what` names the message in the error of a
/// message too short (a broken invariant: both sides run the same code).
template <class T>
T take(const std::vector<char>& in, std::size_t& at, const char* what) {
  static_assert(std::is_standard_layout_v<T>);
  if (at + sizeof(T) > in.size()) throw std::logic_error(std::string(what) + ": a message too short");
  T value;
  std::memcpy(static_cast<void*>(&value), in.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

}  // namespace matpoint::bytes
