// Case results as bytes, for the ranks of a distributed run to send them to the rank that
// writes the archive (src/experiment/run/driver.cpp). Private to src/experiment.
//
// Every field the archive stores goes through the archive's own schema tables, so a column
// added to the schema is sent without a change here. The bytes are in the machine's own
// representation: the ranks of one job run the same build on machines of one architecture.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "gjklab/experiment/cases/records.hpp"

namespace gjklab::experiment::codec {

/// Appends values to a byte string.
class ByteWriter {
 public:
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void put(const T& v) { bytes_.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void put_string(std::string_view s) {
    put<std::uint64_t>(s.size());
    bytes_.append(s);
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

/// Reads values back in the order they were put; a read past the end (a truncated or foreign
/// message) throws instead of reading garbage.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}

  template <class T>
  requires std::is_trivially_copyable_v<T> T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    need(n);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  bool done() const { return at_ == bytes_.size(); }
  /// Bytes read so far: where the rest of the message starts.
  std::size_t position() const { return at_; }

 private:
  void need(std::uint64_t n) const {
    if (n > bytes_.size() - at_)
      throw std::runtime_error("malformed result message: " + std::to_string(n) +
                               " bytes wanted, " + std::to_string(bytes_.size() - at_) + " left");
  }

  std::string_view bytes_;
  std::size_t at_ = 0;
};

/// Appends the results (records, exact answers, algorithms, geometry, traces).
void encode_results(ByteWriter& out, std::span<const CaseResult> results);
/// The results encode_results wrote; throws std::runtime_error on a malformed message.
std::vector<CaseResult> decode_results(ByteReader& in);

}  // namespace gjklab::experiment::codec
