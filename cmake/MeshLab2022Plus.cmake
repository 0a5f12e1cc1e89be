# SPDX-License-Identifier: Apache-2.0
# MeshLab 2022.02 / 2023.12 / 2025.07 for MeshLabPlugin.cmake: an SDK that
# scripts/fetch_meshlab_2022plus.sh builds from Debian's source package into a cache outside the
# tree (the source tree for the headers, distrib/ for libmeshlab-common.so and io_base).
# These releases check at load time that a plugin was built for the same version (first six
# characters of MESHLAB_VERSION) and the same scalar, so both are compile definitions here.

set(ANIMC_MESHLAB_SCALAR "float" CACHE STRING
    "MeshLab's scalar: float (Debian, Flathub, meshlab.net) or double (PyMeshLab, meshlab.net's 'd' builds)")
set_property(CACHE ANIMC_MESHLAB_SCALAR PROPERTY STRINGS float double)
set(MESHLAB_SDK_DIR "${animc_cache_dir}/meshlab-${ANIMC_MESHLAB}-${ANIMC_MESHLAB_SCALAR}" CACHE PATH
    "MeshLab ${ANIMC_MESHLAB} SDK built by scripts/fetch_meshlab_2022plus.sh")
set(MESHLAB_LIB_DIR "${MESHLAB_SDK_DIR}/distrib" CACHE PATH "directory of the SDK's libmeshlab-common.so and plugins/")

set(meshlab_src "${MESHLAB_SDK_DIR}/src/src")
if(NOT EXISTS "${MESHLAB_SDK_DIR}/.complete")
  message(FATAL_ERROR "No complete MeshLab ${ANIMC_MESHLAB} ${ANIMC_MESHLAB_SCALAR} SDK in ${MESHLAB_SDK_DIR}: run "
                      "scripts/fetch_meshlab_2022plus.sh ${ANIMC_MESHLAB} ${ANIMC_MESHLAB_SCALAR}")
endif()
# 2023.12 split the parameters into one header per class and renamed the file ones.
if(EXISTS "${meshlab_src}/common/parameters/rich_parameter/rich_file_open.h")
  set(ANIMC_MESHLAB_API 2023)
else()
  set(ANIMC_MESHLAB_API 2022)
endif()
# The version string MeshLab's own build bakes in: ML_VERSION, "d" appended for double.
file(STRINGS "${MESHLAB_SDK_DIR}/src/ML_VERSION" meshlab_version LIMIT_COUNT 1)
if(ANIMC_MESHLAB_SCALAR STREQUAL "double")
  string(APPEND meshlab_version "d")
endif()
message(STATUS "MeshLab plugins for ${meshlab_version} (${ANIMC_MESHLAB_SCALAR}), interface ${ANIMC_MESHLAB_API}")

find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml Network)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_library(MESHLAB_COMMON_LIBRARY NAMES meshlab-common PATHS "${MESHLAB_LIB_DIR}" NO_DEFAULT_PATH REQUIRED)

add_library(meshlab_common SHARED IMPORTED)
set_target_properties(meshlab_common PROPERTIES
  IMPORTED_LOCATION "${MESHLAB_COMMON_LIBRARY}"
  IMPORTED_SONAME "libmeshlab-common.so")
target_include_directories(meshlab_common SYSTEM INTERFACE "${meshlab_src}" "${meshlab_src}/vcglib")
target_compile_definitions(meshlab_common INTERFACE
  MESHLAB_VERSION=${meshlab_version} MESHLAB_SCALAR=${ANIMC_MESHLAB_SCALAR} ANIMC_MESHLAB_API=${ANIMC_MESHLAB_API})
# No GL or GLEW: the plugins draw nothing, and linking GL would put GLVND's libOpenGL into them.
target_link_libraries(meshlab_common INTERFACE
  Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml Qt5::Network Eigen3::Eigen)

# MeshLab 2022+ also finds plugins in <bin>/../lib/meshlab/plugins; users without root put them
# in its per-user MeshLabExtraPlugins/<version> folder instead (README). mlxrun, installed in
# bin/, looks there too, and needs io_base beside ours to read PLY and the like: a link to the
# SDK's.
set(ANIMC_PLUGIN_INSTALL_DIR "lib/meshlab/plugins")
install(CODE "
  set(plugins \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${ANIMC_PLUGIN_INSTALL_DIR}\")
  file(MAKE_DIRECTORY \"\${plugins}\")
  file(CREATE_LINK \"${MESHLAB_LIB_DIR}/plugins/libio_base.so\" \"\${plugins}/libio_base.so\" SYMBOLIC)")
