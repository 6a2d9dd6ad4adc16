// throng::sim operational models — the catalogue of avoidance models a population can walk with
// ("model" in a scenario's population) and the description of one model choice with its parameter
// values. The scenario loader, the validator, the JSON Schema and docs/scenario-format.md all read
// the same catalogue, so a model's parameters are declared once, with units, limits and defaults,
// next to its code (libs/sim/src/models/<model>.cpp). No I/O.
//
// A model turns each agent's preferred velocity (computed by the steer phase: path corners,
// arrival, formation, deadlock breaking) into the velocity it walks with this step, given its
// neighbours and the walls (after JuPedSim's OperationalModel). See docs/architecture.md, "Adding
// an avoidance model".
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace throng::sim {

/// The operational (avoidance) models. The value is the index into modelCatalogue().
enum class ModelKind : std::uint8_t {
  Orca = 0,                ///< optimal reciprocal collision avoidance (van den Berg et al. 2011)
  CollisionFreeSpeed = 1,  ///< collision-free speed model (Tordeux, Chraibi, Seyfried 2016)
  AnticipationVelocity = 2,  ///< anticipation velocity model (Xu, Chraibi, Seyfried 2021)
};
inline constexpr std::size_t kModelCount = 3;

/// One parameter of a model, after Recast's `[Limit] [Units]` convention.
struct ModelParameter {
  std::string_view key;      ///< scenario key, camelCase
  std::string_view unit;     ///< SI unit ("s", "m", "1" for a ratio, "" for a count)
  double min = 0.0;          ///< lower limit
  bool minExclusive = false; ///< the value must be > min (else >= min)
  double max = 0.0;          ///< upper limit (inclusive)
  bool integer = false;      ///< a whole number
  float defaultValue = 0.0f;
  std::string_view meaning;  ///< one sentence for messages, the schema and the docs
  std::string_view source;   ///< where the default comes from (paper, data set, measurement)

  [[nodiscard]] bool accepts(double v) const {
    return (minExclusive ? v > min : v >= min) && v <= max && (!integer || v == static_cast<double>(static_cast<long long>(v)));
  }
};

inline constexpr std::size_t kMaxModelParameters = 12;

/// A model as the scenario names it.
struct ModelInfo {
  ModelKind kind = ModelKind::Orca;
  std::string_view name;     ///< the value of a population's "model" key
  std::string_view title;    ///< human name
  std::string_view source;   ///< the paper it implements
  std::span<const ModelParameter> parameters;  ///< at most kMaxModelParameters, in ModelDesc::values order
};

/// Every model, in ModelKind order.
[[nodiscard]] std::span<const ModelInfo> modelCatalogue();
[[nodiscard]] const ModelInfo& modelInfo(ModelKind kind);
/// The model called `name` in scenarios, or nullptr.
[[nodiscard]] const ModelInfo* findModel(std::string_view name);

/// A population's model and its parameter values (the model's defaults unless the scenario gives
/// others). The default is avm (the calibrated pedestrian model) with its defaults: the model of
/// every population that names none.
struct ModelDesc {
  ModelDesc() : ModelDesc(ModelKind::AnticipationVelocity) {}
  explicit ModelDesc(ModelKind k);

  ModelKind kind;
  std::array<float, kMaxModelParameters> values{};  ///< in the order of modelInfo(kind).parameters

  /// The value of parameter `key` of this model (its default when unknown to it: never for a
  /// validated scenario).
  [[nodiscard]] float value(std::string_view key) const;
  /// Sets parameter `key`; false when this model has no such parameter.
  bool set(std::string_view key, float v);
  /// How close to a wall a body's centre may come, as a fraction of its radius: the model's
  /// "passageRatio" (bodies that turn their shoulders in narrow openings), 1 for models without
  /// it. The navmesh is eroded by the largest radius × ratio (ScenarioDesc::navRadius).
  [[nodiscard]] float passageRatio() const;
};

}  // namespace throng::sim
