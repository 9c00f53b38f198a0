#pragma once
/// \file json.hpp
/// A small ordered JSON value for the CLI's reports. Keys keep insertion order and numbers are
/// printed with a fixed number of decimals (or shortest round-trip), so identical inputs give
/// byte-identical output. -0 is printed as 0. A non-finite number is never written: dump() throws
/// InternalError naming its place ($.holes[3].x), so producers must report such an item instead.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace roprec::api {

class Json {
 public:
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };

  Json() = default;
  static Json object();
  static Json array();
  static Json str(std::string s);
  static Json boolean(bool b);
  /// decimals < 0: shortest round-trip representation.
  static Json number(double v, int decimals = -1);
  static Json integer(std::int64_t v);
  /// Array of numbers.
  static Json vector(const Eigen::Ref<const Eigen::VectorXd>& v, int decimals = -1);

  /// Object: appends (or replaces) a key; returns the stored value.
  Json& set(const std::string& key, Json value);
  /// Array: appends.
  Json& push(Json value);

  [[nodiscard]] Kind kind() const { return kind_; }
  /// False when a non-finite number is anywhere inside (dump() would throw).
  [[nodiscard]] bool finite() const;
  /// Throws InternalError when the value holds a non-finite number.
  [[nodiscard]] std::string dump(int indent = 2) const;

 private:
  void write(std::string& out, int indent, int level) const;
  Kind kind_{Kind::kNull};
  bool bool_{false};
  double number_{0.0};
  int decimals_{-1};
  bool is_integer_{false};
  std::int64_t integer_{0};
  std::string string_;
  std::vector<Json> items_;
  std::vector<std::string> keys_;
};

/// Escapes a string for JSON (UTF-8 passes through; control characters are escaped).
std::string jsonEscape(const std::string& s);
/// Formats a double with fixed decimals (or shortest round-trip when decimals < 0), -0 -> 0, in
/// the "C" format whatever the locale. Non-finite values give numberText()'s words.
std::string formatNumber(double v, int decimals);

}  // namespace roprec::api
