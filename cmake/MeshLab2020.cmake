# SPDX-License-Identifier: Apache-2.0
# MeshLab 2020.09, Debian bookworm's (../shared/DESIGN.md, "MeshLab facts"), for
# MeshLabPlugin.cmake. Headers: src/common and vcglib from Debian's source package, fetched by
# scripts/setup.sh into a cache outside the tree. Library: the packaged libmeshlab-common.so.
# The compile settings below are ABI: a plugin built otherwise loads, then crashes meshlabserver.

set(MESHLAB_SDK_DIR "${animc_cache_dir}/meshlab-2020.09" CACHE PATH
    "MeshLab 2020.09 source tree holding src/common and vcglib (scripts/fetch_meshlab_sdk.sh)")
set(MESHLAB_LIB_DIR "/usr/lib/x86_64-linux-gnu/meshlab" CACHE PATH
    "directory of Debian's libmeshlab-common.so and plugins/")
option(ANIMC_INSTALL_TO_SYSTEM_MESHLAB
       "cmake --install writes the plugins into MESHLAB_LIB_DIR/plugins instead of staging a private MeshLab under the prefix" OFF)

if(NOT EXISTS "${MESHLAB_SDK_DIR}/src/common/interfaces.h")
  message(FATAL_ERROR "MeshLab headers not found in ${MESHLAB_SDK_DIR}: run scripts/setup.sh "
                      "(or configure with -DANIMC_BUILD_PLUGINS=OFF to build without the plugins)")
endif()

find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml)
find_package(OpenGL REQUIRED)
find_package(GLEW REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_library(MESHLAB_COMMON_LIBRARY NAMES meshlab-common PATHS "${MESHLAB_LIB_DIR}"
             NO_DEFAULT_PATH REQUIRED)

add_library(meshlab_common SHARED IMPORTED)
set_target_properties(meshlab_common PROPERTIES
  IMPORTED_LOCATION "${MESHLAB_COMMON_LIBRARY}"
  IMPORTED_SONAME "libmeshlab-common.so")
# SYSTEM: MeshLab's and vcglib's headers are not ours to keep warning-free.
target_include_directories(meshlab_common SYSTEM INTERFACE
  "${MESHLAB_SDK_DIR}/src" "${MESHLAB_SDK_DIR}/vcglib")
# MESHLAB_SCALAR sets the layout of CMeshO: Debian built with float. System GLEW, hence no
# GLEW_STATIC.
target_compile_definitions(meshlab_common INTERFACE MESHLAB_SCALAR=float ANIMC_MESHLAB_API=2020)
target_link_libraries(meshlab_common INTERFACE
  Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml GLEW::GLEW OpenGL::GL Eigen3::Eigen)

if(ANIMC_INSTALL_TO_SYSTEM_MESHLAB)
  set(ANIMC_PLUGIN_INSTALL_DIR "${MESHLAB_LIB_DIR}/plugins")
else()
  # MeshLab 2020.09 looks for plugins only beside its own binary (bin/../lib/<triplet>/meshlab/
  # plugins); a staged prefix therefore gets copies of the binaries (see StageMeshLab.cmake).
  set(ANIMC_PLUGIN_INSTALL_DIR "lib/x86_64-linux-gnu/meshlab/plugins")
  install(CODE "set(MESHLAB_LIB_DIR \"${MESHLAB_LIB_DIR}\")")
  install(SCRIPT "${CMAKE_CURRENT_LIST_DIR}/StageMeshLab.cmake")
endif()

