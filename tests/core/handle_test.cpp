// Tests for libs/core/include/throng/core/handle.hpp: generational handles never resolve once stale.
#include "throng/core/handle.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <map>

namespace core = throng::core;
struct TestTag {};
using Map = core::SlotMap<TestTag>;
using Id = Map::Id;

TEST(Handle, NullAndPacking) {
  EXPECT_TRUE(Id{}.isNull());
  const Id id{5, 9};
  EXPECT_EQ(Id::unpack(id.pack()), id);
  Map m;
  EXPECT_FALSE(m.contains(Id{}));
  EXPECT_FALSE(m.find(Id{}).has_value());
}

TEST(Handle, ReusedSlotGetsNewGeneration) {
  Map m;
  const Id a = m.insert(10);
  m.erase(a);
  const Id b = m.insert(20);
  EXPECT_EQ(a.index, b.index);
  EXPECT_NE(a.generation, b.generation);
  EXPECT_FALSE(m.find(a).has_value());
  EXPECT_EQ(m.find(b), 20u);
}

// Random insert/erase/set sequences: live handles resolve to their latest payload, every erased
// handle stays unresolvable forever, and size() matches the model.
RC_GTEST_PROP(Handle, StaleHandlesNeverResolve, (const std::vector<std::pair<std::uint8_t, std::uint32_t>>& ops)) {
  Map m;
  std::map<std::uint64_t, std::uint32_t> live;  // packed handle -> payload
  std::vector<Id> dead;
  for (const auto& [op, value] : ops) {
    if (op % 3 == 0 || live.empty()) {
      const Id id = m.insert(value);
      RC_ASSERT(!id.isNull());
      RC_ASSERT(live.count(id.pack()) == 0u);
      live[id.pack()] = value;
    } else {
      auto it = live.begin();
      std::advance(it, value % live.size());
      const Id id = Id::unpack(it->first);
      if (op % 3 == 1) {
        m.erase(id);
        dead.push_back(id);
        live.erase(it);
      } else {
        m.set(id, value);
        it->second = value;
      }
    }
    for (const Id d : dead) RC_ASSERT(!m.find(d).has_value());
    RC_ASSERT(m.size() == live.size());
  }
  for (const auto& [packed, payload] : live) RC_ASSERT(m.find(Id::unpack(packed)) == std::optional<std::uint32_t>(payload));
}
