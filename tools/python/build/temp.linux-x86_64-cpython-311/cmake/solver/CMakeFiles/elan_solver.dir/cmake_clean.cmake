file(REMOVE_RECURSE
  "CMakeFiles/elan_solver.dir/bundles.cpp.o"
  "CMakeFiles/elan_solver.dir/bundles.cpp.o.d"
  "CMakeFiles/elan_solver.dir/color_contacts.cpp.o"
  "CMakeFiles/elan_solver.dir/color_contacts.cpp.o.d"
  "CMakeFiles/elan_solver.dir/coloring.cpp.o"
  "CMakeFiles/elan_solver.dir/coloring.cpp.o.d"
  "CMakeFiles/elan_solver.dir/contact_solver.cpp.o"
  "CMakeFiles/elan_solver.dir/contact_solver.cpp.o.d"
  "CMakeFiles/elan_solver.dir/direct_solve.cpp.o"
  "CMakeFiles/elan_solver.dir/direct_solve.cpp.o.d"
  "CMakeFiles/elan_solver.dir/integrate.cpp.o"
  "CMakeFiles/elan_solver.dir/integrate.cpp.o.d"
  "CMakeFiles/elan_solver.dir/islands.cpp.o"
  "CMakeFiles/elan_solver.dir/islands.cpp.o.d"
  "CMakeFiles/elan_solver.dir/joint_solver.cpp.o"
  "CMakeFiles/elan_solver.dir/joint_solver.cpp.o.d"
  "CMakeFiles/elan_solver.dir/packets.cpp.o"
  "CMakeFiles/elan_solver.dir/packets.cpp.o.d"
  "CMakeFiles/elan_solver.dir/partition.cpp.o"
  "CMakeFiles/elan_solver.dir/partition.cpp.o.d"
  "CMakeFiles/elan_solver.dir/solve.cpp.o"
  "CMakeFiles/elan_solver.dir/solve.cpp.o.d"
  "CMakeFiles/elan_solver.dir/stage_executor.cpp.o"
  "CMakeFiles/elan_solver.dir/stage_executor.cpp.o.d"
  "libelan_solver.a"
  "libelan_solver.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/elan_solver.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
