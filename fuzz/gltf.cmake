# Fuzz target for glTF world files (throng::io::parseWorld: tinygltf, the naming rules, the
# footprint unions, then the scenario parser), included by fuzz/CMakeLists.txt. It links the
# scenario loading objects (the world-file sources are part of them). Corpus: fuzz/corpus/gltf/
# (the gallery, a .glb, each error class, junk).
throng_add_fuzzer(gltf SOURCE gltf_fuzz.cpp LIBS throng_fuzz_scenario_objects
  nlohmann_json::nlohmann_json Recast::Recast Recast::Detour TBB::tbb Threads::Threads)
