// SPDX-License-Identifier: MIT
#include "tools/viewer/overlay.hpp"

#include "elan/debug_draw.hpp"

namespace elan::viewer {
namespace {

Eigen::Vector4f rgba(DebugColor c) {
  return {c.r, c.g, c.b, c.a};
}

class LineDrawer final : public DebugDrawer {
 public:
  explicit LineDrawer(Renderer& renderer) : renderer_(renderer) {}
  void draw_shape(BodyId, const ShapeDef&, const Transform&, DebugColor, bool) override {}
  void draw_line(const Vec3& a, const Vec3& b, DebugColor color) override {
    renderer_.add_overlay_line(a.cast<float>(), b.cast<float>(), rgba(color));
  }
  // A point as three short crossed lines (a size in pixels would need the projection here; a
  // fixed length in metres reads as well at the distances a scene is seen from).
  void draw_point(const Vec3& p, float size_pixels, DebugColor color) override {
    const float h = 0.01f * size_pixels;
    const Eigen::Vector3f c = p.cast<float>();
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3f d = Eigen::Vector3f::Zero();
      d[axis] = h;
      renderer_.add_overlay_line(c - d, c + d, rgba(color));
    }
  }
  void draw_box(const Aabb& box, DebugColor color) override {
    const Eigen::Vector3f lo = box.lo.cast<float>(), hi = box.hi.cast<float>();
    // The twelve edges: from each corner, to the corners that differ from it in one axis
    // where it has the low coordinate.
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f a((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                              (corner & 4) ? hi.z() : lo.z());
      for (int axis = 0; axis < 3; ++axis) {
        if (corner & (1 << axis)) continue;
        Eigen::Vector3f b = a;
        b[axis] = hi[axis];
        renderer_.add_overlay_line(a, b, rgba(color));
      }
    }
  }

 private:
  Renderer& renderer_;
};

}  // namespace

void draw_overlays(const World& world, uint32_t flags, Renderer& renderer) {
  // Shapes, island and half colours included, are the scene view's; kDrawSolverHalves stays for
  // the contacts of the cut (its shape calls are ignored here).
  flags &= ~uint32_t(kDrawShapes | kDrawIslands);
  if (flags == 0) return;
  LineDrawer drawer(renderer);
  world.debug_draw(drawer, flags);
}

}  // namespace elan::viewer
