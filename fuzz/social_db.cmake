# Fuzz target for the social databases loader (throng::io::parseMicroBehaviours / parseMacroPlans),
# included by fuzz/CMakeLists.txt. Corpus: fuzz/corpus/social_db/ (the bundled databases, each
# error class, junk).
throng_fuzz_objects(throng_fuzz_social_db_objects
  ${PROJECT_SOURCE_DIR}/libs/core/src/diagnostic.cpp
  ${PROJECT_SOURCE_DIR}/libs/io/src/json_document.cpp
  ${PROJECT_SOURCE_DIR}/libs/io/src/social_db_loader.cpp)
target_include_directories(throng_fuzz_social_db_objects PRIVATE ${PROJECT_SOURCE_DIR}/libs/common_ground/include)
throng_add_fuzzer(social_db SOURCE social_db_fuzz.cpp LIBS throng_fuzz_social_db_objects nlohmann_json::nlohmann_json)
target_include_directories(fuzz_social_db PRIVATE ${PROJECT_SOURCE_DIR}/libs/common_ground/include)
