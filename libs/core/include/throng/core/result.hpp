// throng::core::Result<T> — a value or the list of diagnostics explaining why there is none.
// Shaped like C++23 std::expected (after Jolt's Result.h); every problem is reported, not the first.
#pragma once
#include <cassert>
#include <utility>
#include <variant>

#include "throng/core/diagnostic.hpp"

namespace throng::core {

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}                 // NOLINT(implicit)
  Result(Diagnostics errors) : data_(std::move(errors)) {      // NOLINT(implicit)
    assert(!std::get<Diagnostics>(data_).empty());
  }
  Result(Diagnostic error) : data_(Diagnostics{std::move(error)}) {}  // NOLINT(implicit)

  [[nodiscard]] bool ok() const { return std::holds_alternative<T>(data_); }
  explicit operator bool() const { return ok(); }

  T& value() & { return std::get<T>(data_); }
  const T& value() const& { return std::get<T>(data_); }
  T&& value() && { return std::get<T>(std::move(data_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }

  [[nodiscard]] const Diagnostics& errors() const { return std::get<Diagnostics>(data_); }
  Diagnostics&& takeErrors() && { return std::get<Diagnostics>(std::move(data_)); }

 private:
  std::variant<T, Diagnostics> data_;
};

/// Result of an operation that has no value on success.
struct Ok {};
using Status = Result<Ok>;

}  // namespace throng::core
