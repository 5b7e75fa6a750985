
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/wt-python/narrowphase/capsule_polyhedron.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/capsule_polyhedron.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/capsule_polyhedron.cpp.o.d"
  "/work/wt-python/narrowphase/clip.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/clip.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/clip.cpp.o.d"
  "/work/wt-python/narrowphase/collide.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/collide.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/collide.cpp.o.d"
  "/work/wt-python/narrowphase/collide_pairs.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/collide_pairs.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/collide_pairs.cpp.o.d"
  "/work/wt-python/narrowphase/composite.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/composite.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/composite.cpp.o.d"
  "/work/wt-python/narrowphase/contact_store.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/contact_store.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/contact_store.cpp.o.d"
  "/work/wt-python/narrowphase/epa.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/epa.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/epa.cpp.o.d"
  "/work/wt-python/narrowphase/general.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/general.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/general.cpp.o.d"
  "/work/wt-python/narrowphase/gjk.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/gjk.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/gjk.cpp.o.d"
  "/work/wt-python/narrowphase/manifold_reduce.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/manifold_reduce.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/manifold_reduce.cpp.o.d"
  "/work/wt-python/narrowphase/polyhedron.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/polyhedron.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/polyhedron.cpp.o.d"
  "/work/wt-python/narrowphase/round_pairs.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/round_pairs.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/round_pairs.cpp.o.d"
  "/work/wt-python/narrowphase/sat.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/sat.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/sat.cpp.o.d"
  "/work/wt-python/narrowphase/shape_cast.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/shape_cast.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/shape_cast.cpp.o.d"
  "/work/wt-python/narrowphase/shape_point.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/shape_point.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/shape_point.cpp.o.d"
  "/work/wt-python/narrowphase/supporting_feature.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/supporting_feature.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/supporting_feature.cpp.o.d"
  "/work/wt-python/narrowphase/toi.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/toi.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/toi.cpp.o.d"
  "/work/wt-python/narrowphase/triangle_contact.cpp" "narrowphase/CMakeFiles/elan_narrowphase.dir/triangle_contact.cpp.o" "gcc" "narrowphase/CMakeFiles/elan_narrowphase.dir/triangle_contact.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/wt-python/tools/python/build/temp.linux-x86_64-cpython-311/cmake/core/base/CMakeFiles/elan_base.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
