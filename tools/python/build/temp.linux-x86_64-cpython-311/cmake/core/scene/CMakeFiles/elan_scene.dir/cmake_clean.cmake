file(REMOVE_RECURSE
  "CMakeFiles/elan_scene.dir/body_schema.cpp.o"
  "CMakeFiles/elan_scene.dir/body_schema.cpp.o.d"
  "CMakeFiles/elan_scene.dir/generators.cpp.o"
  "CMakeFiles/elan_scene.dir/generators.cpp.o.d"
  "CMakeFiles/elan_scene.dir/geometry_schema.cpp.o"
  "CMakeFiles/elan_scene.dir/geometry_schema.cpp.o.d"
  "CMakeFiles/elan_scene.dir/joint_generators.cpp.o"
  "CMakeFiles/elan_scene.dir/joint_generators.cpp.o.d"
  "CMakeFiles/elan_scene.dir/joint_schema.cpp.o"
  "CMakeFiles/elan_scene.dir/joint_schema.cpp.o.d"
  "CMakeFiles/elan_scene.dir/json_reader.cpp.o"
  "CMakeFiles/elan_scene.dir/json_reader.cpp.o.d"
  "CMakeFiles/elan_scene.dir/load_into.cpp.o"
  "CMakeFiles/elan_scene.dir/load_into.cpp.o.d"
  "CMakeFiles/elan_scene.dir/obj_file.cpp.o"
  "CMakeFiles/elan_scene.dir/obj_file.cpp.o.d"
  "CMakeFiles/elan_scene.dir/parse_scene.cpp.o"
  "CMakeFiles/elan_scene.dir/parse_scene.cpp.o.d"
  "CMakeFiles/elan_scene.dir/ragdoll.cpp.o"
  "CMakeFiles/elan_scene.dir/ragdoll.cpp.o.d"
  "CMakeFiles/elan_scene.dir/regular_file.cpp.o"
  "CMakeFiles/elan_scene.dir/regular_file.cpp.o.d"
  "CMakeFiles/elan_scene.dir/run_summary.cpp.o"
  "CMakeFiles/elan_scene.dir/run_summary.cpp.o.d"
  "CMakeFiles/elan_scene.dir/schema_checks.cpp.o"
  "CMakeFiles/elan_scene.dir/schema_checks.cpp.o.d"
  "CMakeFiles/elan_scene.dir/self_contained.cpp.o"
  "CMakeFiles/elan_scene.dir/self_contained.cpp.o.d"
  "CMakeFiles/elan_scene.dir/terrain.cpp.o"
  "CMakeFiles/elan_scene.dir/terrain.cpp.o.d"
  "libelan_scene.a"
  "libelan_scene.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/elan_scene.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
