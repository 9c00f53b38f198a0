#pragma once
/// \file json.hpp
/// A small ordered JSON value for the CLI's reports. Keys keep insertion order and numbers are
/// printed with a fixed number of decimals (or shortest round-trip), so identical inputs give
/// byte-identical output. -0 is printed as 0. A non-finite number is never written: dump() throws
/// InternalError naming its place ($.holes[3].x), so producers must report such an item instead.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "compensator/support/error.hpp"

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
  friend class JsonWriter;
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

/// Writes the bytes Json::dump(2) would give for the same values, in order, without building a
/// tree (the prediction and target exports stream hole by hole in constant memory). Objects and
/// arrays of containers are opened and closed around their members; arrays of scalars are given
/// whole (numbers(), strings()) and written on one line, like Json::dump. Output is appended to
/// `out()`, which the caller may drain at any point between two values (`take()`).
/// Non-finite numbers are never written: number()/numbers() throw JsonNonFinite naming the place
/// ($.holes[3].deviation_um.robot[1]); an item producer can catch it, cut the item off with
/// mark()/rewind() and write a "failed" item instead (see plugin/report/exports.cpp).
class JsonNonFinite : public InternalError {
 public:
  explicit JsonNonFinite(const std::string& where);
  std::string where;  ///< "$.holes[3].x"
};

class JsonWriter {
 public:
  void beginObject();
  void endObject();
  /// An array of objects/arrays, one item per line (arrays of scalars: numbers()/strings()).
  void beginArray();
  void endArray();
  /// Object member name; the value follows. `k` must stay alive until the value is written.
  void key(std::string_view k);
  void str(std::string_view s);
  /// decimals < 0: shortest round-trip. Throws JsonNonFinite for NaN/inf (nothing appended).
  void number(double v, int decimals = -1);
  void integer(std::int64_t v);
  void boolean(bool b);
  void null();
  /// A one-line array of numbers (Json::vector). Throws JsonNonFinite before appending anything.
  void numbers(const Eigen::Ref<const Eigen::VectorXd>& v, int decimals = -1);
  /// A one-line array of strings.
  void strings(const std::vector<std::string>& v);
  /// A whole tree value at the current place (same bytes as inside Json::dump).
  void value(const Json& j);
  /// Ends the document (the final newline of Json::dump); the writer must be back at the top.
  void finish();

  /// Position to rewind to: the output size and the open containers.
  struct Mark {
    size_t size;
    size_t depth;
    size_t count;
  };
  [[nodiscard]] Mark mark() const;
  /// Drops everything written since `m` (which must not have been drained by take()).
  void rewind(const Mark& m);

  /// A writer positioned at item k after the items written so far of the array open here, its
  /// output empty. Runs of items written apart (on several threads) and appended in order with
  /// appendItems() give the bytes of writing them here one after the other; a JsonNonFinite
  /// names the item's own index. Throws InternalError when no array is open here.
  [[nodiscard]] JsonWriter itemWriter(size_t k) const;
  /// Appends the text of the next `n` items of the open array (written by an itemWriter()).
  void appendItems(std::string_view text, size_t n);

  [[nodiscard]] std::string& out() { return out_; }
  /// Moves the text written so far out (the writer keeps its state).
  void take(std::string& to);

 private:
  struct Frame {
    bool object;
    size_t count;
    std::string_view key;  ///< last key (objects), for messages
  };
  void beforeValue();
  /// Before a member or an item: ",\n" (`comma`) or "\n", then the indentation of this level.
  void newLine(bool comma);
  void pad(size_t n);
  [[nodiscard]] std::string where(std::string_view tail = {}) const;
  std::string out_;
  std::vector<Frame> stack_;
};

/// Escapes a string for JSON (UTF-8 passes through; control characters are escaped).
std::string jsonEscape(const std::string& s);
/// Appends jsonEscape(s) to `out`.
void appendJsonEscaped(std::string& out, std::string_view s);
/// Appends formatNumber(v, decimals) to `out` (v finite).
void appendNumber(std::string& out, double v, int decimals);
/// Formats a double with fixed decimals (or shortest round-trip when decimals < 0), -0 -> 0, in
/// the "C" format whatever the locale. Non-finite values give numberText()'s words.
std::string formatNumber(double v, int decimals);

}  // namespace roprec::api
