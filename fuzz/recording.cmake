# Fuzz target for the recording readers (readRecordingSummary, the Common Ground readers and
# metrics of recording_social.hpp, the replay frames of frame_reader.hpp), included by
# fuzz/CMakeLists.txt. The reader is compiled again with the fuzz instrumentation; SQLite stays
# the system library. Corpus: fuzz/corpus/recording_reader/ (tiny valid recordings and junk).
throng_fuzz_objects(throng_fuzz_recording_objects ${PROJECT_SOURCE_DIR}/libs/recording/src/recording_reader.cpp
  ${PROJECT_SOURCE_DIR}/libs/recording/src/recording_social.cpp ${PROJECT_SOURCE_DIR}/libs/recording/src/metrics_queries.cpp
  ${PROJECT_SOURCE_DIR}/libs/recording/src/metrics_analysis.cpp
  ${PROJECT_SOURCE_DIR}/libs/recording/src/frame_reader.cpp)
# The Common Ground readers use throng::common_ground's name tables (header-only use).
target_include_directories(throng_fuzz_recording_objects PRIVATE ${PROJECT_SOURCE_DIR}/libs/common_ground/include)
throng_add_fuzzer(recording_reader SOURCE recording_reader_fuzz.cpp
  LIBS throng_fuzz_recording_objects SQLite::SQLite3)
