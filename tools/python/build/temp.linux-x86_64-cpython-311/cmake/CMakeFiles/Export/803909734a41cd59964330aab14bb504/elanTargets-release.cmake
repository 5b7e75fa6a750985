#----------------------------------------------------------------
# Generated CMake target import file for configuration "Release".
#----------------------------------------------------------------

# Commands may need to know the format version.
set(CMAKE_IMPORT_FILE_VERSION 1)

# Import target "elan::elan" for configuration "Release"
set_property(TARGET elan::elan APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(elan::elan PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libelan.a"
  )

list(APPEND _cmake_import_check_targets elan::elan )
list(APPEND _cmake_import_check_files_for_elan::elan "${_IMPORT_PREFIX}/lib/libelan.a" )

# Import target "elan::elan_scene" for configuration "Release"
set_property(TARGET elan::elan_scene APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(elan::elan_scene PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libelan_scene.a"
  )

list(APPEND _cmake_import_check_targets elan::elan_scene )
list(APPEND _cmake_import_check_files_for_elan::elan_scene "${_IMPORT_PREFIX}/lib/libelan_scene.a" )

# Import target "elan::elan_base" for configuration "Release"
set_property(TARGET elan::elan_base APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(elan::elan_base PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libelan_base.a"
  )

list(APPEND _cmake_import_check_targets elan::elan_base )
list(APPEND _cmake_import_check_files_for_elan::elan_base "${_IMPORT_PREFIX}/lib/libelan_base.a" )

# Import target "elan::elan_broadphase" for configuration "Release"
set_property(TARGET elan::elan_broadphase APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(elan::elan_broadphase PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libelan_broadphase.a"
  )

list(APPEND _cmake_import_check_targets elan::elan_broadphase )
list(APPEND _cmake_import_check_files_for_elan::elan_broadphase "${_IMPORT_PREFIX}/lib/libelan_broadphase.a" )

# Import target "elan::elan_narrowphase" for configuration "Release"
set_property(TARGET elan::elan_narrowphase APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(elan::elan_narrowphase PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libelan_narrowphase.a"
  )

list(APPEND _cmake_import_check_targets elan::elan_narrowphase )
list(APPEND _cmake_import_check_files_for_elan::elan_narrowphase "${_IMPORT_PREFIX}/lib/libelan_narrowphase.a" )

# Import target "elan::elan_solver" for configuration "Release"
set_property(TARGET elan::elan_solver APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(elan::elan_solver PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "CXX"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libelan_solver.a"
  )

list(APPEND _cmake_import_check_targets elan::elan_solver )
list(APPEND _cmake_import_check_files_for_elan::elan_solver "${_IMPORT_PREFIX}/lib/libelan_solver.a" )

# Commands beyond this point should not need to know the version.
set(CMAKE_IMPORT_FILE_VERSION)
