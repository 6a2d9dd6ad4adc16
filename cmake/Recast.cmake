# Debian's librecast-dev ships headers in /usr/include/recastnavigation and plain .so files,
# without a CMake package: wrap them as imported targets.
find_path(RECAST_INCLUDE_DIR Recast.h PATH_SUFFIXES recastnavigation REQUIRED)
foreach(lib Recast Detour DetourCrowd)
  find_library(${lib}_LIBRARY ${lib} REQUIRED)
  add_library(Recast::${lib} UNKNOWN IMPORTED)
  set_target_properties(Recast::${lib} PROPERTIES
    IMPORTED_LOCATION "${${lib}_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${RECAST_INCLUDE_DIR}")
endforeach()
set_property(TARGET Recast::DetourCrowd APPEND PROPERTY INTERFACE_LINK_LIBRARIES Recast::Detour)
