# SPDX-License-Identifier: Apache-2.0
# Install step of a staged prefix: copies of Debian's meshlab and meshlabserver in bin/ (a copy,
# not a symlink: MeshLab resolves /proc/self/exe to find its plugin folder) and symlinks to the
# packaged libmeshlab-common.so and stock plugins, so the staged MeshLab has every stock filter
# and reader plus ours, and nothing is written to /usr.
set(prefix "$ENV{DESTDIR}${CMAKE_INSTALL_PREFIX}")
set(libdir "${prefix}/lib/x86_64-linux-gnu/meshlab")
file(MAKE_DIRECTORY "${prefix}/bin" "${libdir}/plugins")
foreach(program meshlab meshlabserver)
  if(EXISTS "/usr/bin/${program}")
    file(COPY "/usr/bin/${program}" DESTINATION "${prefix}/bin")
  endif()
endforeach()
file(CREATE_LINK "${MESHLAB_LIB_DIR}/libmeshlab-common.so" "${libdir}/libmeshlab-common.so" SYMBOLIC)
file(GLOB stock_plugins "${MESHLAB_LIB_DIR}/plugins/*.so")
# Our own plugins may be in the system folder too (ANIMC_INSTALL_TO_SYSTEM_MESHLAB): never link
# those, or installing ours would write through the link into /usr.
list(FILTER stock_plugins EXCLUDE REGEX "lib(filter_animcompress|io_animstream)\\.so$")
foreach(plugin ${stock_plugins})
  get_filename_component(plugin_name "${plugin}" NAME)
  file(CREATE_LINK "${plugin}" "${libdir}/plugins/${plugin_name}" SYMBOLIC)
endforeach()
message(STATUS "Staged MeshLab: ${prefix}/bin/meshlab and ${prefix}/bin/meshlabserver")
