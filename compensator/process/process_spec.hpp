#pragma once
/// \file process_spec.hpp
/// The cell's <process> element turned into typed, SI process parameters. Every bad value
/// throws InputError naming the file and the line of the element that carries it; unknown
/// elements and attributes are rejected (typos do not pass silently). The schema is documented
/// in docs/process.md.
///
///   <process type="drilling">
///     <drill diameter_mm point_angle_deg helix_angle_deg web_mm chisel_angle_deg lips runout_mm
///            tool_material="carbide|hss" stickout_mm flute_length_mm angle_law="geometric|paper"
///            working_angles/>
///     <cut feed_mm_per_rev spindle_rpm depth_mm through/>
///     <material name/>
///     <coefficients kst0_N_mm2 at bt_per_deg ct_per_deg ksa0_N_mm2 aa ba_per_deg ca_per_deg m
///     h_min_mm
///                   chisel_model="ratio|pressure" chisel_thrust_ratio chisel_pressure_ratio
///                   chisel_torque_ratio source/>                                       (optional)
///     <machining_deviation axis_tilt_deg axis_lever_mm runout_mm stickout_mm
///     equivalent_diameter_ratio
///                          youngs_modulus_GPa spindle_compliance_um_per_N k/>          (optional)
///   </process>
///   <process type="milling">
///     <mill tool name diameter_mm teeth helix_angle_deg runout_mm runout_angle_deg>  (one or
///       <cut .../> <tcp .../>                      more; own cut and TCP optional, as a drill's)
///     </mill>
///     <cut ap_mm ae_mm fz_mm mode="up|down|slot" spindle_rpm/>
///     <material name/>
///     <coefficients kc11_N_mm2 mc radial_ratio axial_ratio force_law="instantaneous|mean_chip"
///     source/> <coupling tolerance_um max_iterations relaxation teeth_between_points
///     compliance_um_per_N="9 numbers" solver="newton|fixed_point"/>
///     <stock top_z_mm/>   (optional: the stock's top face z = top_z in the workobject frame;
///                          the cutting decision of docs/process.md §4.5)
///     <dynamics robot_damping_ratio tool_frequency_hz tool_stiffness_N_per_um
///               tool_damping_ratio/>   (optional; defaults are stated estimates, §4.6)
///   </process>
///   <process type="wrench" force_N="fx fy fz" torque_Nm="mx my mz"/>   (on the TCP, tool frame)

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compensator/process/drill_geometry.hpp"
#include "compensator/process/drilling_forces.hpp"
#include "compensator/process/machining_deviation.hpp"
#include "compensator/process/materials.hpp"
#include "compensator/process/milling.hpp"
#include "compensator/process/milling_dynamics.hpp"
#include "compensator/support/xml_node.hpp"

namespace roprec {

enum class ProcessType { kDrilling, kMilling, kWrench };

/// One cell `<machining_deviation>` element: only the values it states (docs/process.md §5.7).
/// Without `diameter_mm` it applies to every hole diameter; with `diameter_mm="8 12"` only to the
/// diameters it names (matched to 1 µm), and then wins over the general elements.
struct MachiningDeviationOverride {
  std::vector<double> diameters;  ///< [m]; empty = every diameter
  std::optional<double> axis_tilt, axis_lever, runout, stickout, equivalent_diameter_ratio,
      youngs_modulus, spindle_compliance;  ///< SI
  std::string source;                      ///< "cell <machining_deviation> line N"
};

struct DrillingSpec {
  std::string tool;  ///< <drill tool>: the controller's tool number or name; empty: not keyed
  std::string name;  ///< <drill name>; empty: none given
  DrillGeometry geometry;
  AngleLaw law{AngleLaw::kGeometric};
  bool working_angles{true};  ///< build the edge angles with the feed (docs/process.md §1.2)
  bool carbide{true};
  double feed{0.2e-3};  ///< f [m/rev]
  double spindle_rpm{3000};
  double hole_depth{0};  ///< [m]; 0 = 2·Dc
  bool through{false};
  const Material* material{nullptr};
  DrillingCoefficients coeff;  ///< material values with the cell's overrides applied
  std::string coeff_source;    ///< "material table" or the <coefficients source=...>
  bool runout_given{false};
  std::optional<double> drill_stickout;  ///< <drill stickout_mm> [m] (the drill's diameter only)
  std::optional<double> drill_flute_length;  ///< <drill flute_length_mm> [m] (its cutting length)
  std::vector<MachiningDeviationOverride> deviation_overrides;  ///< in document order
  MachiningDeviationParams deviation;  ///< machiningDeviationAt(*this, geometry.diameter)
  int line{0};                         ///< <process> line
  int feed_line{0};                    ///< <cut> line (for calibration messages)
  int drill_line{0};                   ///< <drill> line
};

struct MillingSpec {
  std::string tool_key;  ///< <mill tool>: the controller's tool number or name; empty: not keyed
  std::string name;      ///< <mill name>; empty: none given
  MillingTool tool;
  MillingCut cut;
  const Material* material{nullptr};
  MillingCoefficients coeff;
  MeanForceLaw mean_law{MeanForceLaw::kInstantaneous};
  std::string coeff_source;
  CouplingOptions coupling;
  /// <coupling> gives teeth_between_points or point_spacing_mm (else a path takes the tooth
  /// passes between its points from its spacing, milling_compensation.hpp).
  bool teeth_between_points_given{false};
  std::optional<Mat3> compliance;     ///< [m/N] milling frame, from <coupling compliance_um_per_N>
  std::optional<double> stock_top_z;  ///< [m] workobject frame, from <stock top_z_mm>
  /// A box stock (<stock box_min_mm box_max_mm>, workobject frame [m]): the engagement ae/ap per
  /// path point comes from it and the program's earlier passes (milling_engagement.hpp).
  std::optional<Vec3> stock_box_min, stock_box_max;
  double robot_damping_ratio{0.05};  ///< modal damping of the robot modes (<dynamics>)
  ToolModeSpec tool_mode;            ///< spindle/tool mode (<dynamics>)
  std::string dynamics_source{
      "default estimates (robot modes 5 % damping; tool mode 2000 Hz, 20 N/um, 3 %): give "
      "<dynamics> from an impact test"};
  int line{0};
  int mill_line{0};  ///< <mill> line
};

struct WrenchSpec {
  Vec3 force{Vec3::Zero()};   ///< on the TCP, tool frame [N]
  Vec3 torque{Vec3::Zero()};  ///< [N m]
};

/// δmach parameters of a hole of diameter D (m) drilled under this spec: the per-diameter
/// defaults (defaultMachiningDeviation), then — when D is the drill's diameter — the `<drill>`
/// stick-out and runout, then every `<machining_deviation>` without diameters, then those naming D.
/// A stick-out without an explicit runout moves the runout default with it (0.25 µm/mm).
MachiningDeviationParams machiningDeviationAt(const DrillingSpec& s, double diameter);

/// The deepest hole a drill of diameter D can cut, and where that figure comes from.
struct CuttingLength {
  double length{0};  ///< [m]
  std::string source;
};
/// The cutting length of a drill of diameter D (m) under this spec (docs/process.md §5.7): for
/// the drill's own diameter its `<drill flute_length_mm>`, limited by the stick-out at D
/// (machiningDeviationAt: the flutes inside the holder do not cut); otherwise the stick-out at D
/// itself (`<drill stickout_mm>`, `<machining_deviation stickout_mm>`, else the estimate 3 Dc).
CuttingLength cuttingLengthAt(const DrillingSpec& s, double diameter);

struct ProcessSpec {
  ProcessType type{ProcessType::kDrilling};
  std::string file;
  int line{0};
  /// The tool table (drilling): every <drill> in document order with its cut data; one entry for
  /// a single-drill cell. `drilling` is its first entry (the drill of a hole nothing assigns).
  std::vector<DrillingSpec> drills;
  DrillingSpec drilling;
  /// The tool table (milling): every <mill> in document order with its cut data; one entry for a
  /// single-mill cell. `milling` is its first entry.
  std::vector<MillingSpec> mills;
  MillingSpec milling;
  WrenchSpec wrench;
};

/// The drilling spec of one hole: drill `drill` of the tool table (ProcessSpec::drills) at the
/// hole's diameter (m; its web and machining deviation scaled to it when it differs from the
/// drill's), depth (m), feed (m/rev) and spindle speed (1/min); a value <= 0 keeps the drill's.
DrillingSpec holeDrilling(const ProcessSpec& spec, int drill, double diameter, double depth = 0.0,
                          double feed = 0.0, double spindle_rpm = 0.0);

/// Parses a <process> element (file and line numbers come from the node).
ProcessSpec parseProcess(const XmlNode& process);

/// Whether two tool keys name the same tool: equal ignoring case, or the same integer ("3",
/// "03").
bool sameToolKey(std::string_view a, std::string_view b);
/// The index in `s.drills` of the drill keyed `tool` (sameToolKey), -1 when none.
int drillIndex(const ProcessSpec& s, std::string_view tool);
/// The index in `s.mills` of the mill keyed `tool` (sameToolKey), -1 when none.
int millIndex(const ProcessSpec& s, std::string_view tool);
/// A mill as messages name it: `tool 2 'E6' (Ø6 mm, 4 teeth)`, `the cell's mill (Ø10 mm, 3
/// teeth)` for an unkeyed single mill.
std::string millLabel(const MillingSpec& m);
/// A drill as messages and reports name it: `tool 3 'D6.8' (Ø6.8 mm)`, `the cell's drill (Ø8.5
/// mm)` for an unkeyed single drill.
std::string drillLabel(const DrillingSpec& d);
/// The tool-table entry a command that works on the process alone (forces, milling-stability)
/// uses: the drill or mill (ProcessSpec::drills / ::mills, by the process type) keyed `tool`, the
/// single entry when no `tool` is given. Throws UsageError when a table of several has no `tool`
/// (which one?), when none is keyed `tool`, or when a wrench process is given a `tool`.
std::size_t commandToolIndex(const ProcessSpec& s, const std::optional<std::string>& tool);

/// The drilling model of a spec (working angles at the spec's feed when enabled).
DrillingModel drillingModelOf(const DrillingSpec& s, int nodes = 24);
/// The milling model of a spec.
MillingModel millingModelOf(const MillingSpec& s, int angle_steps = 720, int slices = 20);

/// Writes a copy of the cell XML text with the <process>'s <coefficients> replaced by the
/// calibrated kst0/ksa0 (all other content kept). `note` goes into the source attribute.
std::string cellWithCalibratedCoefficients(const std::string& cell_text, const std::string& file,
                                           const DrillingCoefficients& c, const std::string& note);

}  // namespace roprec
