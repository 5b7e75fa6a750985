# SPDX-License-Identifier: MIT
# Compiles each public header alone (so each is self-contained) and lists every header it pulls
# in: none may come from oneTBB or nlohmann-json, except elan/tbb_interop.hpp, which must include
# TBB (so this check is seen to detect it). Run by CTest with -DCXX, -DHEADER_DIR (the elan/
# folder), -DINCLUDE_DIRS (|-separated) and -DWORK_DIR.
cmake_minimum_required(VERSION 3.25)
string(REPLACE "|" ";" include_dirs "${INCLUDE_DIRS}")
set(flags -std=c++20 -M)  # -M: print the dependencies, system headers included
foreach(dir ${include_dirs})
  list(APPEND flags -I${dir})
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(GLOB headers RELATIVE ${HEADER_DIR} ${HEADER_DIR}/*.hpp)
set(interop tbb_interop.hpp)
if(NOT interop IN_LIST headers)
  message(FATAL_ERROR "elan/${interop} is missing: the check has no positive control")
endif()
set(failures "")
foreach(header ${headers})
  string(REPLACE "." "_" stem ${header})
  set(unit ${WORK_DIR}/${stem}.cpp)
  file(WRITE ${unit} "#include \"elan/${header}\"\n")
  execute_process(COMMAND ${CXX} ${flags} ${unit} OUTPUT_VARIABLE deps ERROR_VARIABLE errors
                  RESULT_VARIABLE r)
  if(r)
    string(APPEND failures "elan/${header} does not compile on its own:\n${errors}\n")
    continue()
  endif()
  string(REGEX MATCHALL "[^ \\\n]*/(tbb|oneapi|nlohmann)/[^ \\\n]*" found "${deps}")
  if(header STREQUAL interop)
    if(NOT found MATCHES "/tbb/")
      string(APPEND failures "elan/${header} shows no TBB header: the check cannot see them\n")
    endif()
  elseif(found)
    list(REMOVE_DUPLICATES found)
    list(LENGTH found count)
    list(SUBLIST found 0 3 first)  # in include order: the first is what a header included
    list(JOIN first "\n    " list)
    string(APPEND failures
           "elan/${header} pulls in ${count} oneTBB or nlohmann-json headers, first:\n    ${list}\n")
  endif()
endforeach()
if(failures)
  message(FATAL_ERROR "${failures}")
endif()
list(LENGTH headers n)
message(STATUS "${n} public headers checked")
