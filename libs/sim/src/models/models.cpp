// The model catalogue (throng/sim/models.hpp): every operational model by ModelKind, with its
// scenario name and parameter table, and ModelDesc's parameter values. One line per model here.
#include <array>

#include "operational_model.hpp"
#include "throng/core/assert.hpp"

namespace throng::sim {
namespace {

struct Entry {
  const ModelInfo& (*info)();
  std::unique_ptr<OperationalModel> (*make)();
};

// In ModelKind order.
constexpr Entry kModels[] = {
    {orcaModelInfo, makeOrcaModel},
    {collisionFreeSpeedModelInfo, makeCollisionFreeSpeedModel},
    {anticipationVelocityModelInfo, makeAnticipationVelocityModel},
};

}  // namespace

std::span<const ModelInfo> modelCatalogue() {
  static const auto catalogue = [] {
    std::array<ModelInfo, std::size(kModels)> all;
    for (std::size_t i = 0; i < all.size(); ++i) {
      all[i] = kModels[i].info();
      THRONG_ASSERT(static_cast<std::size_t>(all[i].kind) == i && all[i].parameters.size() <= kMaxModelParameters);
    }
    return all;
  }();
  return catalogue;
}

const ModelInfo& modelInfo(ModelKind kind) { return modelCatalogue()[static_cast<std::size_t>(kind)]; }

const ModelInfo* findModel(std::string_view name) {
  for (const ModelInfo& m : modelCatalogue()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::unique_ptr<OperationalModel> makeModel(ModelKind kind) { return kModels[static_cast<std::size_t>(kind)].make(); }

ModelDesc::ModelDesc(ModelKind k) : kind(k) {
  const auto params = modelInfo(k).parameters;
  for (std::size_t i = 0; i < params.size(); ++i) values[i] = params[i].defaultValue;
}

float ModelDesc::value(std::string_view key) const {
  const auto params = modelInfo(kind).parameters;
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (params[i].key == key) return values[i];
  }
  return 0.0f;
}

float ModelDesc::passageRatio() const {
  const auto params = modelInfo(kind).parameters;
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (params[i].key == "passageRatio") return values[i];
  }
  return 1.0f;
}

bool ModelDesc::set(std::string_view key, float v) {
  const auto params = modelInfo(kind).parameters;
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (params[i].key == key) {
      values[i] = v;
      return true;
    }
  }
  return false;
}

}  // namespace throng::sim
