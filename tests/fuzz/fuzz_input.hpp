// SPDX-License-Identifier: MIT
// What the fuzz targets share: a reader that turns the fuzzer's bytes into bounded numbers (so
// that the mutations explore shapes and poses, not mostly out-of-range values), and the check
// that stops a run with a message (libFuzzer and the corpus driver both report the abort).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "elan/math.hpp"

namespace elan::fuzz {

// Reads the input from the front; past its end every read gives zero, so any input is valid.
struct Bytes {
  const uint8_t* data;
  std::size_t size;
  std::size_t at = 0;

  bool empty() const { return at >= size; }
  uint8_t u8() { return at < size ? data[at++] : 0; }
  // Low byte first. determinism: each read in a statement of its own, as the operands of one
  // expression (and a call's arguments) may be read in any order: GCC and Clang differ.
  uint16_t u16() {
    const uint32_t low = u8();
    const uint32_t high = u8();
    return uint16_t(low | (high << 8));
  }
  uint32_t u32() {
    const uint32_t low = u16();
    const uint32_t high = u16();
    return low | (high << 16);
  }
  // A value in [lo, hi] on a grid of 65536 steps.
  Real in(Real lo, Real hi) { return lo + (hi - lo) * Real(u16()) / Real(65535); }
  // Any float bit pattern, NaN and infinities included (for the hull's "points" refusal).
  float raw_float() {
    const uint32_t bits = u32();
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
  Vec3 in_box(Real half) { return {in(-half, half), in(-half, half), in(-half, half)}; }
  // A unit quaternion (a zero draw gives the identity).
  Quat rotation() {
    // Braces: the four reads happen in order, as in_box's.
    Quat q{in(-1, 1), in(-1, 1), in(-1, 1), in(-1, 1)};
    if (!(q.norm() > Real(1e-3))) return Quat::Identity();
    q.normalize();
    return q;
  }
};

// A failed property: prints it and aborts, which libFuzzer reports with the input that did it.
[[noreturn]] inline void fail(const char* what, const std::string& detail = {}) {
  std::fprintf(stderr, "fuzz property failed: %s %s\n", what, detail.c_str());
  std::abort();
}
inline void require(bool ok, const char* what, const std::string& detail = {}) {
  if (!ok) fail(what, detail);
}

// An error message is one line (elan::one_line): a refusal must not break a log.
inline void require_one_line(const char* message) {
  require(std::strchr(message, '\n') == nullptr && std::strchr(message, '\r') == nullptr,
          "an error message is one line:", message);
  require(std::strlen(message) > 0, "an error message is not empty");
}

}  // namespace elan::fuzz
