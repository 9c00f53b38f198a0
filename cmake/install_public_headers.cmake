# Installs roprec's public C++ headers (run by `cmake --install`, see CMakeLists.txt): the job API
# (plugin/api/*.hpp), the report writers (plugin/report/*.hpp) and every project header they
# include, directly or not, and nothing else, as PREFIX/include/roprec/<path>. In the installed copies the project's own includes
# (#include "compensator/...", "postproc/...", "plugin/...") become #include "roprec/...", so that
# a consumer needs one include path, PREFIX/include, and writes #include <roprec/plugin/api/job.hpp>.
#
# Input variables: ROPREC_SOURCE_DIR (the source tree), ROPREC_HEADER_STAGE (a folder of the build
# tree for the rewritten copies), ROPREC_INSTALL_INCLUDEDIR (relative to the install prefix).
cmake_policy(PUSH)
cmake_policy(VERSION 3.20)
file(GLOB entries RELATIVE "${ROPREC_SOURCE_DIR}" "${ROPREC_SOURCE_DIR}/plugin/api/*.hpp"
     "${ROPREC_SOURCE_DIR}/plugin/report/*.hpp")
set(queue ${entries})
set(public)
while(queue)
  list(POP_FRONT queue header)
  if(header IN_LIST public)
    continue()
  endif()
  list(APPEND public "${header}")
  file(STRINGS "${ROPREC_SOURCE_DIR}/${header}" includes REGEX "^#include \"(compensator|postproc|plugin)/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${line}")
    if(NOT EXISTS "${ROPREC_SOURCE_DIR}/${included}")
      message(FATAL_ERROR "roprec: ${header} includes ${included}, which does not exist")
    endif()
    list(APPEND queue "${included}")
  endforeach()
endwhile()
list(SORT public)
# One stage per destination: installs into different prefixes may run at the same time.
string(MD5 destination "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}")

foreach(header IN LISTS public)
  file(READ "${ROPREC_SOURCE_DIR}/${header}" text)
  string(REGEX REPLACE "#include \"((compensator|postproc|plugin)/)" "#include \"roprec/\\1" text "${text}")
  set(staged "${ROPREC_HEADER_STAGE}/${destination}/roprec/${header}")
  file(WRITE "${staged}" "${text}")
  get_filename_component(dir "${header}" DIRECTORY)
  file(INSTALL DESTINATION "${CMAKE_INSTALL_PREFIX}/${ROPREC_INSTALL_INCLUDEDIR}/roprec/${dir}" TYPE FILE
       FILES "${staged}")
endforeach()
cmake_policy(POP)
