// SPDX-License-Identifier: MIT
// Little-endian byte writing and bounds-checked reading for snapshot formats, value by value
// (never a struct copy, so the layout is the format's and not the compiler's), and the checksum.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "elan/error.hpp"
#include "elan/math.hpp"

namespace elan::detail {

// 64-bit FNV-1a over 8-byte little-endian words (the tail zero-padded, then the length mixed
// in): each step h = (h ^ w) * odd prime is a bijection of h, so any single changed word (byte)
// changes the sum; a word at a time, not a byte, takes one multiply per eight bytes.
inline uint64_t checksum_words(std::span<const uint8_t> bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  const std::size_t words = bytes.size() / 8;
  for (std::size_t i = 0; i < words; ++i) {
    uint64_t w = 0;
    for (int k = 0; k < 8; ++k) w |= uint64_t(bytes[8 * i + k]) << (8 * k);
    h = (h ^ w) * 0x100000001b3ull;
  }
  uint64_t tail = 0;
  for (std::size_t k = 8 * words; k < bytes.size(); ++k) {
    tail |= uint64_t(bytes[k]) << (8 * (k - 8 * words));
  }
  h = (h ^ tail) * 0x100000001b3ull;
  return (h ^ uint64_t(bytes.size())) * 0x100000001b3ull;
}

using RealBits = std::conditional_t<sizeof(Real) == 8, uint64_t, uint32_t>;

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<uint8_t>& out) : out_(out) {}
  void u8(uint8_t v) { out_.push_back(v); }
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(uint8_t(v >> (8 * i)));
  }
  void u64(uint64_t v) {
    for (int i = 0; i < 8; ++i) out_.push_back(uint8_t(v >> (8 * i)));
  }
  void real(Real v) {
    const RealBits b = std::bit_cast<RealBits>(v);
    for (std::size_t i = 0; i < sizeof(Real); ++i) out_.push_back(uint8_t(b >> (8 * i)));
  }
  void vec3(const Vec3& v) {
    real(v.x());
    real(v.y());
    real(v.z());
  }
  void bytes(const uint8_t* p, std::size_t n) { out_.insert(out_.end(), p, p + n); }
  std::vector<uint8_t>& buffer() { return out_; }

 private:
  std::vector<uint8_t>& out_;
};

// Reads from [begin, end) of `bytes`; every read checks the remaining length and throws
// elan::Error(field) rather than read past the end.
class ByteReader {
 public:
  ByteReader(std::span<const uint8_t> bytes, const char* field) : bytes_(bytes), field_(field) {}
  uint8_t u8() {
    need(1);
    return bytes_[pos_++];
  }
  uint32_t u32() {
    need(4);
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(bytes_[pos_ + i]) << (8 * i);
    pos_ += 4;
    return v;
  }
  uint64_t u64() {
    need(8);
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(bytes_[pos_ + i]) << (8 * i);
    pos_ += 8;
    return v;
  }
  Real real() {
    need(sizeof(Real));
    RealBits b = 0;
    for (std::size_t i = 0; i < sizeof(Real); ++i) b |= RealBits(bytes_[pos_ + i]) << (8 * i);
    pos_ += sizeof(Real);
    return std::bit_cast<Real>(b);
  }
  Vec3 vec3() {
    const Real x = real(), y = real();
    return Vec3(x, y, real());
  }
  // A count of items each at least `min_bytes` long: refused when they cannot fit, so a
  // corrupt count never triggers a huge allocation.
  uint32_t count(std::size_t min_bytes, const char* what) {
    const uint32_t n = u32();
    if (uint64_t(n) * min_bytes > remaining()) fail(std::string(what) + " count runs past the end");
    return n;
  }
  void need(std::size_t n) const {
    if (n > remaining()) fail("truncated");
  }
  [[noreturn]] void fail(const std::string& message) const { throw Error(field_, message); }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::size_t pos() const { return pos_; }

 private:
  std::span<const uint8_t> bytes_;
  const char* field_;
  std::size_t pos_ = 0;
};

}  // namespace elan::detail
