# Windows packaging (cross-built by scripts/windows.sh): CPack makes a ZIP and an NSIS installer of
# the install tree. The install rules are the project's; this adds the DLLs roprec.exe and the
# DLLs load at run time beside them in bin/: the GCC runtime of the MinGW-w64 compiler and the
# dependencies' DLLs from the cross-built prefix (ROPREC_WINDOWS_PREFIX; the test-only ones, KDL
# and kdl_parser, are left out).
foreach(dll libstdc++-6.dll libgcc_s_seh-1.dll libwinpthread-1.dll)
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=${dll}
                  OUTPUT_VARIABLE ROPREC_RUNTIME_DLL OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT IS_ABSOLUTE "${ROPREC_RUNTIME_DLL}")
    message(FATAL_ERROR "roprec: ${dll} not found by ${CMAKE_CXX_COMPILER} -print-file-name")
  endif()
  install(FILES ${ROPREC_RUNTIME_DLL} DESTINATION ${CMAKE_INSTALL_BINDIR})
endforeach()
file(GLOB ROPREC_DEPENDENCY_DLLS ${ROPREC_WINDOWS_PREFIX}/bin/*.dll ${ROPREC_WINDOWS_PREFIX}/lib/*.dll)
list(FILTER ROPREC_DEPENDENCY_DLLS EXCLUDE REGEX "(orocos-kdl|kdl_parser|gtest|gmock)[^/]*$")
install(FILES ${ROPREC_DEPENDENCY_DLLS} DESTINATION ${CMAKE_INSTALL_BINDIR})

# The Python package: pure Python over roprec_c.dll (roprec/_cabi.py), for RoboDK's embedded
# Python 3.7/3.10 or any CPython >= 3.7: add <install folder>/python to its path.
install(FILES ${CMAKE_SOURCE_DIR}/plugin/python/roprec/__init__.py ${CMAKE_SOURCE_DIR}/plugin/python/roprec/_cabi.py
        DESTINATION python/roprec)
# The RoboDK app (README "RoboDK"): copied from here into C:/RoboDK/Apps/roprec.
install(FILES ${CMAKE_SOURCE_DIR}/plugin/robodk/roprec_compensate_program.py DESTINATION robodk)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/samples/cells DESTINATION samples)

set(CPACK_GENERATOR ZIP NSIS)
set(CPACK_PACKAGING_INSTALL_PREFIX "")
set(CPACK_SYSTEM_NAME win64)
set(CPACK_PACKAGE_INSTALL_DIRECTORY roprec)
set(CPACK_NSIS_PACKAGE_NAME "roprec ${PROJECT_VERSION}")
set(CPACK_NSIS_DISPLAY_NAME "roprec ${PROJECT_VERSION}")
set(CPACK_NSIS_MODIFY_PATH ON)  # offers to put roprec\bin on PATH
set(CPACK_NSIS_ENABLE_UNINSTALL_BEFORE_INSTALL ON)
