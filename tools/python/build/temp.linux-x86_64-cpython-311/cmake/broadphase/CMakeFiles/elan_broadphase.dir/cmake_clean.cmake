file(REMOVE_RECURSE
  "CMakeFiles/elan_broadphase.dir/all_pairs.cpp.o"
  "CMakeFiles/elan_broadphase.dir/all_pairs.cpp.o.d"
  "CMakeFiles/elan_broadphase.dir/bounds.cpp.o"
  "CMakeFiles/elan_broadphase.dir/bounds.cpp.o.d"
  "CMakeFiles/elan_broadphase.dir/brute_force.cpp.o"
  "CMakeFiles/elan_broadphase.dir/brute_force.cpp.o.d"
  "CMakeFiles/elan_broadphase.dir/dynamic_tree.cpp.o"
  "CMakeFiles/elan_broadphase.dir/dynamic_tree.cpp.o.d"
  "CMakeFiles/elan_broadphase.dir/sweep_and_prune.cpp.o"
  "CMakeFiles/elan_broadphase.dir/sweep_and_prune.cpp.o.d"
  "CMakeFiles/elan_broadphase.dir/tree_pairs.cpp.o"
  "CMakeFiles/elan_broadphase.dir/tree_pairs.cpp.o.d"
  "libelan_broadphase.a"
  "libelan_broadphase.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/elan_broadphase.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
