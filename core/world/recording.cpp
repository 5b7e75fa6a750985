// SPDX-License-Identifier: MIT
// Recording file format, version 3 (all integers little-endian):
//   magic "\x89ELANREC" | u32 version | u32 real_bytes | (3) u64 n, engine version |
//   (3) u64 n, determinism promise | u64 steps | f64 timestep | i32 substeps | i32 iterations |
//   u32 threads | u32 broadphase | u64 keyframe_every | u64 n, scene name | u64 n, scene text |
//   (3) u64 n, starting snapshot | (3) u64 n, calls | u64 k keyframes, each: u64 step, u64 n,
//   n bytes of snapshot | u64 n, n hashes (u64) | u64 FNV-1a of every byte before it.
// Version 2 is the same without the fields marked (3); version 1 also without keyframe_every and
// the keyframes; both are still read. The promise sits right after the real size, so a
// recording from a build with other promises is named as such before anything else is read. The
// hashes stay last so the newest step sits just before the checksum in every version.
// The leading 0x89 byte keeps a text file from ever passing as a recording (as in PNG).
#include "elan/recording.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "elan/defs.hpp"

namespace elan {
namespace {

constexpr char kMagic[kRecordingMagicBytes] = {'\x89', 'E', 'L', 'A', 'N', 'R', 'E', 'C'};
constexpr uint32_t kVersion = kRecordingVersion;
constexpr uint32_t kOldestVersion = kOldestRecordingVersion;

// FNV-1a, 64 bit: every single-byte change changes the sum (each step is a bijection), which is
// what corruption and truncation checks need; no cryptographic strength is sought.
uint64_t fnv1a(const char* data, std::size_t size) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= uint8_t(data[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

void put_u64(std::string& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(char(uint8_t(v >> (8 * i))));
}
void put_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(char(uint8_t(v >> (8 * i))));
}
void put_string(std::string& out, std::string_view s) {
  put_u64(out, s.size());
  out += s;
}
void put_bytes(std::string& out, const std::vector<uint8_t>& v) {
  put_u64(out, v.size());
  out.append(reinterpret_cast<const char*>(v.data()), v.size());
}

class Reader {
 public:
  Reader(std::string_view bytes, std::size_t end, const std::string& file)
      : bytes_(bytes), end_(end), file_(file) {}
  uint64_t u64(const char* what) {
    need(8, what);
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(uint8_t(bytes_[pos_ + i])) << (8 * i);
    pos_ += 8;
    return v;
  }
  uint32_t u32(const char* what) {
    need(4, what);
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(uint8_t(bytes_[pos_ + i])) << (8 * i);
    pos_ += 4;
    return v;
  }
  std::string string(const char* what) {
    const uint64_t n = u64(what);
    need(n, what);
    std::string s(bytes_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  std::vector<uint8_t> byte_vector(const char* what) {
    const uint64_t n = u64(what);
    need(n, what);
    std::vector<uint8_t> v(bytes_.begin() + std::ptrdiff_t(pos_),
                           bytes_.begin() + std::ptrdiff_t(pos_ + n));
    pos_ += n;
    return v;
  }
  void need(uint64_t n, const char* what) {
    if (n > end_ - pos_)
      throw RecordingError(file_ + ": corrupt recording: " + what + " runs past the end");
  }
  std::size_t pos() const { return pos_; }

 private:
  std::string_view bytes_;
  std::size_t end_;
  const std::string& file_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string encode_recording(const Recording& r) {
  std::string out(kMagic, sizeof kMagic);
  put_u32(out, kVersion);
  put_u32(out, r.real_bytes);
  put_string(out, r.engine_version);
  put_string(out, r.promise);
  put_u64(out, r.steps);
  uint64_t dt_bits;
  std::memcpy(&dt_bits, &r.timestep, 8);
  put_u64(out, dt_bits);
  put_u32(out, uint32_t(r.substeps));
  put_u32(out, uint32_t(r.iterations));
  put_u32(out, r.threads);
  put_u32(out, r.broadphase);
  put_u64(out, r.keyframe_every);
  put_string(out, r.scene_name);
  put_string(out, r.scene_text);
  put_bytes(out, r.initial_snapshot);
  put_bytes(out, r.calls);
  put_u64(out, r.keyframes.size());
  for (const Keyframe& k : r.keyframes) {
    put_u64(out, k.step);
    put_u64(out, k.snapshot.size());
    out.append(reinterpret_cast<const char*>(k.snapshot.data()), k.snapshot.size());
  }
  put_u64(out, r.hashes.size());
  for (uint64_t h : r.hashes) put_u64(out, h);
  put_u64(out, fnv1a(out.data(), out.size()));
  return out;
}

void check_recording_magic(std::string_view head, const std::string& file) {
  const std::size_t magic_seen = std::min(head.size(), sizeof kMagic);
  if (head.empty() || std::memcmp(head.data(), kMagic, magic_seen) != 0) {
    throw RecordingError(file + ": not an elan recording (it does not start with the magic bytes)");
  }
}

Recording decode_recording(std::string_view bytes, const std::string& file) {
  check_recording_magic(bytes, file);
  if (bytes.size() < sizeof kMagic + 4 + 8) {
    throw RecordingError(file + ": truncated recording (" + std::to_string(bytes.size()) +
                         " bytes)");
  }
  const std::size_t body = bytes.size() - 8;
  uint64_t stored = 0;
  for (int i = 0; i < 8; ++i) stored |= uint64_t(uint8_t(bytes[body + i])) << (8 * i);
  if (stored != fnv1a(bytes.data(), body)) {
    throw RecordingError(file + ": truncated or corrupt recording (checksum mismatch)");
  }
  Reader in(bytes, body, file);
  in.need(sizeof kMagic, "magic");
  in.u64("magic");
  const uint32_t version = in.u32("version");
  if (version < kOldestVersion || version > kVersion) {
    throw RecordingError(file + ": unsupported recording version " + std::to_string(version) +
                         " (this elan reads versions " + std::to_string(kOldestVersion) + " to " +
                         std::to_string(kVersion) + ")");
  }
  Recording r;
  r.version = version;
  r.real_bytes = in.u32("real size");
  if (version >= 3) {
    r.engine_version = in.string("engine version");
    r.promise = in.string("determinism promise");
  }
  r.steps = in.u64("steps");
  const uint64_t dt_bits = in.u64("timestep");
  std::memcpy(&r.timestep, &dt_bits, 8);
  r.substeps = int32_t(in.u32("substeps"));
  r.iterations = int32_t(in.u32("iterations"));
  r.threads = in.u32("threads");
  r.broadphase = in.u32("broadphase");
  // A program recording's steps carry their own timesteps; 0 is its "none taken".
  const bool timestep_ok = r.timestep > 0 || (version >= 3 && r.timestep == 0);
  if (!timestep_ok || !std::isfinite(r.timestep) || r.broadphase > 2) {
    throw RecordingError(file + ": corrupt recording: invalid settings");
  }
  // The library's own ranges (elan/defs.hpp): a value no world accepts is a corrupt recording,
  // named here rather than failing later as if the recorded scene were wrong.
  const auto check_range = [&](const char* field, int64_t v, int64_t lo, int64_t hi) {
    if (v < lo || v > hi) {
      throw RecordingError(file + ": corrupt recording: recorded " + field + " must be in " +
                           std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
                           std::to_string(v));
    }
  };
  check_range("substeps", r.substeps, 1, kMaxSubsteps);
  check_range("iterations", r.iterations, 1, kMaxIterations);
  check_range("threads", r.threads, 0, kMaxThreads);
  if (version >= 2) r.keyframe_every = in.u64("keyframe interval");
  r.scene_name = in.string("scene name");
  r.scene_text = in.string("scene text");
  if (version >= 3) {
    r.initial_snapshot = in.byte_vector("starting snapshot");
    r.calls = in.byte_vector("calls");
  }
  if (version >= 2) {
    const uint64_t keyframes = in.u64("keyframe count");
    // Each keyframe takes at least its two 8-byte counts.
    if (keyframes > (body - in.pos()) / 16) {
      throw RecordingError(file + ": corrupt recording: keyframes run past the end");
    }
    r.keyframes.resize(keyframes);
    for (std::size_t k = 0; k < r.keyframes.size(); ++k) {
      r.keyframes[k].step = in.u64("keyframe step");
      r.keyframes[k].snapshot = in.byte_vector("keyframe");
      const bool ordered =
          k == 0 ? r.keyframes[k].step == 0 : r.keyframes[k].step > r.keyframes[k - 1].step;
      if (!ordered || r.keyframes[k].step > r.steps) {
        throw RecordingError(file + ": corrupt recording: keyframe steps out of order");
      }
    }
  }
  const uint64_t count = in.u64("hash count");
  if (count != r.steps + 1 || r.steps == UINT64_MAX) {
    throw RecordingError(file + ": corrupt recording: " + std::to_string(count) + " hashes for " +
                         std::to_string(r.steps) + " steps");
  }
  if (count > body / 8) throw RecordingError(file + ": corrupt recording: hashes run past the end");
  r.hashes.resize(count);
  for (uint64_t& h : r.hashes) h = in.u64("hashes");
  if (in.pos() != body) throw RecordingError(file + ": corrupt recording: trailing bytes");
  return r;
}

void check_recording_build(const Recording& r, const std::string& file) {
  if (r.real_bytes != sizeof(Real)) {
    throw RecordingError(file + ": recorded by a build with " + std::to_string(r.real_bytes * 8) +
                         "-bit Real, this build uses " + std::to_string(sizeof(Real) * 8) +
                         "-bit: hashes are comparable only between builds with the same promises");
  }
  if (r.version >= 3 && r.promise != kDeterminismPromise) {
    throw RecordingError(file + ": recorded by a build that promises \"" + r.promise +
                         "\", this build promises \"" + kDeterminismPromise +
                         "\": hashes are comparable only between builds with the same promises");
  }
}

const Keyframe* keyframe_at_or_before(const Recording& r, uint64_t step) {
  const Keyframe* best = nullptr;
  for (const Keyframe& k : r.keyframes) {
    if (k.step <= step) best = &k;
  }
  return best;
}

}  // namespace elan
