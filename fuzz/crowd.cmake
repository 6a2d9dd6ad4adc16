# Fuzz target for crowd files (throng::io::parseCrowd, inserted into a running world), included by
# fuzz/CMakeLists.txt. It links the scenario loading objects (the crowd parser is part of them).
# Corpus: fuzz/corpus/crowd/ (a good crowd, each error class, junk).
throng_add_fuzzer(crowd SOURCE crowd_fuzz.cpp LIBS throng_fuzz_scenario_objects
  nlohmann_json::nlohmann_json Recast::Recast Recast::Detour TBB::tbb Threads::Threads)
