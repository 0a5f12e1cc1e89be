# SPDX-License-Identifier: Apache-2.0
# The installed package: find_package(animcompress 1.0) gives animcompress::animc (shared) and
# animcompress::animc_static; pkg-config gives `animc`.
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)
set(ANIMC_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/animcompress)
install(EXPORT animcompressTargets NAMESPACE animcompress:: DESTINATION ${ANIMC_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/animcompressConfig.cmake.in
  ${PROJECT_BINARY_DIR}/animcompressConfig.cmake INSTALL_DESTINATION ${ANIMC_CMAKE_DIR})
# 1.x reads what 1.0 wrote and keeps the API: any 1.y >= the asked version will do.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/animcompressConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/animcompressConfig.cmake ${PROJECT_BINARY_DIR}/animcompressConfigVersion.cmake
        DESTINATION ${ANIMC_CMAKE_DIR})

# The .pc file locates the prefix from its own folder, so `cmake --install --prefix P` to
# any P works without configuring again.
file(RELATIVE_PATH ANIMC_PC_TO_PREFIX /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
string(REGEX REPLACE "/$" "" ANIMC_PC_TO_PREFIX "${ANIMC_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/animc.pc.in ${PROJECT_BINARY_DIR}/animc.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/animc.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
