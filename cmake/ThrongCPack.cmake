# A Debian package of the installed tree (docs/install.md): `cpack -G DEB` in the build directory
# writes throng_<version>_amd64.deb, installing to /usr (program, shared libraries, headers, CMake
# package and pkg-config file, bundled data, man pages, completions). Its dependencies on Debian's
# libraries come from dpkg-shlibdeps (dpkg-dev); /usr/share/doc/throng holds the copyright file
# (packaging/debian/copyright) and a changelog. tests/install/deb_package_test.sh builds and checks it.
set(THRONG_DEB_MAINTAINER "throng maintainers <throng-maintainers@users.noreply.github.com>"
    CACHE STRING "The Debian package's Maintainer field")

# /usr/share/doc/throng: copyright and changelog.gz (gzip -9n: no name, no time stamp).
set(_doc ${PROJECT_BINARY_DIR}/debian-doc)
if(DEFINED ENV{SOURCE_DATE_EPOCH})
  set(_epoch $ENV{SOURCE_DATE_EPOCH})
else()
  string(TIMESTAMP _epoch "%s" UTC)
endif()
execute_process(COMMAND date -u -R -d @${_epoch} OUTPUT_VARIABLE _date OUTPUT_STRIP_TRAILING_WHITESPACE)
file(WRITE ${_doc}/changelog
     "throng (${PROJECT_VERSION}) unstable; urgency=medium\n\n"
     "  * Built with CPack from the throng sources (docs/install.md).\n\n"
     " -- ${THRONG_DEB_MAINTAINER}  ${_date}\n")
execute_process(COMMAND gzip -9nf ${_doc}/changelog)
install(FILES ${_doc}/changelog.gz ${PROJECT_SOURCE_DIR}/packaging/debian/copyright
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/throng)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME throng)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "the throng authors")
set(CPACK_PACKAGE_CONTACT "${THRONG_DEB_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${THRONG_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "crowd engine for shared virtual worlds")
# The synopsis is CPACK_PACKAGE_DESCRIPTION_SUMMARY; this is the extended description.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "throng simulates crowds described by a scenario file (groups, goals, Common
Ground coordination, several walking models) and records their trajectories
to SQLite; it serves a running crowd to browsers and native clients, drives a
host application over shared memory, and embeds as a C++ library.
.
This package holds the throng program with its man pages and shell
completions, the shared libraries with their headers, CMake package and
pkg-config file, the bundled scenarios, the verification suites and the
browser viewer.")
# Library dependencies from dpkg-shlibdeps; the package's own libraries get a shlibs file.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS_POLICY "=")
# Shared libraries in /usr/lib: dpkg runs ldconfig once after the transaction (a trigger).
file(WRITE ${PROJECT_BINARY_DIR}/debian-control/triggers "activate-noawait ldconfig\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_BINARY_DIR}/debian-control/triggers)
# `throng verify` runs Python with numpy and matplotlib; building against the package needs the
# development files of what throngConfig.cmake finds (oneTBB, nlohmann_json).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3, python3-numpy, python3-pandas, python3-matplotlib")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libtbb-dev, nlohmann-json3-dev, cmake, pkg-config")
include(CPack)
