// libFuzzer target for DXF floor plans (libs/io plan_import, dxf_reader): arbitrary bytes →
// importPlan(…, PlanFormat::Dxf); nothing may crash, throw or hang, and results are checked by
// plan_fuzz_check.hpp. Corpus: fuzz/corpus/dxf/; dictionary: fuzz/dxf.dict.
#include <cstddef>
#include <cstdint>

#include "plan_fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  throng::fuzz::checkPlan({reinterpret_cast<const char*>(data), size}, throng::io::PlanFormat::Dxf);
  return 0;
}
