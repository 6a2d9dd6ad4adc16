# throng's CMake package and pkg-config file (docs/install.md), written once every library has
# been given to throng_install_library() (cmake/ThrongInstall.cmake):
#   <libdir>/cmake/throng/throngConfig.cmake, throngConfigVersion.cmake, throngTargets*.cmake
#     (throng::<lib>), throngRecast.cmake (Recast's imported targets, for static libraries)
#   <libdir>/pkgconfig/throng.pc (relocatable: its prefix is found from the file's own place)
include(CMakePackageConfigHelpers)

function(throng_install_package)
  install(EXPORT throngTargets NAMESPACE throng:: DESTINATION ${THRONG_INSTALL_CMAKEDIR})
  set(THRONG_PACKAGE_HAS_DIST 0)
  if(TARGET throng_dist)
    set(THRONG_PACKAGE_HAS_DIST 1)
  endif()
  if(NOT BUILD_SHARED_LIBS)
    set(BUILD_SHARED_LIBS 0)
  endif()
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/throngConfig.cmake.in
    ${PROJECT_BINARY_DIR}/throngConfig.cmake INSTALL_DESTINATION ${THRONG_INSTALL_CMAKEDIR})
  # 0.x: only the same minor version is compatible (the SONAME carries major.minor).
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/throngConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/throngConfig.cmake ${PROJECT_BINARY_DIR}/throngConfigVersion.cmake
          DESTINATION ${THRONG_INSTALL_CMAKEDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/Recast.cmake DESTINATION ${THRONG_INSTALL_CMAKEDIR}
          RENAME throngRecast.cmake)

  # pkg-config: the simulation and scenario-loading libraries, dependents first.
  set(THRONG_PC_LIBS "-lthrong_io -lthrong_recording -lthrong_sim -lthrong_motion -lthrong_common_ground -lthrong_crowd -lthrong_nav -lthrong_core")
  # Static libraries: what they link privately goes to Libs too (there is no shared object to carry it).
  if(NOT BUILD_SHARED_LIBS)
    string(APPEND THRONG_PC_LIBS " -lsqlite3 -lDetour -lRecast -lpthread")
  endif()
  file(RELATIVE_PATH THRONG_PC_PREFIX_FROM_PCDIR ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
  string(REGEX REPLACE "/$" "" THRONG_PC_PREFIX_FROM_PCDIR "${THRONG_PC_PREFIX_FROM_PCDIR}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/throng.pc.in ${PROJECT_BINARY_DIR}/throng.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/throng.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
