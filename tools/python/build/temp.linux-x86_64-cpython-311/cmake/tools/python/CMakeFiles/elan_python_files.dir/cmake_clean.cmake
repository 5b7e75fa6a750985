file(REMOVE_RECURSE
  "CMakeFiles/elan_python_files"
  "elan/__init__.py"
  "elan/_columns.py"
  "elan/_elan.pyi"
  "elan/py.typed"
)

# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/elan_python_files.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
