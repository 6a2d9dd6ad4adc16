// throng::io built-in social databases — the text of data/social/micro_behaviours.json and
// data/social/macro_plans.json compiled into the library (generated social_defaults.cpp), so a
// scenario with a "social" section runs without naming database files. Private to throng_io.
#pragma once
#include <string_view>

namespace throng::io {

/// data/social/micro_behaviours.json as it was when throng was built.
[[nodiscard]] std::string_view builtinMicroBehaviours();
/// data/social/macro_plans.json as it was when throng was built.
[[nodiscard]] std::string_view builtinMacroPlans();

}  // namespace throng::io
