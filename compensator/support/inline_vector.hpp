#pragma once
/// \file inline_vector.hpp
/// A vector of at most N elements stored inline (no heap), for per-hole results whose size the
/// model bounds: the uncertainty budget of a hole has 3 robot terms and the machining model's 3
/// components (HolePrediction::budget), so a fresh prediction or compensation result allocates
/// nothing for it (zero heap allocations per hole). The interface is the part of
/// std::vector the results use: push_back, iteration, size, operator[], at, clear, reserve and
/// assignment from a braced list. Exceeding N is a programming error: push_back, reserve and a
/// longer list throw InternalError (never a silent truncation); at() checks the index.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>

#include "compensator/support/error.hpp"

namespace roprec {

template <class T, std::size_t N>
class InlineVector {
 public:
  using value_type = T;
  using iterator = T*;
  using const_iterator = const T*;

  InlineVector() = default;
  InlineVector(std::initializer_list<T> items) { *this = items; }
  InlineVector& operator=(std::initializer_list<T> items) {
    reserve(items.size());
    clear();
    for (const T& v : items) push_back(v);
    return *this;
  }
  /// Throws InternalError when the vector already holds N elements.
  void push_back(const T& v) {
    if (n_ == N) overflow(n_ + 1);
    items_[n_++] = v;
  }
  /// No storage to reserve; throws InternalError when `n` exceeds the capacity N.
  void reserve(std::size_t n) const {
    if (n > N) overflow(n);
  }
  void clear() { n_ = 0; }
  [[nodiscard]] std::size_t size() const { return n_; }
  [[nodiscard]] bool empty() const { return n_ == 0; }
  [[nodiscard]] static constexpr std::size_t capacity() { return N; }
  [[nodiscard]] T& operator[](std::size_t i) { return items_[i]; }
  [[nodiscard]] const T& operator[](std::size_t i) const { return items_[i]; }
  [[nodiscard]] T& at(std::size_t i) {
    if (i >= n_) outOfRange(i);
    return items_[i];
  }
  [[nodiscard]] const T& at(std::size_t i) const {
    if (i >= n_) outOfRange(i);
    return items_[i];
  }
  [[nodiscard]] T* begin() { return items_.data(); }
  [[nodiscard]] T* end() { return items_.data() + n_; }
  [[nodiscard]] const T* begin() const { return items_.data(); }
  [[nodiscard]] const T* end() const { return items_.data() + n_; }
  [[nodiscard]] const T& front() const { return items_[0]; }
  [[nodiscard]] const T& back() const { return items_[n_ - 1]; }

 private:
  [[noreturn]] static void overflow(std::size_t n) {
    throw InternalError("InlineVector: " + std::to_string(n) + " elements exceed its capacity " +
                        std::to_string(N));
  }
  [[noreturn]] void outOfRange(std::size_t i) const {
    throw InternalError("InlineVector: index " + std::to_string(i) + " beyond its " +
                        std::to_string(n_) + " elements");
  }
  std::array<T, N> items_{};
  std::size_t n_{0};
};

}  // namespace roprec
