file(REMOVE_RECURSE
  "CMakeFiles/elan_base.dir/body_store.cpp.o"
  "CMakeFiles/elan_base.dir/body_store.cpp.o.d"
  "CMakeFiles/elan_base.dir/body_traits.cpp.o"
  "CMakeFiles/elan_base.dir/body_traits.cpp.o.d"
  "CMakeFiles/elan_base.dir/bvh.cpp.o"
  "CMakeFiles/elan_base.dir/bvh.cpp.o.d"
  "CMakeFiles/elan_base.dir/compound.cpp.o"
  "CMakeFiles/elan_base.dir/compound.cpp.o.d"
  "CMakeFiles/elan_base.dir/convex_hull.cpp.o"
  "CMakeFiles/elan_base.dir/convex_hull.cpp.o.d"
  "CMakeFiles/elan_base.dir/heightfield.cpp.o"
  "CMakeFiles/elan_base.dir/heightfield.cpp.o.d"
  "CMakeFiles/elan_base.dir/packed_rotation.cpp.o"
  "CMakeFiles/elan_base.dir/packed_rotation.cpp.o.d"
  "CMakeFiles/elan_base.dir/parallel.cpp.o"
  "CMakeFiles/elan_base.dir/parallel.cpp.o.d"
  "CMakeFiles/elan_base.dir/shape.cpp.o"
  "CMakeFiles/elan_base.dir/shape.cpp.o.d"
  "CMakeFiles/elan_base.dir/state_hash.cpp.o"
  "CMakeFiles/elan_base.dir/state_hash.cpp.o.d"
  "CMakeFiles/elan_base.dir/step_scratch.cpp.o"
  "CMakeFiles/elan_base.dir/step_scratch.cpp.o.d"
  "CMakeFiles/elan_base.dir/triangle_mesh.cpp.o"
  "CMakeFiles/elan_base.dir/triangle_mesh.cpp.o.d"
  "libelan_base.a"
  "libelan_base.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/elan_base.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
