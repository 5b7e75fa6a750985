
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/tools/python/src/bodies.cpp" "tools/python/CMakeFiles/elan_python.dir/src/bodies.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/bodies.cpp.o.d"
  "/work/wt-python/tools/python/src/columns.cpp" "tools/python/CMakeFiles/elan_python.dir/src/columns.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/columns.cpp.o.d"
  "/work/wt-python/tools/python/src/convert.cpp" "tools/python/CMakeFiles/elan_python.dir/src/convert.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/convert.cpp.o.d"
  "/work/wt-python/tools/python/src/errors.cpp" "tools/python/CMakeFiles/elan_python.dir/src/errors.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/errors.cpp.o.d"
  "/work/wt-python/tools/python/src/events.cpp" "tools/python/CMakeFiles/elan_python.dir/src/events.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/events.cpp.o.d"
  "/work/wt-python/tools/python/src/joints.cpp" "tools/python/CMakeFiles/elan_python.dir/src/joints.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/joints.cpp.o.d"
  "/work/wt-python/tools/python/src/loading.cpp" "tools/python/CMakeFiles/elan_python.dir/src/loading.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/loading.cpp.o.d"
  "/work/wt-python/tools/python/src/module.cpp" "tools/python/CMakeFiles/elan_python.dir/src/module.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/module.cpp.o.d"
  "/work/wt-python/tools/python/src/queries.cpp" "tools/python/CMakeFiles/elan_python.dir/src/queries.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/queries.cpp.o.d"
  "/work/wt-python/tools/python/src/settings.cpp" "tools/python/CMakeFiles/elan_python.dir/src/settings.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/settings.cpp.o.d"
  "/work/wt-python/tools/python/src/shapes.cpp" "tools/python/CMakeFiles/elan_python.dir/src/shapes.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/shapes.cpp.o.d"
  "/work/wt-python/tools/python/src/snapshots.cpp" "tools/python/CMakeFiles/elan_python.dir/src/snapshots.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/snapshots.cpp.o.d"
  "/work/wt-python/tools/python/src/stepping.cpp" "tools/python/CMakeFiles/elan_python.dir/src/stepping.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/stepping.cpp.o.d"
  "/work/wt-python/tools/python/src/world_class.cpp" "tools/python/CMakeFiles/elan_python.dir/src/world_class.cpp.o" "gcc" "tools/python/CMakeFiles/elan_python.dir/src/world_class.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/scene/CMakeFiles/elan_scene.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/world/CMakeFiles/elan.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/broadphase/CMakeFiles/elan_broadphase.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/narrowphase/CMakeFiles/elan_narrowphase.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/solver/CMakeFiles/elan_solver.dir/DependInfo.cmake"
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/base/CMakeFiles/elan_base.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
