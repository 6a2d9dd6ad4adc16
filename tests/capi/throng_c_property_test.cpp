// The C API under random call sequences (libs/capi/src/throng_c.cpp): every call gets a live
// handle, NULL or a pointer the library never made, random arguments (NaN, infinities, huge and
// negative values, zero and huge capacities, garbage JSON) in any order (record after stepping,
// step after finishing, close without recording, remove twice), and must return exactly the
// status the header documents for that situation, never crash, and leave the world usable.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "capi_fixtures.hpp"
#include "temp_dir.hpp"
#include "throng/throng.h"

namespace throng::capi_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Who { Live, Null, Stranger };

rc::Gen<Who> genWho() { return rc::gen::weightedElement<Who>({{6, Who::Live}, {1, Who::Null}, {1, Who::Stranger}}); }
rc::Gen<double> genCoordinate() {
  return rc::gen::weightedElement<double>({{6, 3.0}, {2, 1e6}, {1, -1e30}, {1, 1e300}, {1, kNaN}, {1, kInf}, {1, -kInf}});
}

/// One random world and the model of what each call must answer.
class Driver {
 public:
  explicit Driver(throng_scenario* scenario) : scenario_(scenario) {
    RC_ASSERT(throng_world_create(scenario, nullptr, &world_) == THRONG_OK);
  }
  ~Driver() {
    EXPECT_EQ(throng_world_free(world_), THRONG_OK);
    EXPECT_EQ(throng_world_free(nullptr), THRONG_OK);
    EXPECT_EQ(throng_world_free(nullptr), THRONG_OK);
  }
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;

  /// The world the call gets, and what a non-live one must answer.
  throng_world* pick(Who who, throng_status& early) {
    early = who == Who::Null ? THRONG_ERROR_NULL_ARGUMENT : who == Who::Stranger ? THRONG_ERROR_BAD_HANDLE : THRONG_OK;
    return who == Who::Live ? world_ : who == Who::Null ? nullptr : reinterpret_cast<throng_world*>(&stranger_);
  }

  void oneCall() {
    throng_status early = THRONG_OK;
    throng_world* w = pick(*genWho(), early);
    const throng_world_stats before = liveStats();
    const throng_status got = call(*rc::gen::inRange(0, 12), w, before, early);
    RC_ASSERT(throng_status_name(got) != std::string("unknown"));
    RC_ASSERT(got == THRONG_OK || std::string(throng_last_error()) != "");
  }

  void check(throng_status got, throng_status early, throng_status want) {
    const throng_status expected = early != THRONG_OK ? early : want;
    RC_ASSERT(throng_status_name(got) == std::string(throng_status_name(expected)));
  }

 private:
  throng_world_stats liveStats() {
    throng_world_stats s{};
    RC_ASSERT(throng_world_stats_get(world_, &s) == THRONG_OK);
    return s;
  }

  throng_status call(int op, throng_world* w, const throng_world_stats& s, throng_status early) {
    switch (op) {
      case 0: return step(w, s, early);
      case 1: return run(w, early);
      case 2: return agents(w, s, early);
      case 3: return events(w, early);
      case 4: return guide(w, s, early);
      case 5: return release(w, s, early);
      case 6: return insert(w, early);
      case 7: return remove(w, early);
      case 8: return record(w, s, early);
      case 9: return recordClose(w, s, early);
      case 10: return queries(w, early);
      case 11: return group(w, s, early);
      default: return createOther();
    }
  }

  throng_status step(throng_world* w, const throng_world_stats& s, throng_status early) {
    const auto n = *rc::gen::inRange<uint64_t>(0, 6);
    uint64_t stepped = 0;
    const throng_status got = throng_world_step(w, n, &stepped);
    check(got, early, s.finished != 0 && n > 0 ? THRONG_ERROR_WRONG_STATE : THRONG_OK);
    if (got == THRONG_OK) RC_ASSERT(liveStats().tick == s.tick + stepped);
    return got;
  }

  throng_status run(throng_world* w, throng_status early) {
    const double until = *rc::gen::element(kNaN, kInf, -kInf, -1.0, 0.0, 0.4, 2.0, 100.0);
    const throng_status got = throng_world_run(w, until);
    check(got, early, std::isfinite(until) && until >= 0 ? THRONG_OK : THRONG_ERROR_INVALID_ARGUMENT);
    if (got == THRONG_OK) {  // ended on the time asked for, or with everyone gone (a guided group never leaves)
      const throng_world_stats after = liveStats();
      RC_ASSERT(after.finished == 1 || after.time >= until - 1e-6);
    }
    return got;
  }

  throng_status agents(throng_world* w, const throng_world_stats& s, throng_status early) {
    const std::size_t capacity = *rc::gen::element<std::size_t>(0, 1, s.active, s.active + 3, 1u << 20);
    const bool withColumns = capacity <= s.active + 3 && *rc::gen::arbitrary<bool>();
    std::vector<float> positions(withColumns ? 2 * capacity : 0);
    std::vector<uint32_t> ids(withColumns ? capacity : 0), groups(withColumns ? capacity : 0);
    throng_agent_arrays arrays{};
    arrays.capacity = capacity;
    if (withColumns) arrays.positions = positions.data(), arrays.ids = ids.data(), arrays.groups = groups.data();
    const bool nullArrays = *rc::gen::weightedElement<bool>({{5, false}, {1, true}});
    std::size_t count = 0;
    const throng_status got = throng_world_agents(w, nullArrays ? nullptr : &arrays, &count);
    check(got, early, nullArrays ? THRONG_ERROR_NULL_ARGUMENT : s.active > capacity ? THRONG_ERROR_BUFFER_TOO_SMALL : THRONG_OK);
    if (early == THRONG_OK && !nullArrays) RC_ASSERT(count == s.active);
    for (std::size_t i = 0; got == THRONG_OK && withColumns && i < count; ++i) RC_ASSERT(groups[i] < s.groups);
    return got;
  }

  throng_status events(throng_world* w, throng_status early) {
    const std::size_t capacity = *rc::gen::element<std::size_t>(0, 1, 4, 100);
    const bool nullEvents = *rc::gen::weightedElement<bool>({{5, false}, {1, true}});
    std::vector<throng_event> buffer(capacity);
    std::size_t count = 99;
    const throng_status got = throng_world_events(w, nullEvents ? nullptr : buffer.data(), capacity, &count);
    check(got, early, nullEvents && capacity > 0 ? THRONG_ERROR_NULL_ARGUMENT : THRONG_OK);
    if (got == THRONG_OK) RC_ASSERT(count <= capacity);
    for (std::size_t i = 0; got == THRONG_OK && i < count; ++i) RC_ASSERT(std::string(throng_event_kind_name(buffer[i].kind)) != "unknown");
    return got;
  }

  throng_status guide(throng_world* w, const throng_world_stats& s, throng_status early) {
    const auto g = *rc::gen::inRange<uint32_t>(0, 8);
    const double x = *genCoordinate(), y = *genCoordinate();
    const bool fits = std::isfinite(x) && std::isfinite(y) && std::fabs(x) < 3e38 && std::fabs(y) < 3e38;
    const throng_status got = throng_world_guide(w, g, x, y);
    check(got, early, !fits ? THRONG_ERROR_INVALID_ARGUMENT : g < s.groups ? THRONG_OK : THRONG_ERROR_NOT_FOUND);
    return got;
  }

  throng_status release(throng_world* w, const throng_world_stats& s, throng_status early) {
    const auto g = *rc::gen::inRange<uint32_t>(0, 8);
    const throng_status got = throng_world_release(w, g);
    check(got, early, g < s.groups ? THRONG_OK : THRONG_ERROR_NOT_FOUND);
    return got;
  }

  throng_status insert(throng_world* w, throng_status early) {
    const int kind = *rc::gen::inRange(0, 3);  // 0 valid, 1 garbage, 2 NULL
    const std::string id = "c" + std::to_string(nextCrowd_);
    const std::string text = kind == 0 ? R"({"format": "throng-crowd/1", "id": ")" + id + R"(", "populations": [{"id": "p)" +
                                             id + R"(", "groups": 2, "size": 1, "spawn": {"polygon": [[1, 1], [4, 1], [4, 3], [1, 3]]}, "goals": ["exit"], "radius": 0.2}]})"
                                       : *rc::gen::element<std::string>("", "{", "[]", "{\"format\": 3}", "\xff\xfe");
    const throng_status got = throng_world_insert_crowd(w, kind == 2 ? nullptr : text.c_str(), nullptr, nullptr, nullptr);
    check(got, early, kind == 2 ? THRONG_ERROR_NULL_ARGUMENT : kind == 1 ? THRONG_ERROR_INVALID_SCENARIO : THRONG_OK);
    if (got == THRONG_OK) inserted_.insert(id), ++nextCrowd_;
    return got;
  }

  throng_status remove(throng_world* w, throng_status early) {
    const int kind = *rc::gen::inRange(0, 3);  // 0 one inserted (maybe removed already), 1 unknown, 2 NULL
    const std::string id = kind == 0 && nextCrowd_ > 0 ? "c" + std::to_string(*rc::gen::inRange(0, nextCrowd_)) : "nobody";
    const throng_status got = throng_world_remove_crowd(w, kind == 2 ? nullptr : id.c_str());
    const bool present = kind != 2 && inserted_.count(id) == 1;
    check(got, early, kind == 2 ? THRONG_ERROR_NULL_ARGUMENT : present ? THRONG_OK : THRONG_ERROR_NOT_FOUND);
    if (got == THRONG_OK) inserted_.erase(id);
    return got;
  }

  throng_status record(throng_world* w, const throng_world_stats& s, throng_status early) {
    const double fps = *rc::gen::element(10.0, 10.0, 0.0, -5.0, kNaN, kInf);
    const bool nullPath = *rc::gen::weightedElement<bool>({{5, false}, {1, true}});
    const std::string path = dir_.file("r" + std::to_string(recordings_) + ".sqlite");
    const throng_status got = throng_world_record(w, nullPath ? nullptr : path.c_str(), fps, 1);
    const throng_status want = nullPath                              ? THRONG_ERROR_NULL_ARGUMENT
                               : !(std::isfinite(fps) && fps > 0)    ? THRONG_ERROR_INVALID_ARGUMENT
                               : s.recording != 0 || s.tick != 0     ? THRONG_ERROR_WRONG_STATE
                                                                     : THRONG_OK;
    check(got, early, want);
    if (got == THRONG_OK) ++recordings_;
    return got;
  }

  throng_status recordClose(throng_world* w, const throng_world_stats& s, throng_status early) {
    uint64_t frames = 0;
    const throng_status got = throng_world_record_close(w, &frames);
    check(got, early, s.recording != 0 ? THRONG_OK : THRONG_ERROR_WRONG_STATE);
    if (got == THRONG_OK) RC_ASSERT(frames >= 1);
    return got;
  }

  throng_status queries(throng_world* w, throng_status early) {
    const bool nullOut = *rc::gen::arbitrary<bool>();
    throng_world_stats st{};
    uint64_t hash = 0;
    std::size_t pending = 0;
    switch (*rc::gen::inRange(0, 3)) {
      case 0: {
        const throng_status got = throng_world_stats_get(w, nullOut ? nullptr : &st);
        check(got, early, nullOut ? THRONG_ERROR_NULL_ARGUMENT : THRONG_OK);
        return got;
      }
      case 1: {
        const throng_status got = throng_world_state_hash(w, nullOut ? nullptr : &hash);
        check(got, early, nullOut ? THRONG_ERROR_NULL_ARGUMENT : THRONG_OK);
        return got;
      }
      default: {
        const throng_status got = throng_world_pending_events(w, nullOut ? nullptr : &pending);
        check(got, early, nullOut ? THRONG_ERROR_NULL_ARGUMENT : THRONG_OK);
        return got;
      }
    }
  }

  throng_status group(throng_world* w, const throng_world_stats& s, throng_status early) {
    const char* population = *rc::gen::element<const char*>("walkers", "walkers", "nope", nullptr);
    const auto index = *rc::gen::inRange<uint32_t>(0, 6);
    uint32_t g = 0;
    const throng_status got = throng_world_group(w, population, index, &g);
    const bool exists = population != nullptr && std::string(population) == "walkers" && index < 4;
    check(got, early, population == nullptr ? THRONG_ERROR_NULL_ARGUMENT : exists ? THRONG_OK : THRONG_ERROR_NOT_FOUND);
    if (got == THRONG_OK) RC_ASSERT(g < s.groups);
    return got;
  }

  /// Scenario handles and world options: a second world is created and freed at once.
  throng_status createOther() {
    throng_world_options o = throng_world_options_default();
    o.threads = *rc::gen::element(-1, 0, 1, 2, 2000);
    o.duration = *rc::gen::element(0.0, 5.0, -1.0, kNaN, kInf);
    const Who who = *genWho();
    int notAScenario = 0;
    const throng_scenario* s = who == Who::Live ? scenario_ : who == Who::Null ? nullptr : reinterpret_cast<throng_scenario*>(&notAScenario);
    throng_world* other = nullptr;
    const throng_status got = throng_world_create(s, &o, &other);
    const bool optionsOk = o.threads >= 0 && o.threads <= 1024 && std::isfinite(o.duration) && o.duration >= 0;
    const throng_status want = who == Who::Null ? THRONG_ERROR_NULL_ARGUMENT
                               : !optionsOk     ? THRONG_ERROR_INVALID_ARGUMENT
                               : who == Who::Stranger ? THRONG_ERROR_BAD_HANDLE
                                                      : THRONG_OK;
    check(got, THRONG_OK, want);
    throng_scenario_info info{};
    check(throng_scenario_info_get(s, &info), THRONG_OK,
          who == Who::Null ? THRONG_ERROR_NULL_ARGUMENT : who == Who::Stranger ? THRONG_ERROR_BAD_HANDLE : THRONG_OK);
    RC_ASSERT(throng_world_free(other) == THRONG_OK);
    return got;
  }

  throng_scenario* scenario_;
  throng_world* world_ = nullptr;
  long stranger_ = 42;  ///< an address the library never handed out
  std::set<std::string> inserted_;
  int nextCrowd_ = 0;
  int recordings_ = 0;
  test::TempDir dir_{"capi-prop"};
};

RC_GTEST_PROP(CApiProperties, RandomCallSequencesReturnTheDocumentedStatusAndNeverCrash, ()) {
  // Freed at exit, after this thread's thread_local destructors ran: the library must still work
  // then (it once wrote to a destroyed thread_local error string here).
  static ScenarioPtr scenario = loadJson(corridor(4, 60.0));
  Driver driver(scenario.get());
  const int calls = *rc::gen::inRange(1, 40);
  for (int i = 0; i < calls; ++i) driver.oneCall();
}

// Random text as a scenario: a diagnostic or a scenario, never a crash; NULL arguments refused.
RC_GTEST_PROP(CApiProperties, AnyTextLoadsOrGivesDiagnostics, ()) {
  const std::string text = *rc::gen::oneOf(
      rc::gen::arbitrary<std::string>(),
      rc::gen::map(rc::gen::inRange<std::size_t>(0, corridor(2).size()), [](std::size_t cut) { return corridor(2).substr(0, cut); }));
  throng_scenario* s = nullptr;
  char* diagnostics = nullptr;
  const throng_status got = throng_scenario_load_json(text.c_str(), "random.json", &s, &diagnostics);
  RC_ASSERT(got == THRONG_OK || got == THRONG_ERROR_INVALID_SCENARIO);
  RC_ASSERT((got == THRONG_OK) == (diagnostics == nullptr));
  RC_ASSERT((got == THRONG_OK) == (s != nullptr));
  if (diagnostics != nullptr) RC_ASSERT(std::string(diagnostics).rfind("random.json:", 0) == 0);
  throng_string_free(diagnostics);
  RC_ASSERT(throng_scenario_free(s) == THRONG_OK);
  RC_ASSERT(throng_scenario_load_json(nullptr, nullptr, &s, nullptr) == THRONG_ERROR_NULL_ARGUMENT);
  RC_ASSERT(throng_scenario_load_json(text.c_str(), nullptr, nullptr, nullptr) == THRONG_ERROR_NULL_ARGUMENT);
}

}  // namespace
}  // namespace throng::capi_test
