
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/core/scene/body_schema.cpp" "core/scene/CMakeFiles/elan_scene.dir/body_schema.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/body_schema.cpp.o.d"
  "/work/wt-python/core/scene/generators.cpp" "core/scene/CMakeFiles/elan_scene.dir/generators.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/generators.cpp.o.d"
  "/work/wt-python/core/scene/geometry_schema.cpp" "core/scene/CMakeFiles/elan_scene.dir/geometry_schema.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/geometry_schema.cpp.o.d"
  "/work/wt-python/core/scene/joint_generators.cpp" "core/scene/CMakeFiles/elan_scene.dir/joint_generators.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/joint_generators.cpp.o.d"
  "/work/wt-python/core/scene/joint_schema.cpp" "core/scene/CMakeFiles/elan_scene.dir/joint_schema.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/joint_schema.cpp.o.d"
  "/work/wt-python/core/scene/json_reader.cpp" "core/scene/CMakeFiles/elan_scene.dir/json_reader.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/json_reader.cpp.o.d"
  "/work/wt-python/core/scene/load_into.cpp" "core/scene/CMakeFiles/elan_scene.dir/load_into.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/load_into.cpp.o.d"
  "/work/wt-python/core/scene/obj_file.cpp" "core/scene/CMakeFiles/elan_scene.dir/obj_file.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/obj_file.cpp.o.d"
  "/work/wt-python/core/scene/parse_scene.cpp" "core/scene/CMakeFiles/elan_scene.dir/parse_scene.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/parse_scene.cpp.o.d"
  "/work/wt-python/core/scene/ragdoll.cpp" "core/scene/CMakeFiles/elan_scene.dir/ragdoll.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/ragdoll.cpp.o.d"
  "/work/wt-python/core/scene/regular_file.cpp" "core/scene/CMakeFiles/elan_scene.dir/regular_file.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/regular_file.cpp.o.d"
  "/work/wt-python/core/scene/run_summary.cpp" "core/scene/CMakeFiles/elan_scene.dir/run_summary.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/run_summary.cpp.o.d"
  "/work/wt-python/core/scene/schema_checks.cpp" "core/scene/CMakeFiles/elan_scene.dir/schema_checks.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/schema_checks.cpp.o.d"
  "/work/wt-python/core/scene/self_contained.cpp" "core/scene/CMakeFiles/elan_scene.dir/self_contained.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/self_contained.cpp.o.d"
  "/work/wt-python/core/scene/terrain.cpp" "core/scene/CMakeFiles/elan_scene.dir/terrain.cpp.o" "gcc" "core/scene/CMakeFiles/elan_scene.dir/terrain.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/world/CMakeFiles/elan.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/broadphase/CMakeFiles/elan_broadphase.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/narrowphase/CMakeFiles/elan_narrowphase.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/solver/CMakeFiles/elan_solver.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/base/CMakeFiles/elan_base.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
