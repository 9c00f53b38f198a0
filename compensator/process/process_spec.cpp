#include "compensator/process/process_spec.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <sstream>

#include "compensator/support/c_format.hpp"
#include "compensator/support/error.hpp"

namespace roprec {
namespace {

constexpr double kMm = 1e-3;
constexpr double kMPa = 1e6;

const XmlNode& required(const XmlNode& parent, const std::string& name, const std::string& what) {
  const XmlNode* c = parent.child(name);
  if (c == nullptr)
    parent.fail("<process type=\"" + parent.str("type", "") + "\"> needs a <" + name +
                "> element (" + what + ")");
  return *c;
}

double positive(const XmlNode& e, const std::string& attr, double fallback, bool has_fallback) {
  const double v = has_fallback ? e.number(attr, fallback) : e.number(attr);
  if (!(v > 0))
    e.fail("<" + e.name + "> " + attr + " must be > 0, got " + e.str(attr, std::to_string(v)));
  return v;
}

double nonNegative(const XmlNode& e, const std::string& attr, double fallback) {
  const double v = e.number(attr, fallback);
  if (!(v >= 0)) e.fail("<" + e.name + "> " + attr + " must be >= 0, got " + e.str(attr, ""));
  return v;
}

const Material& material(const XmlNode& proc) {
  const XmlNode& m =
      required(proc, "material", "workpiece material, e.g. <material name=\"Al 6061-T6\"/>");
  allowOnly(m, {"name"});
  const std::string name = m.str("name");
  const Material* mat = findMaterial(name);
  if (mat == nullptr) m.fail("unknown material '" + name + "' (known: " + materialNames() + ")");
  return *mat;
}

std::optional<double> optionalAt(const XmlNode& e, const std::string& attr, double scale,
                                 bool strictly_positive) {
  if (!e.has(attr)) return std::nullopt;
  return (strictly_positive ? positive(e, attr, 0, false) : nonNegative(e, attr, 0)) * scale;
}

/// Largest plausible entry of <coupling compliance_um_per_N> (um/N): 1 mm/N. A robot at the
/// tool is ~0.1-10 um/N; the bound still admits unphysical cells whose coupling diverges (reported
/// per point), not numbers that overflow.
constexpr double kMaxCouplingCompliance = 1000.0;

/// Refuses a value (in the file's unit) outside the plausible [lo, hi]: a corrupted number such
/// as stickout_mm="1e-300" would otherwise silently remove the tool's compliance.
void plausible(const XmlNode& e, const std::string& attr, double lo, double hi,
               const std::string& why) {
  if (!e.has(attr)) return;
  const double v = e.number(attr);
  if (v >= lo && v <= hi) return;
  e.fail("<" + e.name + "> " + attr + " = " + numberText(v) + " is outside the plausible range " +
         numberText(lo) + " .. " + numberText(hi) + " (" + why + ")");
}

/// Plausible ranges of the tool-side machining-deviation inputs (docs/process.md).
void plausibleToolInputs(const XmlNode& e) {
  plausible(e, "stickout_mm", 1.0, 1000.0, "tool length out of the holder, mm");
  plausible(e, "axis_tilt_deg", 0.0, 5.0, "spindle axis tilt, deg");
  plausible(e, "axis_lever_mm", 0.0, 2000.0, "lever of the tilt, mm");
  plausible(e, "runout_mm", 0.0, 1.0, "radial runout, mm");
  plausible(e, "youngs_modulus_GPa", 10.0, 1000.0, "tool material modulus, GPa");
  plausible(e, "equivalent_diameter_ratio", 0.3, 1.0, "fluted section / nominal diameter");
  plausible(e, "spindle_compliance_um_per_N", 0.0, 100.0, "spindle compliance, um/N");
}

MachiningDeviationOverride parseDeviationOverride(const XmlNode& md) {
  if (md.has("k")) {
    md.fail(
        "<machining_deviation> k is not used: U_mach is expanded with the budget's 2-D radial "
        "coverage factor (k = 2.4477 for 95 %) in every command; remove the attribute");
  }
  allowOnly(md, {"diameter_mm", "axis_tilt_deg", "axis_lever_mm", "runout_mm", "stickout_mm",
                 "equivalent_diameter_ratio", "youngs_modulus_GPa", "spindle_compliance_um_per_N"});
  MachiningDeviationOverride o;
  o.source = "cell <machining_deviation> line " + std::to_string(md.line);
  if (md.has("diameter_mm")) {
    std::istringstream in(md.str("diameter_mm"));
    std::string tok;
    while (in >> tok) {
      const std::optional<double> v = parseNumber(tok);
      if (!v || !(*v > 0) || *v > 1000)
        md.fail("<machining_deviation> diameter_mm must list diameters in mm, got '" + tok + "'");
      o.diameters.push_back(*v * kMm);
    }
    if (o.diameters.empty()) md.fail("<machining_deviation> diameter_mm is empty");
  }
  plausibleToolInputs(md);
  o.axis_tilt = optionalAt(md, "axis_tilt_deg", kDeg, false);
  o.axis_lever = optionalAt(md, "axis_lever_mm", kMm, false);
  o.runout = optionalAt(md, "runout_mm", kMm, false);
  o.stickout = optionalAt(md, "stickout_mm", kMm, true);
  o.equivalent_diameter_ratio = optionalAt(md, "equivalent_diameter_ratio", 1.0, true);
  if (o.equivalent_diameter_ratio && *o.equivalent_diameter_ratio > 1)
    md.fail("<machining_deviation> equivalent_diameter_ratio must be <= 1");
  o.youngs_modulus = optionalAt(md, "youngs_modulus_GPa", 1e9, true);
  o.spindle_compliance = optionalAt(md, "spindle_compliance_um_per_N", 1e-6, false);
  return o;
}

bool namesDiameter(const MachiningDeviationOverride& o, double diameter) {
  for (const double d : o.diameters)
    if (std::abs(d - diameter) < 1e-6) return true;
  return false;
}

/// Applies the values `o` states; `runout_set` tracks whether a runout was stated explicitly.
void applyOverride(const MachiningDeviationOverride& o, MachiningDeviationParams& p,
                   bool& runout_set) {
  if (o.axis_tilt) {
    p.axis_tilt = *o.axis_tilt;
    p.axis_source = o.source;
  }
  if (o.axis_lever) p.axis_lever = *o.axis_lever;
  if (o.stickout) {
    p.stickout = *o.stickout;
    p.stickout_source = o.source;
  }
  if (o.runout) {
    p.runout = *o.runout;
    p.runout_source = o.source;
    runout_set = true;
  }
  if (o.equivalent_diameter_ratio) p.equivalent_diameter_ratio = *o.equivalent_diameter_ratio;
  if (o.youngs_modulus) {
    p.youngs_modulus = *o.youngs_modulus;
    p.modulus_source = o.source;
  }
  if (o.spindle_compliance) {
    p.spindle_compliance = *o.spindle_compliance;
    p.spindle_source = o.source;
  }
}

/// The <cut> of tool `d` (a <drill> or <mill>): the process's <cut> with the attributes of the
/// tool's own <cut> over it (messages at the tool's <cut> when it has one). Throws (`what`: the
/// cut's content) when neither exists.
XmlNode cutOf(const XmlNode& proc, const XmlNode& d, const std::string& what) {
  allowChildren(d, {"cut", "tcp"});  // <tcp>: the tool's own TCP, read with the cell's tool
  allowAtMostOnce(d, {"cut", "tcp"});
  const XmlNode* shared = proc.child("cut");
  const XmlNode* own = d.child("cut");
  if (own == nullptr) return required(proc, "cut", what);
  XmlNode c = shared != nullptr ? *shared : *own;
  c.line = own->line;
  for (const auto& [name, value] : own->attributes) {
    auto it = std::find_if(c.attributes.begin(), c.attributes.end(),
                           [&](const auto& a) { return a.first == name; });
    if (it == c.attributes.end())
      c.attributes.emplace_back(name, value);
    else
      it->second = value;
  }
  return c;
}

/// Refuses an entry `t` (<drill> or <mill>) of a tool table of `count` without tool=, or with the
/// tool of an `earlier` entry (its tool key and line).
void checkToolKey(const XmlNode& t, std::size_t count,
                  const std::vector<std::pair<std::string, int>>& earlier) {
  if (count > 1 && !t.has("tool")) {
    t.fail("<" + t.name + "> needs tool=\"...\" in a tool table of " + std::to_string(count) + " " +
           t.name +
           "s: the controller's tool number or name that selects it (KRL TOOL_DATA[n], "
           "RAPID tooldata, FANUC UTOOL n)");
  }
  for (const auto& [key, line] : earlier) {
    if (!key.empty() && sameToolKey(key, t.str("tool", "")))
      t.fail("<" + t.name + "> tool=\"" + t.str("tool") + "\" is given twice (first at line " +
             std::to_string(line) + ")");
  }
}

/// Every `element` (<drill> or <mill>) of the process's tool table, in document order, each read
/// by `parse(proc, node, spec)` after its tool key is checked (checkToolKey).
template <class Spec, class Parse>
std::vector<Spec> parseToolTable(const XmlNode& proc, const std::string& element,
                                 const std::string& what, Parse parse) {
  const std::vector<const XmlNode*> nodes = proc.childrenNamed(element);
  if (nodes.empty()) required(proc, element, what);
  std::vector<std::pair<std::string, int>> keys;
  std::vector<Spec> out;
  for (const XmlNode* t : nodes) {
    checkToolKey(*t, nodes.size(), keys);
    keys.emplace_back(t->str("tool", ""), t->line);
    Spec s;
    s.line = proc.line;
    parse(proc, *t, s);
    out.push_back(std::move(s));
  }
  return out;
}

/// One <drill> of the tool table with its cut data (docs/process.md §8, tool table).
void parseDrill(const XmlNode& proc, const XmlNode& d, DrillingSpec& s) {
  s.tool = d.str("tool", "");
  s.name = d.str("name", "");
  s.drill_line = d.line;
  allowOnly(d, {"tool", "name", "diameter_mm", "point_angle_deg", "helix_angle_deg", "web_mm",
                "chisel_angle_deg", "lips", "runout_mm", "tool_material", "stickout_mm",
                "flute_length_mm", "angle_law", "working_angles"});
  DrillGeometry& g = s.geometry;
  g.diameter = positive(d, "diameter_mm", 0, false) * kMm;
  plausible(d, "diameter_mm", 0.1, 100.0, "twist drill diameter, mm");
  g.point_angle = d.number("point_angle_deg", 118.0) * kDeg;
  g.helix_angle = d.number("helix_angle_deg", 30.0) * kDeg;
  g.web_thickness = d.number("web_mm", 0.16 * g.diameter / kMm) * kMm;
  if (d.has("web_mm") && g.web_thickness >= 0 && g.web_thickness < 0.02 * g.diameter) {
    d.fail("<drill> web_mm = " + numberText(g.web_thickness / kMm) +
           " is below 0.02 Dc = " + numberText(0.02 * g.diameter / kMm) +
           " mm: not a twist drill's web (about 0.1 .. 0.25 Dc)");
  }
  g.chisel_angle = d.number("chisel_angle_deg", 125.0) * kDeg;
  const double lips = d.number("lips", 2.0);
  if (lips != std::floor(lips)) d.fail("<drill> lips must be an integer");
  g.lips = static_cast<int>(lips);
  s.runout_given = d.has("runout_mm");
  g.runout = nonNegative(d, "runout_mm", 0.0) * kMm;
  const std::string tm = d.str("tool_material", "carbide");
  if (tm != "carbide" && tm != "hss")
    d.fail("<drill> tool_material must be 'carbide' or 'hss', got '" + tm + "'");
  s.carbide = tm == "carbide";
  const std::string law = d.str("angle_law", "geometric");
  if (law != "geometric" && law != "paper")
    d.fail("<drill> angle_law must be 'geometric' or 'paper', got '" + law + "'");
  s.law = law == "paper" ? AngleLaw::kPaperProportional : AngleLaw::kGeometric;
  s.working_angles = d.boolean("working_angles", true);
  if (const std::string problem = drillGeometryProblem(g); !problem.empty()) d.fail(problem);

  if (d.has("stickout_mm")) {
    s.drill_stickout = positive(d, "stickout_mm", 0, false) * kMm;
    plausible(d, "stickout_mm", g.diameter / kMm, 1000.0,
              "tool length out of the holder, mm: at least the drill diameter");
  }
  if (d.has("flute_length_mm")) {
    s.drill_flute_length = positive(d, "flute_length_mm", 0, false) * kMm;
    plausible(d, "flute_length_mm", g.diameter / kMm, 1000.0,
              "the drill's cutting (flute) length, mm: at least the drill diameter");
  }

  const XmlNode c = cutOf(proc, d, "feed and speed");
  allowOnly(c, {"feed_mm_per_rev", "spindle_rpm", "depth_mm", "through"});
  s.feed_line = c.line;
  const double f = c.number("feed_mm_per_rev");
  if (!(f > 0)) c.fail("<cut> feed_mm_per_rev must be > 0, got " + c.str("feed_mm_per_rev"));
  if (f > 0.1 * g.diameter / kMm)
    c.fail("<cut> feed_mm_per_rev " + c.str("feed_mm_per_rev") + " is above 0.1 Dc");
  s.feed = f * kMm;
  s.spindle_rpm = positive(c, "spindle_rpm", 3000.0, true);
  plausible(c, "spindle_rpm", 10.0, 100000.0, "spindle speed, 1/min");
  plausible(c, "feed_mm_per_rev", 0.001, 10.0, "feed per revolution, mm");
  s.hole_depth = positive(c, "depth_mm", 2.0 * g.diameter / kMm, true) * kMm;
  plausible(c, "depth_mm", 0.1, 1000.0, "hole depth, mm");
  s.through = c.boolean("through", false);

  const Material& mat = material(proc);
  s.material = &mat;
  s.coeff = mat.drilling;
  s.coeff_source = mat.drilling_source;
  if (const XmlNode* k = proc.child("coefficients")) {
    allowOnly(*k, {"kst0_N_mm2", "at", "bt_per_deg", "ct_per_deg", "ksa0_N_mm2", "aa", "ba_per_deg",
                   "ca_per_deg", "m", "h_min_mm", "chisel_model", "chisel_thrust_ratio",
                   "chisel_pressure_ratio", "chisel_torque_ratio", "source"});
    SpecificPressure& t = s.coeff.tangential;
    SpecificPressure& a = s.coeff.axial;
    t.k0 = positive(*k, "kst0_N_mm2", t.k0 / kMPa, true) * kMPa;
    a.k0 = positive(*k, "ksa0_N_mm2", a.k0 / kMPa, true) * kMPa;
    t.a = k->number("at", t.a);
    t.b = k->number("bt_per_deg", t.b * kDeg) / kDeg;
    t.c = k->number("ct_per_deg", t.c * kDeg) / kDeg;
    a.a = k->number("aa", a.a);
    a.b = k->number("ba_per_deg", a.b * kDeg) / kDeg;
    a.c = k->number("ca_per_deg", a.c * kDeg) / kDeg;
    const double m = k->number("m", t.m);
    if (!(m >= 0 && m < 1)) k->fail("<coefficients> m must lie in [0, 1)");
    t.m = a.m = m;
    const double hmin = positive(*k, "h_min_mm", t.h_min / kMm, true) * kMm;
    t.h_min = a.h_min = hmin;
    const std::string cm = k->str("chisel_model", "ratio");
    if (cm != "ratio" && cm != "pressure")
      k->fail("<coefficients> chisel_model must be 'ratio' or 'pressure'");
    s.coeff.chisel.kind = cm == "ratio" ? ChiselModelKind::kRatio : ChiselModelKind::kPressure;
    s.coeff.chisel.thrust_ratio =
        nonNegative(*k, "chisel_thrust_ratio", s.coeff.chisel.thrust_ratio);
    s.coeff.chisel.pressure_ratio =
        nonNegative(*k, "chisel_pressure_ratio", s.coeff.chisel.pressure_ratio);
    s.coeff.chisel.torque_ratio =
        nonNegative(*k, "chisel_torque_ratio", s.coeff.chisel.torque_ratio);
    s.coeff_source = k->str("source", "cell <coefficients> (no source given)");
  }

  for (const XmlNode* md : proc.childrenNamed("machining_deviation"))
    s.deviation_overrides.push_back(parseDeviationOverride(*md));
  s.deviation = machiningDeviationAt(s, g.diameter);
  if (!s.runout_given) g.runout = s.deviation.runout;
  if (const std::string problem = drillGeometryProblem(g); !problem.empty()) d.fail(problem);
}

void parseDrilling(const XmlNode& proc, ProcessSpec& spec) {
  allowChildren(proc, {"drill", "cut", "material", "coefficients", "machining_deviation"});
  spec.drills = parseToolTable<DrillingSpec>(proc, "drill", "drill geometry", parseDrill);
  spec.drilling = spec.drills.front();
}

}  // namespace

DrillingSpec holeDrilling(const ProcessSpec& spec, int drill, double diameter, double depth,
                          double feed, double spindle_rpm) {
  const DrillingSpec& own =
      spec.drills.empty() ? spec.drilling : spec.drills[static_cast<size_t>(std::max(drill, 0))];
  DrillingSpec s = own;
  if (feed > 0) s.feed = feed;
  if (spindle_rpm > 0) s.spindle_rpm = spindle_rpm;
  if (depth > 0) s.hole_depth = depth;
  if (diameter > 0 && std::abs(diameter - s.geometry.diameter) >= 1e-9) {
    const double scale = diameter / s.geometry.diameter;
    s.geometry.web_thickness *= scale;
    s.geometry.diameter = diameter;
    s.deviation = machiningDeviationAt(own, diameter);
    s.geometry.runout = s.deviation.runout;
  }
  return s;
}

bool sameToolKey(std::string_view a, std::string_view b) {
  const auto integer = [](std::string_view t) -> std::optional<long> {
    if (t.empty() || t.size() > 9) return std::nullopt;
    long v = 0;
    for (const char ch : t) {
      if (ch < '0' || ch > '9') return std::nullopt;
      v = v * 10 + (ch - '0');
    }
    return v;
  };
  if (const auto ia = integer(a), ib = integer(b); ia && ib) return *ia == *ib;
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

int drillIndex(const ProcessSpec& s, std::string_view tool) {
  for (std::size_t i = 0; i < s.drills.size(); ++i)
    if (!s.drills[i].tool.empty() && sameToolKey(s.drills[i].tool, tool))
      return static_cast<int>(i);
  return -1;
}

int millIndex(const ProcessSpec& s, std::string_view tool) {
  for (std::size_t i = 0; i < s.mills.size(); ++i)
    if (!s.mills[i].tool_key.empty() && sameToolKey(s.mills[i].tool_key, tool))
      return static_cast<int>(i);
  return -1;
}

namespace {

/// commandToolIndex over one table: `labels` name its entries; `index` is the entry keyed `tool`.
std::size_t tableEntry(const std::vector<std::string>& labels, bool single_unkeyed,
                       const std::optional<std::string>& tool, int index, const char* kind) {
  std::string all;
  for (const std::string& l : labels) all += (all.empty() ? "" : ", ") + l;
  if (!tool) {
    if (labels.size() == 1) return 0;
    throw UsageError("the cell's tool table has " + std::to_string(labels.size()) + " " + kind +
                     "s (" + all + "): which " + kind + "? Give --tool N");
  }
  if (single_unkeyed || index < 0)
    throw UsageError("--tool " + *tool + ": the cell has no such " + kind + " (" + all + ")");
  return static_cast<std::size_t>(index);
}

}  // namespace

std::size_t commandToolIndex(const ProcessSpec& s, const std::optional<std::string>& tool) {
  std::vector<std::string> labels;
  switch (s.type) {
    case ProcessType::kDrilling:
      for (const DrillingSpec& d : s.drills) labels.push_back(drillLabel(d));
      return tableEntry(labels, s.drills.size() == 1 && s.drills.front().tool.empty(), tool,
                        tool ? drillIndex(s, *tool) : -1, "drill");
    case ProcessType::kMilling:
      for (const MillingSpec& m : s.mills) labels.push_back(millLabel(m));
      return tableEntry(labels, s.mills.size() == 1 && s.mills.front().tool_key.empty(), tool,
                        tool ? millIndex(s, *tool) : -1, "mill");
    case ProcessType::kWrench:
      break;
  }
  if (tool) throw UsageError("--tool " + *tool + ": the cell's process is a wrench, not a tool");
  return 0;
}

std::string millLabel(const MillingSpec& m) {
  const std::string size =
      "Ø" + numberText(m.tool.diameter / kMm) + " mm, " + std::to_string(m.tool.teeth) + " teeth";
  if (m.tool_key.empty()) return "the cell's mill (" + size + ")";
  return "tool " + m.tool_key + (m.name.empty() ? "" : " '" + m.name + "'") + " (" + size + ")";
}

std::string drillLabel(const DrillingSpec& d) {
  const std::string size = "Ø" + numberText(d.geometry.diameter / kMm) + " mm";
  if (d.tool.empty()) return "the cell's drill (" + size + ")";
  return "tool " + d.tool + (d.name.empty() ? "" : " '" + d.name + "'") + " (" + size + ")";
}

MachiningDeviationParams machiningDeviationAt(const DrillingSpec& s, double diameter) {
  MachiningDeviationParams p = defaultMachiningDeviation(diameter, s.carbide);
  bool runout_set = false;
  if (std::abs(diameter - s.geometry.diameter) < 1e-6) {
    if (s.drill_stickout) {
      p.stickout = *s.drill_stickout;
      p.stickout_source = "cell <drill stickout_mm>";
    }
    if (s.runout_given) {
      p.runout = s.geometry.runout;
      p.runout_source = "cell <drill runout_mm>";
      runout_set = true;
    }
  }
  for (const MachiningDeviationOverride& o : s.deviation_overrides)
    if (o.diameters.empty()) applyOverride(o, p, runout_set);
  for (const MachiningDeviationOverride& o : s.deviation_overrides)
    if (namesDiameter(o, diameter)) applyOverride(o, p, runout_set);
  if (!runout_set) p.runout = 0.25e-3 * p.stickout;  // the default law follows the stick-out
  return p;
}

CuttingLength cuttingLengthAt(const DrillingSpec& s, double diameter) {
  const MachiningDeviationParams p = machiningDeviationAt(s, diameter);
  CuttingLength c{p.stickout, p.stickout_source};
  const bool own = std::abs(diameter - s.geometry.diameter) < 1e-6;
  if (own && s.drill_flute_length && *s.drill_flute_length <= p.stickout)
    c = {*s.drill_flute_length, "cell <drill flute_length_mm>"};
  else if (own && s.drill_flute_length)
    c.source += " (below <drill flute_length_mm>: the flutes inside the holder do not cut)";
  return c;
}

namespace {

/// <dynamics>: the robot's modal damping and the spindle/tool mode (docs/process.md §4.6).
void parseMillingDynamics(const XmlNode& dy, MillingSpec& s) {
  allowOnly(dy, {"robot_damping_ratio", "tool_frequency_hz", "tool_stiffness_N_per_um",
                 "tool_damping_ratio", "source"});
  s.robot_damping_ratio = positive(dy, "robot_damping_ratio", s.robot_damping_ratio, true);
  plausible(dy, "robot_damping_ratio", 0.001, 0.5, "modal damping ratio of the robot");
  s.tool_mode.frequency_hz = positive(dy, "tool_frequency_hz", s.tool_mode.frequency_hz, true);
  plausible(dy, "tool_frequency_hz", 50.0, 50000.0, "spindle/tool natural frequency, Hz");
  s.tool_mode.stiffness =
      positive(dy, "tool_stiffness_N_per_um", s.tool_mode.stiffness * 1e-6, true) * 1e6;
  plausible(dy, "tool_stiffness_N_per_um", 0.1, 1000.0, "spindle/tool stiffness, N/um");
  s.tool_mode.damping_ratio = positive(dy, "tool_damping_ratio", s.tool_mode.damping_ratio, true);
  plausible(dy, "tool_damping_ratio", 0.001, 0.5, "modal damping ratio of the tool");
  s.dynamics_source = dy.str("source", "cell <dynamics> line " + std::to_string(dy.line));
}

/// One <mill> `t` of the tool table with its cut data and the process's shared elements.
void parseMill(const XmlNode& proc, const XmlNode& t, MillingSpec& s) {
  allowOnly(t, {"tool", "name", "diameter_mm", "teeth", "helix_angle_deg", "runout_mm",
                "runout_angle_deg"});
  s.tool_key = t.str("tool", "");
  s.name = t.str("name", "");
  s.mill_line = t.line;
  s.tool.diameter = positive(t, "diameter_mm", 0, false) * kMm;
  plausible(t, "diameter_mm", 0.1, 200.0, "cutter diameter, mm");
  const double teeth = t.number("teeth", 3.0);
  if (!(teeth >= 1 && teeth <= 12 && teeth == std::floor(teeth)))
    t.fail("<mill> teeth must be an integer 1..12");
  s.tool.teeth = static_cast<int>(teeth);
  s.tool.helix_angle = t.number("helix_angle_deg", 30.0) * kDeg;
  if (!(s.tool.helix_angle >= 0 && s.tool.helix_angle < 60 * kDeg))
    t.fail("<mill> helix_angle_deg must lie in [0, 60)");
  s.tool.runout = nonNegative(t, "runout_mm", 0.0) * kMm;
  if (!(s.tool.runout < 0.05 * s.tool.diameter)) t.fail("<mill> runout_mm must be < 0.05 D");
  plausible(t, "runout_angle_deg", -360.0, 360.0, "angle of the runout, deg");
  s.tool.runout_angle = t.number("runout_angle_deg", 0.0) * kDeg;

  const XmlNode c = cutOf(proc, t, "ap, ae, fz and mode");
  allowOnly(c, {"ap_mm", "ae_mm", "fz_mm", "mode", "spindle_rpm"});
  s.cut.ap = positive(c, "ap_mm", 0, false) * kMm;
  s.cut.ae = positive(c, "ae_mm", 0, false) * kMm;
  const double fz = c.number("fz_mm");
  if (!(fz > 0)) c.fail("<cut> fz_mm must be > 0, got " + c.str("fz_mm"));
  s.cut.fz = fz * kMm;
  if (s.cut.fz > 0.2 * s.tool.diameter) c.fail("<cut> fz_mm is above 0.2 D");
  if (s.cut.ae > s.tool.diameter) c.fail("<cut> ae_mm must be <= the cutter diameter");
  const std::string mode = c.str("mode", s.cut.ae >= s.tool.diameter ? "slot" : "up");
  if (mode == "up") {
    s.cut.mode = MillingMode::kUp;
  } else if (mode == "down") {
    s.cut.mode = MillingMode::kDown;
  } else if (mode == "slot") {
    s.cut.mode = MillingMode::kSlot;
    s.cut.ae = s.tool.diameter;
  } else {
    c.fail("<cut> mode must be 'up', 'down' or 'slot', got '" + mode + "'");
  }
  s.cut.spindle_rpm = positive(c, "spindle_rpm", 10000.0, true);
  plausible(c, "spindle_rpm", 10.0, 100000.0, "spindle speed, 1/min");
  plausible(c, "ap_mm", 0.001, 200.0, "axial depth of cut, mm");
  plausible(c, "ae_mm", 0.001, 200.0, "radial depth of cut, mm");
  plausible(c, "fz_mm", 1e-4, 10.0, "feed per tooth, mm");

  const Material& mat = material(proc);
  s.material = &mat;
  s.coeff = mat.milling;
  s.coeff_source = mat.kienzle_source + "; " + mat.milling_ratio_source;
  if (const XmlNode* k = proc.child("coefficients")) {
    allowOnly(*k, {"kc11_N_mm2", "mc", "radial_ratio", "axial_ratio", "force_law", "source"});
    s.coeff.kc11 = positive(*k, "kc11_N_mm2", s.coeff.kc11 / kMPa, true) * kMPa;
    s.coeff.mc = k->number("mc", s.coeff.mc);
    if (!(s.coeff.mc >= 0 && s.coeff.mc < 1)) k->fail("<coefficients> mc must lie in [0, 1)");
    s.coeff.radial_ratio = nonNegative(*k, "radial_ratio", s.coeff.radial_ratio);
    s.coeff.axial_ratio = nonNegative(*k, "axial_ratio", s.coeff.axial_ratio);
    const std::string law = k->str("force_law", "instantaneous");
    if (law != "instantaneous" && law != "mean_chip") {
      k->fail("<coefficients> force_law must be 'instantaneous' or 'mean_chip'");
    }
    s.mean_law = law == "mean_chip" ? MeanForceLaw::kMeanChip : MeanForceLaw::kInstantaneous;
    s.coeff_source = k->str("source", "cell <coefficients> (no source given)");
  }
  if (const XmlNode* cp = proc.child("coupling")) {
    allowOnly(*cp, {"tolerance_um", "max_iterations", "relaxation", "teeth_between_points",
                    "point_spacing_mm", "compliance_um_per_N", "solver"});
    s.coupling.tolerance = positive(*cp, "tolerance_um", s.coupling.tolerance * 1e6, true) * 1e-6;
    plausible(*cp, "tolerance_um", 1e-4, 100.0, "deflection fixed-point tolerance, um");
    const double it = cp->number("max_iterations", s.coupling.max_iterations);
    if (!(it >= 1 && it <= 10000 && it == std::floor(it)))
      cp->fail("<coupling> max_iterations must be an integer 1..10000");
    s.coupling.max_iterations = static_cast<int>(it);
    s.coupling.relaxation = positive(*cp, "relaxation", 1.0, true);
    if (s.coupling.relaxation > 1) cp->fail("<coupling> relaxation must lie in (0, 1]");
    plausible(*cp, "relaxation", 0.01, 1.0, "under-relaxation of the fixed point");
    const std::string solver = cp->str("solver", "newton");
    if (solver != "newton" && solver != "fixed_point")
      cp->fail("<coupling> solver must be 'newton' or 'fixed_point', got '" + solver + "'");
    s.coupling.method = solver == "newton" ? CouplingMethod::kNewton : CouplingMethod::kFixedPoint;
    if (cp->has("teeth_between_points") && cp->has("point_spacing_mm")) {
      cp->fail("<coupling> give teeth_between_points or point_spacing_mm, not both");
    }
    const double tb = cp->number("teeth_between_points", s.coupling.teeth_between_points);
    if (!(tb >= 1 && tb <= 1e6 && tb == std::floor(tb)))
      cp->fail("<coupling> teeth_between_points must be an integer >= 1");
    s.coupling.teeth_between_points = static_cast<int>(tb);
    s.teeth_between_points_given = cp->has("teeth_between_points") || cp->has("point_spacing_mm");
    if (cp->has("point_spacing_mm")) {
      const double spacing = positive(*cp, "point_spacing_mm", 0, false) * kMm;
      s.coupling.teeth_between_points =
          std::max(1, static_cast<int>(std::lround(spacing / s.cut.fz)));
    }
    if (cp->has("compliance_um_per_N")) {
      const Eigen::VectorXd v = cp->numbers("compliance_um_per_N", 9);
      for (Eigen::Index k = 0; k < v.size(); ++k) {
        if (!(std::abs(v[k]) <= kMaxCouplingCompliance)) {
          cp->fail("<coupling> compliance_um_per_N entry " + std::to_string(k + 1) + " = " +
                   numberText(v[k]) + " is outside the plausible range -" +
                   numberText(kMaxCouplingCompliance) + " .. " +
                   numberText(kMaxCouplingCompliance) +
                   " um/N (1 mm/N is softer than any machining set-up)");
        }
      }
      Mat3 C;
      C << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
      s.compliance = C * 1e-6;
    }
  }
  if (const XmlNode* st = proc.child("stock")) {
    allowOnly(*st, {"top_z_mm", "box_min_mm", "box_max_mm"});
    if (st->has("box_min_mm") != st->has("box_max_mm"))
      st->fail("<stock> a box needs both box_min_mm and box_max_mm");
    if (st->has("box_min_mm")) {
      const Vec3 lo = st->vec3("box_min_mm", Vec3::Zero()) * kMm;
      const Vec3 hi = st->vec3("box_max_mm", Vec3::Zero()) * kMm;
      if (!lo.allFinite() || !hi.allFinite() || !(hi.array() > lo.array()).all())
        st->fail("<stock> box_max_mm must be above box_min_mm in x, y and z");
      s.stock_box_min = lo;
      s.stock_box_max = hi;
      if (st->has("top_z_mm") && std::abs(st->number("top_z_mm") * kMm - hi.z()) > 1e-9)
        st->fail("<stock> top_z_mm differs from the box's top (box_max_mm z): give one");
      s.stock_top_z = hi.z();
    } else {
      if (!st->has("top_z_mm")) st->fail("<stock> needs top_z_mm (or box_min_mm and box_max_mm)");
      const double z = st->number("top_z_mm");
      if (!std::isfinite(z)) st->fail("<stock> top_z_mm must be a number");
      s.stock_top_z = z * kMm;
    }
  }
  if (const XmlNode* dy = proc.child("dynamics")) parseMillingDynamics(*dy, s);
}

void parseMilling(const XmlNode& proc, ProcessSpec& spec) {
  allowChildren(proc, {"mill", "cut", "material", "coefficients", "coupling", "stock", "dynamics"});
  spec.mills = parseToolTable<MillingSpec>(proc, "mill", "cutter geometry", parseMill);
  if (spec.mills.size() > 1 && spec.mills.front().stock_box_min) {
    const XmlNode* st = proc.child("stock");
    st->fail(
        "<stock box_min_mm box_max_mm> with a tool table of several mills is not supported: the "
        "box's engagement follows one cutter diameter; give <stock top_z_mm> (or one <mill>)");
  }
  spec.milling = spec.mills.front();
}

}  // namespace

ProcessSpec parseProcess(const XmlNode& proc) {
  ProcessSpec s;
  s.file = proc.file;
  s.line = proc.line;
  if (proc.name != "process") proc.fail("expected a <process> element, got <" + proc.name + ">");
  const std::string type = proc.str("type");
  if (type == "drilling") {
    allowOnly(proc, {"type"});
    s.type = ProcessType::kDrilling;
    parseDrilling(proc, s);
  } else if (type == "milling") {
    allowOnly(proc, {"type"});
    s.type = ProcessType::kMilling;
    parseMilling(proc, s);
  } else if (type == "wrench") {
    allowOnly(proc, {"type", "force_N", "torque_Nm"});
    allowChildren(proc, {});
    s.type = ProcessType::kWrench;
    if (!proc.has("force_N") && !proc.has("torque_Nm")) {
      proc.fail(
          "<process type=\"wrench\"> needs force_N=\"fx fy fz\" and/or torque_Nm=\"mx my mz\" "
          "(tool frame)");
    }
    s.wrench.force = proc.vec3("force_N", Vec3::Zero());
    s.wrench.torque = proc.vec3("torque_Nm", Vec3::Zero());
  } else {
    proc.fail("unknown process type '" + type + "' (drilling, milling or wrench)");
  }
  return s;
}

DrillingModel drillingModelOf(const DrillingSpec& s, int nodes) {
  return makeDrillingModel(s.geometry, s.coeff, s.law, s.working_angles ? s.feed : 0.0, nodes);
}

MillingModel millingModelOf(const MillingSpec& s, int angle_steps, int slices) {
  MillingModel m = makeMillingModel(s.tool, s.cut, s.coeff, angle_steps, slices);
  m.mean_law = s.mean_law;
  return m;
}

std::string cellWithCalibratedCoefficients(const std::string& cell_text, const std::string& file,
                                           const DrillingCoefficients& c, const std::string& note) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(cell_text.c_str(), cell_text.size()) != tinyxml2::XML_SUCCESS) {
    throw InputError(file, doc.ErrorLineNum(), std::string("malformed XML: ") + doc.ErrorName());
  }
  tinyxml2::XMLElement* root = doc.RootElement();
  tinyxml2::XMLElement* proc = root != nullptr ? root->FirstChildElement("process") : nullptr;
  if (proc == nullptr) throw InputError(file, 0, "the cell has no <process> element");
  tinyxml2::XMLElement* k = proc->FirstChildElement("coefficients");
  if (k == nullptr) {
    k = doc.NewElement("coefficients");
    proc->InsertEndChild(k);
  }
  k->SetAttribute("kst0_N_mm2", cGeneral(c.tangential.k0 / kMPa, 6).c_str());
  k->SetAttribute("ksa0_N_mm2", cGeneral(c.axial.k0 / kMPa, 6).c_str());
  k->SetAttribute("source", note.c_str());
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

}  // namespace roprec
