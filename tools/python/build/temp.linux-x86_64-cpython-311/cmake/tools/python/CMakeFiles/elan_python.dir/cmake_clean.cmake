file(REMOVE_RECURSE
  "CMakeFiles/elan_python.dir/src/bodies.cpp.o"
  "CMakeFiles/elan_python.dir/src/bodies.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/columns.cpp.o"
  "CMakeFiles/elan_python.dir/src/columns.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/convert.cpp.o"
  "CMakeFiles/elan_python.dir/src/convert.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/errors.cpp.o"
  "CMakeFiles/elan_python.dir/src/errors.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/events.cpp.o"
  "CMakeFiles/elan_python.dir/src/events.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/joints.cpp.o"
  "CMakeFiles/elan_python.dir/src/joints.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/loading.cpp.o"
  "CMakeFiles/elan_python.dir/src/loading.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/module.cpp.o"
  "CMakeFiles/elan_python.dir/src/module.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/queries.cpp.o"
  "CMakeFiles/elan_python.dir/src/queries.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/settings.cpp.o"
  "CMakeFiles/elan_python.dir/src/settings.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/shapes.cpp.o"
  "CMakeFiles/elan_python.dir/src/shapes.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/snapshots.cpp.o"
  "CMakeFiles/elan_python.dir/src/snapshots.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/stepping.cpp.o"
  "CMakeFiles/elan_python.dir/src/stepping.cpp.o.d"
  "CMakeFiles/elan_python.dir/src/world_class.cpp.o"
  "CMakeFiles/elan_python.dir/src/world_class.cpp.o.d"
  "elan/_elan.cpython-311-x86_64-linux-gnu.so"
  "elan/_elan.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/elan_python.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
