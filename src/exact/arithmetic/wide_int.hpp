// Internal to src/exact/: a signed integer of fixed capacity, for the certificates' fast path.
//
// A certificate on a small simplex multiplies integers of a few hundred bits (degree 10 in
// the coordinates at most, see distance_certificate.cpp). GMP's mpz_class allocates for each
// temporary and dispatches every operation through a library call, which costs more than the
// GJK query being certified. Wide keeps its magnitude in kLimbs 64-bit limbs on the stack and
// does schoolbook arithmetic inline. A result that does not fit throws WideOverflow; the
// caller then redoes the whole certificate with mpz_class, so the capacity bounds only speed,
// never correctness.
#pragma once

#include <gmp.h>

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace gjklab::exact::detail {

/// Thrown when a Wide result would exceed its capacity.
struct WideOverflow {};

/// Double-width limb arithmetic (a GCC/Clang extension; __extension__ keeps -Wpedantic quiet).
__extension__ typedef unsigned __int128 WideProduct;

class Wide {
 public:
  /// 1024 bits: coordinates of up to about 95 significant bits in the certificate's frame
  /// (the largest value, N·N or D·(N·W), has about 10 times their bits, plus 40).
  static constexpr int kLimbs = 16;

  Wide() = default;
  // Copies take the whole fixed-size array, which compiles to a few vector moves: a loop over
  // the limbs in use is turned by the compiler into a library memmove call, which costs more
  // than the few limbs it copies. (Limbs past size_ are copied as unused bytes.)
  Wide(const Wide& other) : size_(other.size_), negative_(other.negative_) {
    std::memcpy(limb_, other.limb_, sizeof limb_);
  }
  Wide& operator=(const Wide& other) {
    size_ = other.size_;
    negative_ = other.negative_;
    std::memcpy(limb_, other.limb_, sizeof limb_);
    return *this;
  }
  Wide(long long v) {  // NOLINT: implicit, as mpz_class converts from integers
    if (v == 0) return;
    negative_ = v < 0;
    limb_[0] = negative_ ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
    size_ = 1;
  }
  Wide(int v) : Wide(static_cast<long long>(v)) {}  // NOLINT

  /// |m|·2^shift for an integer m with |m| < 2^64 (shift ≥ 0).
  static Wide shifted(std::uint64_t magnitude, bool negative, long shift) {
    Wide out;
    if (magnitude == 0) return out;
    const long whole = shift / 64;
    const int part = static_cast<int>(shift % 64);
    const std::uint64_t high = part ? magnitude >> (64 - part) : 0;
    if (whole + (high ? 2 : 1) > kLimbs) throw WideOverflow{};
    for (long k = 0; k < whole; ++k)
      out.limb_[k] = 0;
    out.limb_[whole] = magnitude << part;
    out.size_ = static_cast<int>(whole) + 1;
    if (high) out.limb_[out.size_++] = high;
    out.negative_ = negative;
    return out;
  }

  friend int sgn(const Wide& x) { return x.size_ == 0 ? 0 : (x.negative_ ? -1 : 1); }

  Wide operator-() const {
    Wide out = *this;
    out.negative_ = size_ != 0 && !negative_;
    return out;
  }

  friend Wide operator+(const Wide& x, const Wide& y) { return sum(x, y, y.negative_); }
  friend Wide operator-(const Wide& x, const Wide& y) {
    return sum(x, y, y.size_ != 0 && !y.negative_);
  }
  Wide& operator+=(const Wide& y) { return *this = *this + y; }
  Wide& operator-=(const Wide& y) { return *this = *this - y; }

  friend Wide operator*(const Wide& x, const Wide& y) {
    Wide out;
    if (x.size_ == 0 || y.size_ == 0) return out;
    out.negative_ = x.negative_ != y.negative_;
    if (x.size_ == 1 && y.size_ == 1) {  // the most common product: one multiplication
      const WideProduct p = static_cast<WideProduct>(x.limb_[0]) * y.limb_[0];
      out.limb_[0] = static_cast<std::uint64_t>(p);
      out.limb_[1] = static_cast<std::uint64_t>(p >> 64);
      out.size_ = out.limb_[1] != 0 ? 2 : 1;
      return out;
    }
    int n = x.size_ + y.size_;
    if (n - 1 > kLimbs) throw WideOverflow{};
    if (n <= kLimbs) {
      multiply_into(x, y, out.limb_);
    } else {  // the top limb may still be zero: compute into room for it, then check
      std::uint64_t r[2 * kLimbs];
      multiply_into(x, y, r);
      if (r[n - 1] != 0) throw WideOverflow{};
      std::memcpy(out.limb_, r, sizeof out.limb_);  // fixed size: see the copy constructor
      n = kLimbs;
    }
    out.size_ = n;
    while (out.size_ > 0 && out.limb_[out.size_ - 1] == 0)
      --out.size_;
    return out;
  }

  /// x·2^bits (bits ≥ 0).
  Wide shifted_left(long bits) const {
    if (size_ == 0 || bits == 0) return *this;
    const long whole = bits / 64;
    const int part = static_cast<int>(bits % 64);
    if (size_ + whole > kLimbs) throw WideOverflow{};
    Wide out;
    out.negative_ = negative_;
    std::uint64_t carry = 0;
    for (long k = 0; k < whole; ++k)
      out.limb_[k] = 0;
    for (int k = 0; k < size_; ++k) {
      const std::uint64_t v = limb_[k];
      out.limb_[whole + k] = part ? (v << part) | carry : v;
      carry = part ? v >> (64 - part) : 0;
    }
    out.size_ = static_cast<int>(size_ + whole);
    if (carry != 0) {
      if (out.size_ == kLimbs) throw WideOverflow{};
      out.limb_[out.size_++] = carry;
    }
    return out;
  }

  friend int compare(const Wide& x, const Wide& y) {
    if (x.negative_ != y.negative_) return x.negative_ ? -1 : 1;
    const int m = compare_magnitude(x, y);
    return x.negative_ ? -m : m;
  }
  friend bool operator<(const Wide& x, const Wide& y) { return compare(x, y) < 0; }
  friend bool operator>(const Wide& x, const Wide& y) { return compare(x, y) > 0; }
  friend bool operator<=(const Wide& x, const Wide& y) { return compare(x, y) <= 0; }
  friend bool operator>=(const Wide& x, const Wide& y) { return compare(x, y) >= 0; }
  friend bool operator==(const Wide& x, const Wide& y) {
    return x.size_ == y.size_ && x.negative_ == y.negative_ &&
           std::equal(x.limb_, x.limb_ + x.size_, y.limb_);
  }
  friend bool operator!=(const Wide& x, const Wide& y) { return !(x == y); }

  /// x = m·2^exponent with 0.5 ≤ |m| < 1, m truncated to 53 bits (as mpz_get_d_2exp): the
  /// relative error of m·2^exponent is below 2^-52. 0 for x = 0.
  double mantissa_2exp(long* exponent) const {
    if (size_ == 0) {
      *exponent = 0;
      return 0.0;
    }
    const std::uint64_t top = limb_[size_ - 1];
    const int lz = __builtin_clzll(top);
    std::uint64_t bits = top << lz;
    if (lz != 0 && size_ > 1) bits |= limb_[size_ - 2] >> (64 - lz);
    *exponent = 64L * size_ - lz;
    const double m = static_cast<double>(bits >> 11) * 0x1p-53;  // 53 bits: exact
    return negative_ ? -m : m;
  }

  /// The top 64 bits of |x| as a long double mantissa m in [0.5, 1) (truncated: relative
  /// error below 2^-63), with |x| ≈ m·2^exponent. x must not be 0.
  long double magnitude_2exp(long* exponent) const {
    const std::uint64_t top = limb_[size_ - 1];
    const int lz = __builtin_clzll(top);
    std::uint64_t bits = top << lz;
    if (lz != 0 && size_ > 1) bits |= limb_[size_ - 2] >> (64 - lz);
    *exponent = 64L * size_ - lz;
    return static_cast<long double>(bits) * 0x1p-64L;  // 64 bits: exact in x87 extended
  }

  friend Wide abs(const Wide& x) {
    Wide out = x;
    out.negative_ = false;
    return out;
  }

  /// The same value as an mpz (z must be initialised).
  void to_mpz(mpz_ptr z) const {
    if (size_ == 0) {
      mpz_set_ui(z, 0);
      return;
    }
    static_assert(sizeof(mp_limb_t) == sizeof(std::uint64_t), "64-bit GMP limbs");
    mp_limb_t* out = mpz_limbs_write(z, size_);
    std::memcpy(out, limb_, sizeof(std::uint64_t) * static_cast<std::size_t>(size_));
    mpz_limbs_finish(z, negative_ ? -size_ : size_);
  }

 private:
  static int compare_magnitude(const Wide& x, const Wide& y) {
    if (x.size_ != y.size_) return x.size_ < y.size_ ? -1 : 1;
    for (int k = x.size_ - 1; k >= 0; --k)
      if (x.limb_[k] != y.limb_[k]) return x.limb_[k] < y.limb_[k] ? -1 : 1;
    return 0;
  }

  /// r[0, x.size_ + y.size_) := |x|·|y| (schoolbook).
  static void multiply_into(const Wide& x, const Wide& y, std::uint64_t* r) {
    for (int k = 0; k < y.size_; ++k)  // the rows below set r[i + y.size_] themselves
      r[k] = 0;
    for (int i = 0; i < x.size_; ++i) {
      WideProduct carry = 0;
      const WideProduct xi = x.limb_[i];
      for (int j = 0; j < y.size_; ++j) {
        carry += xi * y.limb_[j] + r[i + j];
        r[i + j] = static_cast<std::uint64_t>(carry);
        carry >>= 64;
      }
      r[i + y.size_] = static_cast<std::uint64_t>(carry);
    }
  }

  /// x + (y with sign y_negative).
  [[gnu::always_inline]] static Wide sum(const Wide& x, const Wide& y, bool y_negative) {
    if (y.size_ == 0) return x;
    if (x.size_ == 0) {
      Wide out = y;
      out.negative_ = y_negative;
      return out;
    }
    if (x.negative_ == y_negative) {
      Wide out = add_magnitudes(x, y);
      out.negative_ = x.negative_;
      return out;
    }
    const int c = compare_magnitude(x, y);
    if (c == 0) return Wide{};
    Wide out = c > 0 ? subtract_magnitudes(x, y) : subtract_magnitudes(y, x);
    out.negative_ = c > 0 ? x.negative_ : y_negative;
    return out;
  }

  static Wide add_magnitudes(const Wide& x, const Wide& y) {
    const Wide& big = x.size_ >= y.size_ ? x : y;
    const Wide& small = x.size_ >= y.size_ ? y : x;
    Wide out;
    WideProduct carry = 0;
    for (int k = 0; k < big.size_; ++k) {
      carry += static_cast<WideProduct>(big.limb_[k]) + (k < small.size_ ? small.limb_[k] : 0);
      out.limb_[k] = static_cast<std::uint64_t>(carry);
      carry >>= 64;
    }
    out.size_ = big.size_;
    if (carry != 0) {
      if (out.size_ == kLimbs) throw WideOverflow{};
      out.limb_[out.size_++] = 1;
    }
    return out;
  }

  /// |x| − |y| for |x| > |y|.
  static Wide subtract_magnitudes(const Wide& x, const Wide& y) {
    Wide out;
    std::uint64_t borrow = 0;
    for (int k = 0; k < x.size_; ++k) {
      const std::uint64_t yk = k < y.size_ ? y.limb_[k] : 0;
      const WideProduct d = static_cast<WideProduct>(x.limb_[k]) - yk - borrow;
      out.limb_[k] = static_cast<std::uint64_t>(d);
      borrow = static_cast<std::uint64_t>(d >> 64) & 1;  // 1 when the limb wrapped
    }
    out.size_ = x.size_;
    out.trim();
    return out;
  }

  void trim() {
    while (size_ > 0 && limb_[size_ - 1] == 0)
      --size_;
    if (size_ == 0) negative_ = false;
  }

  std::uint64_t limb_[kLimbs];  ///< magnitude, least significant first; [size_, kLimbs) unused
  int size_ = 0;                ///< limbs in use, the top one non-zero; 0 for zero
  bool negative_ = false;       ///< never set for zero
};

}  // namespace gjklab::exact::detail
