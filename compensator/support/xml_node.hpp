#pragma once
/// \file xml_node.hpp
/// A small owned XML tree (element name, attributes, children, source line) so that
/// tinyxml2 types never leave the loader. Typed attribute readers throw InputError with the
/// file and the line of the element.

#include <Eigen/Core>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "compensator/support/input_file.hpp"

namespace roprec {

struct XmlNode {
  std::string file;  ///< source file (for messages)
  std::string name;  ///< element name
  int line{0};       ///< 1-based line of the element's start tag
  std::vector<std::pair<std::string, std::string>> attributes;  ///< in document order
  std::vector<XmlNode> children;
  std::string text;  ///< concatenated text content (trimmed)

  [[nodiscard]] bool has(const std::string& attr) const;
  [[nodiscard]] std::optional<std::string> get(const std::string& attr) const;
  /// Required string attribute.
  [[nodiscard]] std::string str(const std::string& attr) const;
  [[nodiscard]] std::string str(const std::string& attr, const std::string& fallback) const;
  /// Finite double (required / with default).
  [[nodiscard]] double number(const std::string& attr) const;
  [[nodiscard]] double number(const std::string& attr, double fallback) const;
  /// Whitespace-separated list of exactly n finite doubles.
  [[nodiscard]] Eigen::VectorXd numbers(const std::string& attr, int n) const;
  [[nodiscard]] Eigen::Vector3d vec3(const std::string& attr,
                                     const Eigen::Vector3d& fallback) const;
  [[nodiscard]] bool boolean(const std::string& attr, bool fallback) const;
  /// First child with this element name, or nullptr.
  [[nodiscard]] const XmlNode* child(const std::string& element) const;
  [[nodiscard]] std::vector<const XmlNode*> childrenNamed(const std::string& element) const;

  /// InputError at this element's line.
  [[noreturn]] void fail(const std::string& message) const;
};

/// Parses an XML file; malformed XML throws InputError with tinyxml2's line.
XmlNode loadXmlFile(const std::string& path, InputKind kind = InputKind::kXml);
/// Parses XML text (`file` is used in messages only).
XmlNode parseXmlText(const std::string& text, const std::string& file);

/// " (did you mean 'x'?)" for the known name nearest to `name` when it is a near miss: the same
/// name in another case, an edit distance (adjacent swaps count 1) <= 2 (<= 1 for names of 3-4
/// characters), or an abbreviation of at least 3 characters ('dia' -> 'diameter'); else "".
/// `quote_open`/`quote_close` wrap the suggestion ("'" and "'" for attributes, "<" and ">" for
/// elements).
std::string didYouMean(const std::string& name, const std::vector<std::string>& known,
                       const std::string& quote_open = "'", const std::string& quote_close = "'");

/// Unknown attributes are errors (a misspelt parameter must not silently take its default).
/// Throws InputError at `e`'s line: `unknown attribute 'mas_kg' on <tool> (did you mean
/// 'mass_kg'?)`, or `... on <tool> (known: name, xyz, ...)` when no known name is near.
void allowOnly(const XmlNode& e, std::initializer_list<const char*> names);

/// Unknown child elements are errors. Throws InputError at the child's line: `unknown element
/// <tolerence> in <cell> (did you mean <tolerance>?)`, or `(known: <a>, <b>)`.
void allowChildren(const XmlNode& e, std::initializer_list<const char*> names);

/// Each named child element at most once: throws InputError at the second one's line
/// `<tool> is given twice in <cell> (first at line N)`.
void allowAtMostOnce(const XmlNode& e, std::initializer_list<const char*> names);

/// Strictly parses a finite double from the whole string (no trailing garbage).
std::optional<double> parseNumber(const std::string& s);

}  // namespace roprec
