# The bundled data an installed `throng` reads at run time, under <prefix>/share/throng
# (apps/throng/data_dirs.hpp finds it from the executable's path):
#   scenarios/     the bundled scenarios, their motion clips, crowds, glTF worlds and JSON Schema
#   verification/  the verification suites' scenarios and texts (`throng verify`)
#   scripts/       scripts/verify.py and scripts/plot.py and the Python packages they import
#                  (verification, validation, plotting; plot_recording.py's WKT reader);
#                  verify.py finds verification/ as ../verification from its own directory
#   python/throng/ analysis.py and recording.py of the Python package, which plot.py loads by path
#                  as ../python/throng/ (without the package's native module)
#   web/           the browser viewer's built files (web/dist; built by scripts/deps.sh's
#                  throng_build_web, skipped when absent: `throng serve` then says it is not built)
#   examples/      the embedding examples to copy and build against the install (docs/embedding.md):
#                  embed/ (C++, find_package(throng)) and c/crowd_summary.c (the C API)
# plus the C headers of include/throng/ (the shared-memory link's throng_link.h, and any other
# public C header placed there).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/ DESTINATION ${THRONG_INSTALL_DATADIR}/scenarios)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/verification/ DESTINATION ${THRONG_INSTALL_DATADIR}/verification)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/verify.py ${PROJECT_SOURCE_DIR}/scripts/plot.py
                 ${PROJECT_SOURCE_DIR}/scripts/plot_recording.py DESTINATION ${THRONG_INSTALL_DATADIR}/scripts)
install(FILES ${PROJECT_SOURCE_DIR}/python/throng/analysis.py ${PROJECT_SOURCE_DIR}/python/throng/recording.py
        DESTINATION ${THRONG_INSTALL_DATADIR}/python/throng)
foreach(package verification validation plotting)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/scripts/${package}/ DESTINATION ${THRONG_INSTALL_DATADIR}/scripts/${package}
          FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/web/dist/ DESTINATION ${THRONG_INSTALL_DATADIR}/web OPTIONAL)
install(FILES ${PROJECT_SOURCE_DIR}/examples/embed/CMakeLists.txt ${PROJECT_SOURCE_DIR}/examples/embed/main.cpp
        DESTINATION ${THRONG_INSTALL_DATADIR}/examples/embed)
install(FILES ${PROJECT_SOURCE_DIR}/examples/c/crowd_summary.c DESTINATION ${THRONG_INSTALL_DATADIR}/examples/c)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
