// SPDX-License-Identifier: MIT
// Trajectory CSV writer. %.9g round-trips a float and %.17g a double (the digits needed to
// identify any value of the type, C++ std::numeric_limits<T>::max_digits10).
#include "tools/trajectory.hpp"

#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace elan::cli {
namespace {

constexpr const char* kRealFormat = std::numeric_limits<Real>::max_digits10 == 9 ? "%.9g" : "%.17g";

void append(std::string& line, const char* format, double v) {
  char buf[40];
  const int n = std::snprintf(buf, sizeof buf, format, v);
  line.append(buf, std::size_t(n));
}

}  // namespace

TrajectoryWriter::TrajectoryWriter(const std::string& path, const World& world) : path_(path) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
  for (std::size_t i = 0; i < world.body_count(); ++i) {
    const BodyId id = world.body_at(i);
    if (world.motion_type(id) != MotionType::Static) {
      bodies_.push_back(id);
      indices_.push_back(i);
    }
  }
  std::fputs("step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n", file_);
}

TrajectoryWriter::~TrajectoryWriter() {
  if (file_) std::fclose(file_);
}

void TrajectoryWriter::write(const World& world, uint64_t step, double time) {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const BodyId id = bodies_[b];
    line_ = std::to_string(step);
    line_ += ',';
    append(line_, "%.17g", time);
    line_ += ',';
    line_ += std::to_string(indices_[b]);
    const Vec3 p = world.position(id);
    const Quat q = world.orientation(id);
    const Vec3 v = world.linear_velocity(id);
    const Vec3 w = world.angular_velocity(id);
    const Real values[13] = {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(),
                             v.x(), v.y(), v.z(), w.x(), w.y(), w.z()};
    for (Real r : values) {
      line_ += ',';
      append(line_, kRealFormat, double(r));
    }
    line_ += '\n';
    std::fwrite(line_.data(), 1, line_.size(), file_);
  }
}

void TrajectoryWriter::close() {
  std::FILE* f = file_;
  file_ = nullptr;
  const bool failed = std::ferror(f) != 0;
  if (std::fclose(f) != 0 || failed) {
    throw std::runtime_error(path_ + ": writing the trajectory failed: " + std::strerror(errno));
  }
}

}  // namespace elan::cli
