# SPDX-License-Identifier: Apache-2.0
# Building plugins for MeshLab. ANIMC_MESHLAB picks the release (one binary per release and
# scalar: MeshLab 2022+ refuses a plugin built for another one):
#   2020.09 (default): Debian bookworm's MeshLab (../shared/DESIGN.md, "MeshLab facts"), below;
#   2022.02, 2025.07: an SDK built from Debian's source package (MeshLab2022Plus.cmake).
# Either way the target meshlab_common carries the headers, the library and the ABI settings,
# and ANIMC_MESHLAB_API tells meshlab_adapter/meshlab_compat.h which interface it is.

set(ANIMC_MESHLAB "2020.09" CACHE STRING "MeshLab release the plugins are built for: 2020.09, 2022.02 or 2025.07")
set_property(CACHE ANIMC_MESHLAB PROPERTY STRINGS 2020.09 2022.02 2025.07)
# Where scripts/setup.sh put the MeshLab SDKs: its ANIMC_CACHE_DIR, by default /var/cache/animcompress.
set(animc_cache_dir "$ENV{ANIMC_CACHE_DIR}")
if(animc_cache_dir STREQUAL "")
  set(animc_cache_dir /var/cache/animcompress)
endif()

if(ANIMC_MESHLAB STREQUAL "2020.09")
  include(${CMAKE_CURRENT_LIST_DIR}/MeshLab2020.cmake)
elseif(ANIMC_MESHLAB MATCHES "^202[2-9]\\.")
  include(${CMAKE_CURRENT_LIST_DIR}/MeshLab2022Plus.cmake)
else()
  message(FATAL_ERROR "ANIMC_MESHLAB=${ANIMC_MESHLAB}: not a release we build for (2020.09, 2022.02, 2025.07)")
endif()

# add_meshlab_plugin(name sources...): lib<name>.so, loadable by PluginManager.
function(add_meshlab_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE meshlab_common)
  target_link_options(${name} PRIVATE "-Wl,--no-undefined")
  set_target_properties(${name} PROPERTIES
    PREFIX "lib"
    AUTOMOC ON
    LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/plugins"
    INSTALL_RPATH "${MESHLAB_LIB_DIR}")
  install(TARGETS ${name} LIBRARY DESTINATION "${ANIMC_PLUGIN_INSTALL_DIR}")
endfunction()
