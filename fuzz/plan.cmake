# Fuzz targets for floor plan import (throng::io::importPlan: DXF and WKT), included by
# fuzz/CMakeLists.txt. They link the scenario loading objects too: every fragment is loaded as a
# scenario to check that its polygons and walls pass. Corpora: fuzz/corpus/dxf/, fuzz/corpus/wkt/
# (small valid plans of every entity or geometry kind, each error class); dictionaries:
# fuzz/dxf.dict, fuzz/wkt.dict.
throng_fuzz_objects(throng_fuzz_plan_objects
  ${PROJECT_SOURCE_DIR}/libs/io/src/plan_import.cpp
  ${PROJECT_SOURCE_DIR}/libs/io/src/dxf_reader.cpp
  ${PROJECT_SOURCE_DIR}/libs/io/src/wkt_reader.cpp)
foreach(format dxf wkt)
  throng_add_fuzzer(${format} SOURCE ${format}_fuzz.cpp LIBS throng_fuzz_plan_objects throng_fuzz_scenario_objects
    nlohmann_json::nlohmann_json Recast::Recast Recast::Detour TBB::tbb Threads::Threads)
endforeach()
