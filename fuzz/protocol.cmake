# Fuzz target for the protocol decoders (throng::protocol::decodeAny, CrowdDecoder, worldJson),
# included by fuzz/CMakeLists.txt. Corpus: fuzz/corpus/protocol/ (the golden messages of
# tests/protocol/golden/ and a few broken ones).
find_package(PkgConfig REQUIRED)
pkg_check_modules(THRONG_FUZZ_ZSTD REQUIRED IMPORTED_TARGET libzstd)
file(GLOB THRONG_FUZZ_PROTOCOL_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/libs/protocol/src/*.cpp)
throng_fuzz_objects(throng_fuzz_protocol_objects
  ${PROJECT_SOURCE_DIR}/libs/core/src/diagnostic.cpp
  ${THRONG_FUZZ_PROTOCOL_SOURCES})
target_include_directories(throng_fuzz_protocol_objects PRIVATE ${PROJECT_SOURCE_DIR}/libs/protocol/include
                                                                ${PROJECT_SOURCE_DIR}/libs/protocol/src)
throng_add_fuzzer(protocol SOURCE protocol_fuzz.cpp LIBS throng_fuzz_protocol_objects PkgConfig::THRONG_FUZZ_ZSTD)
target_include_directories(fuzz_protocol PRIVATE ${PROJECT_SOURCE_DIR}/libs/protocol/include)
