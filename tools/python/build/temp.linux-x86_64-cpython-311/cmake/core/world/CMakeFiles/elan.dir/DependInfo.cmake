
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/core/world/body_control.cpp" "core/world/CMakeFiles/elan.dir/body_control.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/body_control.cpp.o.d"
  "/work/wt-python/core/world/body_state.cpp" "core/world/CMakeFiles/elan.dir/body_state.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/body_state.cpp.o.d"
  "/work/wt-python/core/world/bulk.cpp" "core/world/CMakeFiles/elan.dir/bulk.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/bulk.cpp.o.d"
  "/work/wt-python/core/world/character_mover.cpp" "core/world/CMakeFiles/elan.dir/character_mover.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/character_mover.cpp.o.d"
  "/work/wt-python/core/world/contact_views.cpp" "core/world/CMakeFiles/elan.dir/contact_views.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/contact_views.cpp.o.d"
  "/work/wt-python/core/world/continuous.cpp" "core/world/CMakeFiles/elan.dir/continuous.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/continuous.cpp.o.d"
  "/work/wt-python/core/world/debug_draw.cpp" "core/world/CMakeFiles/elan.dir/debug_draw.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/debug_draw.cpp.o.d"
  "/work/wt-python/core/world/divergence.cpp" "core/world/CMakeFiles/elan.dir/divergence.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/divergence.cpp.o.d"
  "/work/wt-python/core/world/events.cpp" "core/world/CMakeFiles/elan.dir/events.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/events.cpp.o.d"
  "/work/wt-python/core/world/joints.cpp" "core/world/CMakeFiles/elan.dir/joints.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/joints.cpp.o.d"
  "/work/wt-python/core/world/memory_use.cpp" "core/world/CMakeFiles/elan.dir/memory_use.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/memory_use.cpp.o.d"
  "/work/wt-python/core/world/overlap_queries.cpp" "core/world/CMakeFiles/elan.dir/overlap_queries.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/overlap_queries.cpp.o.d"
  "/work/wt-python/core/world/point_queries.cpp" "core/world/CMakeFiles/elan.dir/point_queries.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/point_queries.cpp.o.d"
  "/work/wt-python/core/world/queries.cpp" "core/world/CMakeFiles/elan.dir/queries.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/queries.cpp.o.d"
  "/work/wt-python/core/world/query_tree.cpp" "core/world/CMakeFiles/elan.dir/query_tree.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/query_tree.cpp.o.d"
  "/work/wt-python/core/world/ray_queries.cpp" "core/world/CMakeFiles/elan.dir/ray_queries.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/ray_queries.cpp.o.d"
  "/work/wt-python/core/world/sensors.cpp" "core/world/CMakeFiles/elan.dir/sensors.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/sensors.cpp.o.d"
  "/work/wt-python/core/world/shape_cast.cpp" "core/world/CMakeFiles/elan.dir/shape_cast.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/shape_cast.cpp.o.d"
  "/work/wt-python/core/world/shape_defs.cpp" "core/world/CMakeFiles/elan.dir/shape_defs.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/shape_defs.cpp.o.d"
  "/work/wt-python/core/world/snapshot.cpp" "core/world/CMakeFiles/elan.dir/snapshot.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/snapshot.cpp.o.d"
  "/work/wt-python/core/world/step.cpp" "core/world/CMakeFiles/elan.dir/step.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/step.cpp.o.d"
  "/work/wt-python/core/world/thread_pool.cpp" "core/world/CMakeFiles/elan.dir/thread_pool.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/thread_pool.cpp.o.d"
  "/work/wt-python/core/world/world.cpp" "core/world/CMakeFiles/elan.dir/world.cpp.o" "gcc" "core/world/CMakeFiles/elan.dir/world.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/base/CMakeFiles/elan_base.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/broadphase/CMakeFiles/elan_broadphase.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/narrowphase/CMakeFiles/elan_narrowphase.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/solver/CMakeFiles/elan_solver.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
