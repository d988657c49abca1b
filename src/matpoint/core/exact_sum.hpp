// The exact sum of non-negative doubles, whatever their order and however they are split among
// ranks (docs/scale-out.md §17 stage 3: the dynamic FMPM measure, a sum over the active nodes
// that decides when the loop stops, must give the same decision on every rank and on any
// number of ranks). A floating-point sum depends on its association; this one does not: every
// term is added exactly into a fixed-point integer that spans the whole double range (a "long
// accumulator"), and only value() rounds, once.
//
// A finite double x > 0 is m 2^(e - 1075) with the integer significand m < 2^53 and the biased
// exponent e (1 for the subnormals), so it is the integer m shifted left by e - 1 bits above
// 2^-1074. The accumulator holds that integer in 32-bit digits, each in a uint64 with room for
// 2^31 unnormalised additions; the digits of two accumulators (two ranks) add as exact doubles.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "matpoint/parallel/communicator.hpp"

namespace matpoint {

class ExactSum {
 public:
  /// Adds x >= 0 exactly (zero and negative terms are ignored: the callers' terms are
  /// magnitudes); a non-finite x makes the sum NaN.
  void add(double x) {
    if (!(x > 0.0)) {
      if (std::isnan(x)) finite_ = false;
      return;
    }
    const auto bits = std::bit_cast<std::uint64_t>(x);
    auto exponent = static_cast<int>(bits >> 52);
    if (exponent == 2047) {
      finite_ = false;
      return;
    }
    std::uint64_t significand = bits & ((std::uint64_t{1} << 52) - 1);
    if (exponent > 0)
      significand |= std::uint64_t{1} << 52;
    else
      exponent = 1;
    const int shift = exponent - 1;  // x = significand 2^shift in units of 2^-1074
    const auto k = static_cast<std::size_t>(shift / kBits);
    const int s = shift % kBits;  // significand << s (< 2^85) in three digits
    const std::uint64_t rest = significand >> (kBits - s);
    digits_[k] += (significand & (kMask >> s)) << s;
    digits_[k + 1] += rest & kMask;
    digits_[k + 2] += rest >> kBits;
    if (++pending_ == kPendingLimit) normalise();
  }

  /// Adds the other ranks' sums (a collective): afterwards every rank holds the exact total.
  void sum_over(const Communicator& comm) {
    if (!comm.distributed()) return;
    normalise();
    std::vector<double> parts(kDigits + 1);
    for (std::size_t k = 0; k < kDigits; ++k) parts[k] = static_cast<double>(digits_[k]);  // < 2^32: exact
    parts[kDigits] = finite_ ? 0.0 : 1.0;
    comm.sum(parts);  // each entry below 2^32 times the rank count: exact in a double
    for (std::size_t k = 0; k < kDigits; ++k) digits_[k] = static_cast<std::uint64_t>(parts[k]);
    finite_ = parts[kDigits] == 0.0;
    normalise();
  }

  /// The sum from its leading 96 bits (faithfully rounded): a function of the exact sum only.
  [[nodiscard]] double value() const {
    if (!finite_) return std::numeric_limits<double>::quiet_NaN();
    ExactSum s = *this;
    s.normalise();
    std::size_t top = kDigits;
    while (top > 0 && s.digits_[top - 1] == 0) --top;
    if (top == 0) return 0.0;
    const std::size_t t = top - 1;
    const auto at = [&](std::size_t k) { return k <= t ? static_cast<double>(s.digits_[k]) : 0.0; };
    const auto scale = [](std::size_t k) { return static_cast<int>(k) * kBits - 1074; };
    // digits t, t - 1, t - 2 (each exact), added from the smallest: the same bits on every rank
    double sum = t >= 2 ? std::ldexp(at(t - 2), scale(t - 2)) : 0.0;
    if (t >= 1) sum += std::ldexp(at(t - 1), scale(t - 1));
    return sum + std::ldexp(at(t), scale(t));
  }

 private:
  static constexpr int kBits = 32;
  static constexpr std::uint64_t kMask = (std::uint64_t{1} << kBits) - 1;
  // 2046 + 85 bits of the largest term, plus 64 bits of carries: 69 digits; 72 for round numbers
  static constexpr std::size_t kDigits = 72;
  static constexpr long kPendingLimit = long{1} << 30;  // a digit gains < 2^32 per add: no overflow

  /// Carries every digit's excess into the next one (digits in [0, 2^32) afterwards).
  void normalise() {
    for (std::size_t k = 0; k + 1 < kDigits; ++k) {
      digits_[k + 1] += digits_[k] >> kBits;
      digits_[k] &= kMask;
    }
    pending_ = 0;
  }

  std::array<std::uint64_t, kDigits> digits_{};
  long pending_ = 0;
  bool finite_ = true;
};

}  // namespace matpoint
