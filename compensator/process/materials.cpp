#include "compensator/process/materials.hpp"

#include <cctype>

#include "compensator/support/rotation.hpp"

namespace roprec {
namespace {

constexpr double kMPa = 1e6;

// Sources (docs/process.md §2.3, §1.5, §4.2).
const char* const kIscarGroup22 =
    "ISCAR catalogue material-group table (ISO 513 / VDI 3323), group 22 'Al wrought, hardenable': "
    "kc1.1 = 800 N/mm2, mc = 0.25, 100 HB (docs.steelcam.org copy)";
const char* const kIscarGroup24 =
    "ISCAR catalogue material-group table, group 24 'Al cast <= 12 % Si, hardenable': kc1.1 = 700 "
    "N/mm2, "
    "mc = 0.25, 90 HB (docs.steelcam.org copy)";
const char* const kIscarGroup23 =
    "ISCAR catalogue material-group table, group 23 'Al cast <= 12 % Si, not hardenable': kc1.1 = "
    "700 N/mm2, "
    "mc = 0.25, 75 HB (docs.steelcam.org copy); AlSi9Cu3 (EN AC-46000) is normally used as-cast "
    "(estimate: mapping to group 23 by Si content and temper)";
const char* const kDrillingSource =
    "docs/process.md §2.3 illustrative calibration [D]: kst0 = ksa0 = kc1.1 of the group, m = mc; "
    "at = 1.0, bt = -0.010/deg (Sandvik 1 %/deg rake rule, sandvik.coromant.com), ct = 0; "
    "aa = 0.80, ba = -0.0185/deg, ca = 0 (Fa/Ft ~ 0.35 at +30 deg, ~0.8 at 0 deg; "
    "estimate: Merchant tan(beta-alpha) with beta 35-40 deg plus ploughing). Re-fit with "
    "--calibrate.";
const char* const kChiselSource =
    "docs/process.md §1.5/§2.3: F_ch = 1.2 Fa_lips, a 55 % chisel share of the thrust for a "
    "conventional point "
    "(chisel 50-60 % of thrust: Modern Machining Technology (Davim 2011) p. 145; 50-70 %: "
    "Mitsubishi "
    "Materials drilling course)";
const char* const kMillingRatioSource =
    "Fr/Ft = 0.35: docs/process.md §4.2 Kienzle column (Altintas Al7075 set gives 0.44-0.63 at h = "
    "0.04-0.10 mm); "
    "Fa/Ft = 0.2: docs/process.md §4.2 '0.1-0.3 for a 30 deg helix' [L] (estimate: mid-range)";

Material wroughtHardenable(std::string name, std::vector<std::string> aliases, double hb) {
  Material m;
  m.name = std::move(name);
  m.aliases = std::move(aliases);
  m.group = "ISCAR 22";
  m.kc11 = 800 * kMPa;
  m.mc = 0.25;
  m.hardness_HB = hb;
  m.kienzle_source = kIscarGroup22;
  return m;
}

void setDrilling(Material& m) {
  const double per_deg = 1.0 / kDeg;
  m.drilling.tangential = SpecificPressure{m.kc11, 1.0, -0.010 * per_deg, 0.0, m.mc, 5e-6};
  m.drilling.axial = SpecificPressure{m.kc11, 0.80, -0.0185 * per_deg, 0.0, m.mc, 5e-6};
  m.drilling.chisel = ChiselModel{ChiselModelKind::kRatio, 1.2, 5.0, 0.0};
  m.milling = MillingCoefficients{m.kc11, m.mc, 0.35, 0.2, 2e-6};
  m.drilling_source = kDrillingSource;
  m.chisel_source = kChiselSource;
  m.milling_ratio_source = kMillingRatioSource;
}

std::vector<Material> buildTable() {
  std::vector<Material> t;
  t.push_back(wroughtHardenable("Al 6061-T6",
                                {"6061-T6", "6061", "AlMg1SiCu", "EN AW-6061-T6", "3.3211"}, 95));
  t.push_back(wroughtHardenable(
      "Al 7075-T6", {"7075-T6", "7075", "AlZn5.5MgCu", "EN AW-7075-T6", "3.4365"}, 150));
  t.push_back(
      wroughtHardenable("Al 2024-T3", {"2024-T3", "2024", "AlCu4Mg1", "EN AW-2024-T3"}, 120));
  {
    Material m;
    m.name = "AlSi7Mg (A356-T6)";
    m.aliases = {"AlSi7Mg", "A356", "A356-T6", "AlSi7Mg0.3", "EN AC-42100", "AlSi7Mg-T6"};
    m.group = "ISCAR 24";
    m.kc11 = 700 * kMPa;
    m.mc = 0.25;
    m.hardness_HB = 90;
    m.kienzle_source = kIscarGroup24;
    t.push_back(m);
  }
  {
    Material m;
    m.name = "AlSi9Cu3";
    m.aliases = {"AlSi9Cu3", "AlSi9Cu3(Fe)", "EN AC-46000", "226"};
    m.group = "ISCAR 23";
    m.kc11 = 700 * kMPa;
    m.mc = 0.25;
    m.hardness_HB = 80;
    m.kienzle_source = kIscarGroup23;
    t.push_back(m);
  }
  {
    Material m;
    m.name = "Al wrought, not hardenable";
    m.aliases = {"1050", "5083", "AlMg4.5Mn", "3003", "Al99.5"};
    m.group = "ISCAR 21";
    m.kc11 = 700 * kMPa;
    m.mc = 0.25;
    m.hardness_HB = 60;
    m.kienzle_source =
        "ISCAR catalogue material-group table, group 21 'Al wrought, not hardenable': kc1.1 = 700 "
        "N/mm2, "
        "mc = 0.25, 60 HB (docs.steelcam.org copy)";
    t.push_back(m);
  }
  for (Material& m : t) setDrilling(m);
  return t;
}

std::string key(const std::string& s) {
  std::string k;
  for (char ch : s) {
    if (ch == ' ' || ch == '-' || ch == '_') continue;
    k.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(ch))));
  }
  return k;
}

}  // namespace

const std::vector<Material>& materialTable() {
  static const std::vector<Material> table = buildTable();
  return table;
}

const Material* findMaterial(const std::string& name) {
  const std::string k = key(name);
  for (const Material& m : materialTable()) {
    if (key(m.name) == k) return &m;
    for (const std::string& a : m.aliases) {
      if (key(a) == k) return &m;
    }
  }
  return nullptr;
}

std::string materialNames() {
  std::string s;
  for (const Material& m : materialTable()) {
    if (!s.empty()) s += ", ";
    s += m.name;
  }
  return s;
}

}  // namespace roprec
