# Installing throng (docs/install.md): where things go (GNUInstallDirs), the RPATH policy, and
# throng_install_library(), which makes a library part of the installed set: versioned shared
# object (SONAME), its public headers, and an exported target throng::<name> in the CMake package
# (throngConfig.cmake, cmake/throngConfig.cmake.in). The package files themselves are written by
# throng_install_package() (cmake/ThrongPackage.cmake) once every library is known.
include(GNUInstallDirs)

# The bundled data (scenarios, verification suites and scripts, the viewer) under
# <prefix>/share/throng; the program finds it relative to its own path (apps/throng/data_dirs.cpp).
set(THRONG_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/throng)
set(THRONG_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/throng)
# 0.x: every minor release may break the ABI, so the SONAME carries major.minor.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(THRONG_SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
else()
  set(THRONG_SOVERSION ${PROJECT_VERSION_MAJOR})
endif()

# RPATH: the build tree's (tests run in place); installed, none when the library directory is one
# the linker searches anyway (Debian's /usr/lib/<triplet>), else $ORIGIN/../<libdir> so a custom
# prefix works without LD_LIBRARY_PATH (lintian accepts $ORIGIN paths in a .deb).
list(FIND CMAKE_PLATFORM_IMPLICIT_LINK_DIRECTORIES "${CMAKE_INSTALL_FULL_LIBDIR}" _throng_system_libdir)
if(_throng_system_libdir EQUAL -1)
  list(FIND CMAKE_CXX_IMPLICIT_LINK_DIRECTORIES "${CMAKE_INSTALL_FULL_LIBDIR}" _throng_system_libdir)
endif()
if(_throng_system_libdir EQUAL -1)
  set(CMAKE_INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
endif()
set(CMAKE_INSTALL_RPATH_USE_LINK_PATH OFF)

# throng_install_library(TARGET...) — installs each library (shared objects with VERSION and
# SOVERSION, archives when BUILD_SHARED_LIBS is off), exports it as throng::<name> (the target
# name without its throng_ prefix) and installs its public headers (libs/<name>/include/). Include
# directories inside the source or build tree are wrapped in $<BUILD_INTERFACE:>: installed, the
# headers are found in <prefix>/include.
function(throng_install_library)
  foreach(target IN LISTS ARGN)
    get_target_property(type ${target} TYPE)
    string(REGEX REPLACE "^throng_" "" name ${target})
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
    if(NOT type STREQUAL "INTERFACE_LIBRARY")
      # DEFINE_SYMBOL "": no <target>_EXPORTS macro (nothing uses it), so a shared build compiles
      # the very same command lines as a static one (and shares their ccache entries).
      set_target_properties(${target} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${THRONG_SOVERSION}
                                                 DEFINE_SYMBOL "")
    endif()
    get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
    set(wrapped)
    foreach(dir IN LISTS dirs)
      string(FIND "${dir}/" "${PROJECT_SOURCE_DIR}/" in_source)
      string(FIND "${dir}/" "${PROJECT_BINARY_DIR}/" in_build)
      if(in_source EQUAL 0 OR in_build EQUAL 0)
        list(APPEND wrapped "$<BUILD_INTERFACE:${dir}>")
      else()
        list(APPEND wrapped "${dir}")
      endif()
    endforeach()
    set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${wrapped}")
    install(TARGETS ${target} EXPORT throngTargets
            RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
            LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
            INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    get_target_property(source_dir ${target} SOURCE_DIR)
    if(IS_DIRECTORY ${source_dir}/include)
      install(DIRECTORY ${source_dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
    set_property(GLOBAL APPEND PROPERTY THRONG_INSTALLED_LIBRARIES ${target})
  endforeach()
endfunction()
