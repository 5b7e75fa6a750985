// SPDX-License-Identifier: MIT
// Choosing the edge query's kernel (edge_query.hpp), once per process.
#include "core/base/simd_path.hpp"
#include "narrowphase/edge_query.hpp"

namespace elan::detail {

#if defined(ELAN_DISPATCH)
namespace isa_avx2 {
EdgeQuery query_gauss_edges(const Polyhedron& a, const Polyhedron& b);
}
namespace isa_avx512 {
EdgeQuery query_gauss_edges(const Polyhedron& a, const Polyhedron& b);
}
#endif

namespace {

using EdgeQueryKernel = EdgeQuery (*)(const Polyhedron&, const Polyhedron&);

EdgeQueryKernel pick_edge_query() {
#if defined(ELAN_DISPATCH)
  switch (process_simd_path()) {
    case SimdPath::Avx512:
      return &isa_avx512::query_gauss_edges;
    case SimdPath::Avx2:
      return &isa_avx2::query_gauss_edges;
    default:
      return &isa_sse2::query_gauss_edges;
  }
#else
  return &query_gauss_edges;
#endif
}

}  // namespace

EdgeQuery query_hull_edges(const Polyhedron& a, const Polyhedron& b) {
  static const EdgeQueryKernel kernel = pick_edge_query();
  return kernel(a, b);
}

}  // namespace elan::detail
