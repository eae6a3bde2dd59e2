# SPDX-License-Identifier: Apache-2.0
# The C++ settings of every shadecore CMake project (the main build and sim/light_core, the lighting-core
# build the CLI configures): C++17 without extensions (Debian's SystemC is built for C++17), Release
# unless a build type is given.
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "" FORCE)
endif()
