# CMake toolchain: Windows x86-64 from Debian's MinGW-w64 cross compiler (posix threads model).
# -DROPREC_WINDOWS_PREFIX=<dir> is the cross-built dependency prefix (scripts/windows.sh); the
# test executables run under wine64 (CMAKE_CROSSCOMPILING_EMULATOR).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(ROPREC_MINGW x86_64-w64-mingw32)
set(CMAKE_C_COMPILER ${ROPREC_MINGW}-gcc-posix)
set(CMAKE_CXX_COMPILER ${ROPREC_MINGW}-g++-posix)
set(CMAKE_RC_COMPILER ${ROPREC_MINGW}-windres)

set(ROPREC_WINDOWS_PREFIX "" CACHE PATH "Cross-built dependencies (scripts/windows.sh)")
# Passed on to try_compile projects.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ROPREC_WINDOWS_PREFIX)
set(CMAKE_FIND_ROOT_PATH /usr/${ROPREC_MINGW} ${ROPREC_WINDOWS_PREFIX})
set(CMAKE_PREFIX_PATH ${ROPREC_WINDOWS_PREFIX})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The GCC runtime stays dynamic (libgcc_s_seh-1.dll, libstdc++-6.dll, libwinpthread-1.dll): one
# C++ runtime shared by libroprec's C++ API and its callers. They are installed beside the exe.

find_program(ROPREC_WINE wine64 PATHS /usr/lib/wine)
if(ROPREC_WINE)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${ROPREC_WINE})
endif()
