
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/core/base/body_store.cpp" "core/base/CMakeFiles/elan_base.dir/body_store.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/body_store.cpp.o.d"
  "/work/wt-python/core/base/body_traits.cpp" "core/base/CMakeFiles/elan_base.dir/body_traits.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/body_traits.cpp.o.d"
  "/work/wt-python/core/base/bvh.cpp" "core/base/CMakeFiles/elan_base.dir/bvh.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/bvh.cpp.o.d"
  "/work/wt-python/core/base/compound.cpp" "core/base/CMakeFiles/elan_base.dir/compound.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/compound.cpp.o.d"
  "/work/wt-python/core/base/convex_hull.cpp" "core/base/CMakeFiles/elan_base.dir/convex_hull.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/convex_hull.cpp.o.d"
  "/work/wt-python/core/base/heightfield.cpp" "core/base/CMakeFiles/elan_base.dir/heightfield.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/heightfield.cpp.o.d"
  "/work/wt-python/core/base/packed_rotation.cpp" "core/base/CMakeFiles/elan_base.dir/packed_rotation.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/packed_rotation.cpp.o.d"
  "/work/wt-python/core/base/parallel.cpp" "core/base/CMakeFiles/elan_base.dir/parallel.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/parallel.cpp.o.d"
  "/work/wt-python/core/base/shape.cpp" "core/base/CMakeFiles/elan_base.dir/shape.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/shape.cpp.o.d"
  "/work/wt-python/core/base/state_hash.cpp" "core/base/CMakeFiles/elan_base.dir/state_hash.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/state_hash.cpp.o.d"
  "/work/wt-python/core/base/step_scratch.cpp" "core/base/CMakeFiles/elan_base.dir/step_scratch.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/step_scratch.cpp.o.d"
  "/work/wt-python/core/base/triangle_mesh.cpp" "core/base/CMakeFiles/elan_base.dir/triangle_mesh.cpp.o" "gcc" "core/base/CMakeFiles/elan_base.dir/triangle_mesh.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
