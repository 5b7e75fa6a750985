# SPDX-License-Identifier: MIT
# The README's hello-world program, as a newcomer would use it: the first ```cpp block after the
# `<!-- hello-world` marker and the first ```cmake block after that are written into a fresh
# project, built against the installed package and run; the program's output must be the text
# the README says it prints (the code span after "It prints"). Run by CTest with -DBUILD_DIR,
# -DSOURCE_DIR, -DWORK_DIR.
file(READ ${SOURCE_DIR}/README.md readme)

# The text of the first fenced block of language `lang` in `text`, into `out`; the rest of the
# text after the block into `rest`.
function(fenced_block text lang out rest)
  string(FIND "${text}" "\n```${lang}\n" start)
  if(start EQUAL -1)
    message(FATAL_ERROR "README.md: no ```${lang} block after the hello-world marker")
  endif()
  string(LENGTH "\n```${lang}\n" fence)
  math(EXPR start "${start} + ${fence}")
  string(SUBSTRING "${text}" ${start} -1 after)
  string(FIND "${after}" "\n```" end)
  if(end EQUAL -1)
    message(FATAL_ERROR "README.md: the ```${lang} block is not closed")
  endif()
  string(SUBSTRING "${after}" 0 ${end} block)
  string(SUBSTRING "${after}" ${end} -1 tail)
  set(${out} "${block}\n" PARENT_SCOPE)
  set(${rest} "${tail}" PARENT_SCOPE)
endfunction()

string(FIND "${readme}" "<!-- hello-world" marker)
if(marker EQUAL -1)
  message(FATAL_ERROR "README.md: no <!-- hello-world --> marker before the program")
endif()
string(SUBSTRING "${readme}" ${marker} -1 readme)
fenced_block("${readme}" cpp program readme)
if(NOT readme MATCHES "It prints `([^`]+)`")
  message(FATAL_ERROR "README.md: no \"It prints `...`\" after the hello-world program")
endif()
set(expected "${CMAKE_MATCH_1}")
fenced_block("${readme}" cmake project readme)
if(NOT project MATCHES "add_executable\\(([A-Za-z0-9_]+) ([A-Za-z0-9_.]+)\\)")
  message(FATAL_ERROR "README.md: the cmake block has no add_executable(NAME FILE.cpp)")
endif()
set(target "${CMAKE_MATCH_1}")
set(source "${CMAKE_MATCH_2}")

file(REMOVE_RECURSE ${WORK_DIR})
file(WRITE ${WORK_DIR}/hello/${source} "${program}")
file(WRITE ${WORK_DIR}/hello/CMakeLists.txt "${project}")

execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                OUTPUT_QUIET RESULT_VARIABLE r)
if(r)
  message(FATAL_ERROR "install failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK_DIR}/hello -B ${WORK_DIR}/build
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_CXX_FLAGS=-Wall\ -Wextra\ -Werror
                RESULT_VARIABLE r)
if(r)
  message(FATAL_ERROR "configuring the README's project against the installed package failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE r)
if(r)
  message(FATAL_ERROR "the README's hello-world program does not compile (${WORK_DIR}/hello)")
endif()
execute_process(COMMAND ${WORK_DIR}/build/${target} RESULT_VARIABLE r OUTPUT_VARIABLE output)
string(STRIP "${output}" output)
if(r)
  message(FATAL_ERROR "the README's hello-world program exited with ${r}; it printed: ${output}")
endif()
if(NOT output STREQUAL expected)
  message(FATAL_ERROR "the README's hello-world program printed\n  ${output}\n"
                      "but the README says it prints\n  ${expected}")
endif()
message(STATUS "the README's program printed what the README says: ${output}")
