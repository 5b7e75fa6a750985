
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/broadphase/all_pairs.cpp" "broadphase/CMakeFiles/elan_broadphase.dir/all_pairs.cpp.o" "gcc" "broadphase/CMakeFiles/elan_broadphase.dir/all_pairs.cpp.o.d"
  "/work/wt-python/broadphase/bounds.cpp" "broadphase/CMakeFiles/elan_broadphase.dir/bounds.cpp.o" "gcc" "broadphase/CMakeFiles/elan_broadphase.dir/bounds.cpp.o.d"
  "/work/wt-python/broadphase/brute_force.cpp" "broadphase/CMakeFiles/elan_broadphase.dir/brute_force.cpp.o" "gcc" "broadphase/CMakeFiles/elan_broadphase.dir/brute_force.cpp.o.d"
  "/work/wt-python/broadphase/dynamic_tree.cpp" "broadphase/CMakeFiles/elan_broadphase.dir/dynamic_tree.cpp.o" "gcc" "broadphase/CMakeFiles/elan_broadphase.dir/dynamic_tree.cpp.o.d"
  "/work/wt-python/broadphase/sweep_and_prune.cpp" "broadphase/CMakeFiles/elan_broadphase.dir/sweep_and_prune.cpp.o" "gcc" "broadphase/CMakeFiles/elan_broadphase.dir/sweep_and_prune.cpp.o.d"
  "/work/wt-python/broadphase/tree_pairs.cpp" "broadphase/CMakeFiles/elan_broadphase.dir/tree_pairs.cpp.o" "gcc" "broadphase/CMakeFiles/elan_broadphase.dir/tree_pairs.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/base/CMakeFiles/elan_base.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
