# CMake toolchain for arm64 (aarch64) with Debian's cross compiler (crossbuild-essential-arm64)
# against an arm64 Debian root holding the -dev packages rovctl links (made by
# `bash deploy/setup.sh --arch arm64`). The arm64 libraries live in their own root rather than as
# multiarch packages on the host, because Debian's arm64 OpenCV cannot be co-installed with the
# host's amd64 OpenCV (apt would remove the amd64 one).
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=deploy/toolchain-arm64.cmake \
#         -DROVCTL_ARM64_SYSROOT=$PWD/build-arm64/sysroot
# Programs built here run under Debian's qemu-aarch64-static (the cross-compiling emulator), so
# ctest and gtest's test discovery run the arm64 binaries on an amd64 machine.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
# GCC's note that aarch64 passes std::pair<double, double> as GCC 10.1 changed it (-Wpsabi) is
# about linking with objects built by GCC before 10.1; everything here is built by one compiler.
string(APPEND CMAKE_CXX_FLAGS_INIT " -Wno-psabi")

# try_compile projects read this file again; they need the root too.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ROVCTL_ARM64_SYSROOT)
if(NOT ROVCTL_ARM64_SYSROOT)
  set(ROVCTL_ARM64_SYSROOT $ENV{ROVCTL_ARM64_SYSROOT})
endif()
if(NOT ROVCTL_ARM64_SYSROOT OR NOT EXISTS "${ROVCTL_ARM64_SYSROOT}/usr/lib/aarch64-linux-gnu")
  message(FATAL_ERROR "ROVCTL_ARM64_SYSROOT='${ROVCTL_ARM64_SYSROOT}' is not an arm64 Debian root "
                      "(make one with: bash deploy/setup.sh --arch arm64)")
endif()
set(CMAKE_SYSROOT ${ROVCTL_ARM64_SYSROOT})

# Headers, libraries and CMake/pkg-config packages from the arm64 root; programs from the host.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(ENV{PKG_CONFIG_SYSROOT_DIR} ${CMAKE_SYSROOT})
set(ENV{PKG_CONFIG_LIBDIR}
    "${CMAKE_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${CMAKE_SYSROOT}/usr/share/pkgconfig")

# The arm64 libraries' own dependencies (OpenCV's codecs and video back-ends) resolve in the root
# at link time, and at run time through qemu's -L.
string(APPEND CMAKE_EXE_LINKER_FLAGS_INIT
       " -Wl,-rpath-link,${CMAKE_SYSROOT}/usr/lib/aarch64-linux-gnu -Wl,-rpath-link,${CMAKE_SYSROOT}/lib/aarch64-linux-gnu")
string(APPEND CMAKE_SHARED_LINKER_FLAGS_INIT
       " -Wl,-rpath-link,${CMAKE_SYSROOT}/usr/lib/aarch64-linux-gnu -Wl,-rpath-link,${CMAKE_SYSROOT}/lib/aarch64-linux-gnu")
find_program(ROVCTL_QEMU_AARCH64 qemu-aarch64-static)
if(ROVCTL_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${ROVCTL_QEMU_AARCH64} -L ${CMAKE_SYSROOT})
endif()
