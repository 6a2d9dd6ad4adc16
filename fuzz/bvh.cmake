# Fuzz target for the BVH motion clip parser (throng::motion::parseBvh), included by
# fuzz/CMakeLists.txt. Corpus: fuzz/corpus/bvh/ (small valid clips, each error class, junk);
# dictionary: fuzz/bvh.dict (the format's keywords).
throng_fuzz_objects(throng_fuzz_bvh_objects
  ${PROJECT_SOURCE_DIR}/libs/core/src/diagnostic.cpp
  ${PROJECT_SOURCE_DIR}/libs/motion/src/bvh_parser.cpp)
throng_add_fuzzer(bvh SOURCE bvh_fuzz.cpp LIBS throng_fuzz_bvh_objects)
