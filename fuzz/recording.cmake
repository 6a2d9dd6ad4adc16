# Fuzz target for the recording reader (throng::io::readRecordingSummary), included by
# fuzz/CMakeLists.txt. The reader is compiled again with the fuzz instrumentation; SQLite stays
# the system library. Corpus: fuzz/corpus/recording_reader/ (tiny valid recordings and junk).
throng_fuzz_objects(throng_fuzz_recording_objects ${PROJECT_SOURCE_DIR}/libs/io/src/recording_reader.cpp)
throng_add_fuzzer(recording_reader SOURCE recording_reader_fuzz.cpp
  LIBS throng_fuzz_recording_objects SQLite::SQLite3)
