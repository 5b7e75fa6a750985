
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/solver/bundles.cpp" "solver/CMakeFiles/elan_solver.dir/bundles.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/bundles.cpp.o.d"
  "/work/wt-python/solver/color_contacts.cpp" "solver/CMakeFiles/elan_solver.dir/color_contacts.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/color_contacts.cpp.o.d"
  "/work/wt-python/solver/coloring.cpp" "solver/CMakeFiles/elan_solver.dir/coloring.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/coloring.cpp.o.d"
  "/work/wt-python/solver/contact_solver.cpp" "solver/CMakeFiles/elan_solver.dir/contact_solver.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/contact_solver.cpp.o.d"
  "/work/wt-python/solver/direct_solve.cpp" "solver/CMakeFiles/elan_solver.dir/direct_solve.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/direct_solve.cpp.o.d"
  "/work/wt-python/solver/integrate.cpp" "solver/CMakeFiles/elan_solver.dir/integrate.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/integrate.cpp.o.d"
  "/work/wt-python/solver/islands.cpp" "solver/CMakeFiles/elan_solver.dir/islands.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/islands.cpp.o.d"
  "/work/wt-python/solver/joint_solver.cpp" "solver/CMakeFiles/elan_solver.dir/joint_solver.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/joint_solver.cpp.o.d"
  "/work/wt-python/solver/packets.cpp" "solver/CMakeFiles/elan_solver.dir/packets.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/packets.cpp.o.d"
  "/work/wt-python/solver/partition.cpp" "solver/CMakeFiles/elan_solver.dir/partition.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/partition.cpp.o.d"
  "/work/wt-python/solver/solve.cpp" "solver/CMakeFiles/elan_solver.dir/solve.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/solve.cpp.o.d"
  "/work/wt-python/solver/stage_executor.cpp" "solver/CMakeFiles/elan_solver.dir/stage_executor.cpp.o" "gcc" "solver/CMakeFiles/elan_solver.dir/stage_executor.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/base/CMakeFiles/elan_base.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
