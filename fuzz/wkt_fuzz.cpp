// libFuzzer target for WKT floor plans (libs/io plan_import, wkt_reader): arbitrary bytes →
// importPlan(…, PlanFormat::Wkt); nothing may crash, throw or hang, and results are checked by
// plan_fuzz_check.hpp. Corpus: fuzz/corpus/wkt/; dictionary: fuzz/wkt.dict.
#include <cstddef>
#include <cstdint>

#include "plan_fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  throng::fuzz::checkPlan({reinterpret_cast<const char*>(data), size}, throng::io::PlanFormat::Wkt);
  return 0;
}
