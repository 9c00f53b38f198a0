/// Writing configuration flags into targets (docs/programs.md §7.4, §9).
#include <cmath>
#include <utility>

#include "postproc/dialects.hpp"
#include "postproc/lexer.hpp"

namespace roprec::postproc {
namespace {

constexpr NumberHints kInteger{0, false, false};

std::string binaryLike(std::string_view original, int value) {
  // original: 'B0101' -> same digit count (more when needed)
  const std::size_t digits = original.size() >= 3 ? original.size() - 3 : 1;
  std::string bits;
  for (int v = value; v > 0; v >>= 1) bits.insert(bits.begin(), static_cast<char>('0' + (v & 1)));
  if (bits.empty()) bits = "0";
  if (bits.size() < digits) bits.insert(0, digits - bits.size(), '0');
  return std::string("'") + original[1] + bits + "'";
}

void setInt(const Program& p, EditQueue& q, NumberField& f, int value) {
  const std::string_view orig =
      std::string_view(p.files[static_cast<std::size_t>(f.file)].bytes).substr(f.offset, f.length);
  if (f.value == static_cast<double>(value)) {
    q.erase(f.file, f.offset);
    return;
  }
  f.value = value;
  if (!orig.empty() && orig.front() == '\'') {
    if (orig.size() >= 2 && (orig[1] == 'H' || orig[1] == 'h')) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "'%c%X'", orig[1], static_cast<unsigned>(value));
      q.put(f.file, f.offset, f.length, buf);
    } else {
      q.put(f.file, f.offset, f.length, binaryLike(orig, value));
    }
    return;
  }
  q.put(f.file, f.offset, f.length, formatLike(orig, value, kInteger));
}

EditResult writeKrl(const Program& p, EditQueue& q, Target& t, const Configuration& c) {
  EditResult r;
  if (c.status > 255 || c.turn > 63) {
    r.reason = "S/T out of range";
    return r;
  }
  std::string insert;
  if (c.status >= 0) {
    if (std::as_const(t).statusField().present()) {
      setInt(p, q, t.statusField(), c.status);
    } else {
      insert += ",S " + std::to_string(c.status);
    }
    t.config.status = c.status;
  }
  if (c.turn >= 0) {
    if (std::as_const(t).turnField().present()) {
      setInt(p, q, t.turnField(), c.turn);
    } else {
      insert += ",T " + std::to_string(c.turn);
    }
    t.config.turn = c.turn;
  }
  if (!insert.empty()) q.put(t.file, t.aggregate_end, 0, insert);
  r.ok = true;
  return r;
}

EditResult writeRapid(const Program& p, EditQueue& q, Target& t, const Configuration& c) {
  EditResult r;
  for (const NumberField& f : t.cf_fields) {
    if (!f.present()) {
      r.reason = "target has no confdata";
      return r;
    }
  }
  for (std::size_t i = 0; i < 4; ++i) setInt(p, q, t.cf_fields[i], c.cf[i]);
  t.config.cf = c.cf;
  r.ok = true;
  return r;
}

EditResult writeTp(const Program& p, EditQueue& q, Target& t, const Configuration& c) {
  EditResult r;
  const NumberField& config_span = std::as_const(t).fanucConfig();
  if (!config_span.present()) {
    r.reason = "position has no CONFIG string";
    return r;
  }
  const bool letters_ok = (c.flip == 'F' || c.flip == 'N') && (c.elbow == 'U' || c.elbow == 'D') &&
                          (c.front == 'T' || c.front == 'B');
  if (!letters_ok) {
    r.reason = "FANUC configuration letters must be F|N U|D T|B";
    return r;
  }
  if (!p.fanuc_turn_axes && (c.turns[0] != t.config.turns[0] || c.turns[1] != t.config.turns[1])) {
    r.reason =
        "turn digit 1 or 2 changes but $SCR_GRP[1].$TURN_AXIS is unknown (J1,J4,J6 vs J4,J5,J6, "
        "docs/programs.md §9 item 1); refused";
    return r;
  }
  const std::string_view orig =
      std::string_view(p.files[static_cast<std::size_t>(config_span.file)].bytes)
          .substr(config_span.offset, config_span.length);
  // keep the original separators: replace letters and digit groups in place
  std::string out;
  int letter = 0;
  int turn = 0;
  const std::array<char, 3> letters{c.flip, c.elbow, c.front};
  for (std::size_t i = 0; i < orig.size();) {
    const char ch = orig[i];
    if (letter < 3 && std::isalpha(static_cast<unsigned char>(ch))) {
      out += letters[static_cast<std::size_t>(letter++)];
      ++i;
    } else if (letter == 3 && turn < 3 && (isDigit(ch) || ch == '-')) {
      std::size_t j = i + 1;
      while (j < orig.size() && isDigit(orig[j])) ++j;
      out += std::to_string(c.turns[static_cast<std::size_t>(turn++)]);
      i = j;
    } else {
      out += ch;
      ++i;
    }
  }
  if (letter != 3 || turn != 3) {
    r.reason = "CONFIG string not understood: '" + std::string(orig) + "'";
    return r;
  }
  if (out != orig) q.put(config_span.file, config_span.offset, config_span.length, out);
  t.config.flip = c.flip;
  t.config.elbow = c.elbow;
  t.config.front = c.front;
  t.config.turns = c.turns;
  r.ok = true;
  return r;
}

}  // namespace

EditResult writeConfiguration(const Program& p, EditQueue& q, Target& t, const Configuration& c) {
  switch (p.dialect) {
    case Dialect::kKrl:
      return writeKrl(p, q, t, c);
    case Dialect::kRapid:
      return writeRapid(p, q, t, c);
    case Dialect::kTp:
      return writeTp(p, q, t, c);
    default:
      break;
  }
  EditResult r;
  r.reason = "this dialect carries no configuration flags";
  return r;
}

}  // namespace roprec::postproc
