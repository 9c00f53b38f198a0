// Measured-hole files: the three formats recognised by content, round trips through
// every writer, refusals with FILE:LINE (missing columns, non-numbers, non-finite values,
// duplicates, absurd values, decimal commas), matching to the program's holes and the metres
// refusal.
#include "postproc/measured.hpp"

#include <gtest/gtest.h>

#include <clocale>
#include <cstdio>
#include <functional>
#include <locale>

#include "compensator/support/error.hpp"
#include "tests/support/test_support.hpp"

namespace roprec::postproc {
namespace {

std::string dataFile(const std::string& name) {
  return test::sourceDir() + "/tests/data/measured/" + name;
}

/// Holes with every optional field, coordinates on the 4-decimal grid the writers print.
std::vector<MeasuredHole> sampleHoles() {
  std::vector<MeasuredHole> h(4);
  h[0] = {"T001", Vec3(150.0412, -0.0183, 250.0021), Vec3(0, 0, -1), 2.5, 6.8031, 0};
  h[1] = {"T002", Vec3(144.9301, 38.8049, 250.0011), Vec3(0, 0, -1), std::nullopt, 6.8027, 0};
  h[2] = {"R001", Vec3(-104.9682, -169.9853, 40.0147), Vec3(0, 1, 0), 3.0, std::nullopt, 0};
  h[3] = {"F001",
          Vec3(-175.3553, -105.0001, 154.6449),
          Vec3(0.707106781, 0, -0.707106781),
          1.25,
          12.0012,
          0};
  return h;
}

/// The InputError `f` throws, formatted FILE:LINE: message ("" when it does not throw).
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return formatInputError(e);
  }
  return "";
}

TEST(Measured, EveryFormatRoundTripsThroughItsWriter) {
  const std::vector<MeasuredHole> holes = sampleHoles();
  for (const MeasuredFormat f :
       {MeasuredFormat::kCsv, MeasuredFormat::kPcDmis, MeasuredFormat::kDmis}) {
    SCOPED_TRACE(measuredFormatName(f));
    const std::string text = writeMeasured(holes, f);
    ASSERT_EQ(detectMeasuredFormat(text), f);
    const MeasuredHoles back = parseMeasured(text, "round.trip");
    ASSERT_EQ(back.format, f);
    ASSERT_EQ(back.holes.size(), holes.size());
    for (std::size_t k = 0; k < holes.size(); ++k) {
      const MeasuredHole& a = holes[k];
      const MeasuredHole& b = back.holes[k];
      EXPECT_EQ(a.id, b.id);
      EXPECT_LE((a.p_mm - b.p_mm).cwiseAbs().maxCoeff(), 1e-9) << a.id;
      ASSERT_TRUE(b.axis.has_value()) << a.id;
      EXPECT_LE((*a.axis - *b.axis).norm(), 1e-8) << a.id;
      EXPECT_GT(b.line, 0);
      if (f == MeasuredFormat::kCsv) {
        EXPECT_EQ(a.u_um, b.u_um) << a.id;  // CSV carries u, not the diameter
        EXPECT_FALSE(b.diameter_mm.has_value());
      } else {
        EXPECT_FALSE(b.u_um.has_value());
        ASSERT_EQ(a.diameter_mm.has_value(), b.diameter_mm.has_value()) << a.id;
        if (a.diameter_mm) {
          EXPECT_NEAR(*a.diameter_mm, *b.diameter_mm, 1e-9);
        }
      }
    }
    // writing what was read gives the same bytes
    EXPECT_EQ(writeMeasured(back.holes, f), text);
  }
  // DMIS needs an axis
  std::vector<MeasuredHole> no_axis = holes;
  no_axis[1].axis.reset();
  EXPECT_THROW(writeMeasuredDmis(no_axis), std::invalid_argument);
  // the CSV writer leaves the axis cells of a hole without one empty, and they read back as none
  const MeasuredHoles csv = parseMeasured(writeMeasuredCsv(no_axis), "x.csv");
  EXPECT_FALSE(csv.holes[1].axis.has_value());
  EXPECT_TRUE(csv.holes[2].axis.has_value());
}

TEST(Measured, TheBundledSamplesOfTheThreeFormatsReadTheSameHoles) {
  const MeasuredHoles csv = readMeasured(dataFile("housing_measured.csv"));
  const MeasuredHoles pc = readMeasured(dataFile("housing_pcdmis.csv"));
  const MeasuredHoles dmo = readMeasured(dataFile("housing.dmo"));
  EXPECT_EQ(csv.format, MeasuredFormat::kCsv);
  EXPECT_EQ(pc.format, MeasuredFormat::kPcDmis);
  EXPECT_EQ(dmo.format, MeasuredFormat::kDmis);
  for (const MeasuredHoles* m : {&pc, &dmo}) {
    ASSERT_EQ(m->holes.size(), 3u)
        << measuredFormatName(m->format);  // datum plane / boss / nominals skipped
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(m->holes[k].id, csv.holes[k].id);
      EXPECT_LE((m->holes[k].p_mm - csv.holes[k].p_mm).norm(), 1e-12);
      EXPECT_LE((*m->holes[k].axis - *csv.holes[k].axis).norm(), 1e-12);
    }
  }
  EXPECT_EQ(csv.holes[0].u_um, 2.5);
  EXPECT_FALSE(csv.holes[2].u_um.has_value());
  EXPECT_EQ(pc.holes[0].line, 5);
  EXPECT_EQ(dmo.holes[0].line, 8);  // the FA statement, not the nominal F
  EXPECT_EQ(dmo.holes[1].line, 9);  // first line of a $-continued statement
  EXPECT_NEAR(*dmo.holes[1].diameter_mm, 6.8027, 1e-12);
}

TEST(Measured, FormatIsRecognisedByContentWithUnitsCommentsAndColumnOrder) {
  // columns in another order, upper case, _mm suffixes, extra column, CRLF, comments
  const MeasuredHoles a =
      parseMeasured("# run 1\r\nZ_mm,ID,X_mm,Y_mm,note\r\n\r\n3.5,H1,1,2,ok\r\n", "a.dmo");
  ASSERT_EQ(a.format, MeasuredFormat::kCsv);
  ASSERT_EQ(a.holes.size(), 1u);
  EXPECT_EQ(a.holes[0].p_mm, Vec3(1, 2, 3.5));
  EXPECT_EQ(a.holes[0].line, 4);
  // DMIS in inches, F-only (nominal form) when there are no actuals, lower-case keywords
  const MeasuredHoles d = parseMeasured(
      "units/inch,angdec\nf(H1) = feat/circle,inner,cart,1,2,3,0,0,1,0.25 $$ in\n", "d.txt");
  ASSERT_EQ(d.format, MeasuredFormat::kDmis);
  ASSERT_EQ(d.holes.size(), 1u);
  EXPECT_EQ(d.holes[0].id, "H1");
  EXPECT_LE((d.holes[0].p_mm - Vec3(25.4, 50.8, 76.2)).norm(), 1e-12);
  EXPECT_NEAR(*d.holes[0].diameter_mm, 6.35, 1e-12);
  // quoted PC-DMIS names with commas
  const MeasuredHoles p = parseMeasured("TYPE,NAME,X,Y,Z\nCIRCLE,\"H,1\",1,2,3\n", "p.csv");
  ASSERT_EQ(p.holes.size(), 1u);
  EXPECT_EQ(p.holes[0].id, "H,1");
  EXPECT_EQ(parseMeasured(writeMeasuredCsv(p.holes), "q.csv").holes[0].id, "H,1");
}

/// A C++ locale whose numbers use a decimal comma (iostream parsing would read "1.5" as 1).
struct CommaDecimal : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};

TEST(Measured, NumbersAreReadTheSameUnderACommaDecimalLocale) {
  // the C++ global locale (iostreams) and, where one is installed, the C locale (strtod, printf)
  const std::locale saved_cpp =
      std::locale::global(std::locale(std::locale::classic(), new CommaDecimal));
  const char* old = std::setlocale(LC_NUMERIC, nullptr);
  const std::string saved_c = old ? old : "C";
  const bool c_comma = std::setlocale(LC_NUMERIC, "de_DE.UTF-8") != nullptr ||
                       std::setlocale(LC_NUMERIC, "fr_FR.UTF-8") != nullptr;
  const MeasuredHoles m = parseMeasured("id,x,y,z\nH1,1.5,-2.25,3e2\n", "l.csv");
  const std::string written = writeMeasuredCsv(m.holes);
  std::setlocale(LC_NUMERIC, saved_c.c_str());
  std::locale::global(saved_cpp);
  EXPECT_EQ(m.holes[0].p_mm, Vec3(1.5, -2.25, 300));
  EXPECT_EQ(written, "id,x,y,z\nH1,1.5000,-2.2500,300.0000\n");
  if (!c_comma)
    std::printf("(no comma-decimal C locale installed: checked under the C++ locale only)\n");
}

TEST(Measured, BadFilesAreRefusedWithFileAndLine) {
  struct Case {
    const char* text;
    const char* expect;  // FILE:LINE: start of the message
  };
  const Case cases[] = {
      {"id,x,y\nH1,1,2\n", "bad.csv:1: missing column 'z'"},
      {"# c\nid,x,y,z\nH1,1,2\n", "bad.csv:3: missing value in column 'z'"},
      {"id,x,y,z\nH1,1,2,3\nH2,1,two,3\n", "bad.csv:3: 'two' in column 'y' is not a finite number"},
      {"id,x,y,z\nH1,1,2,inf\n", "bad.csv:2: 'inf' in column 'z' is not a finite number"},
      {"id,x,y,z\nH1,1,2,nan\n", "bad.csv:2: 'nan'"},
      {"id,x,y,z\nH1,1,2,1e999\n", "bad.csv:2: '1e999'"},
      {"id,x,y,z\nH1,1,2,3\nH2,4,5,6\nH1,7,8,9\n",
       "bad.csv:4: duplicate hole id 'H1' (first on line 2)"},
      {"id,x,y,z,i,j\nH1,1,2,3,0,0\n", "bad.csv:1: the axis columns i, j, k"},
      {"id,x,y,z,i,j,k\nH1,1,2,3,0,0,0\n", "bad.csv:2: the measured axis (i, j, k) is zero"},
      {"id,x,y,z,i,j,k\nH1,1,2,3,0,,1\n", "bad.csv:2: the axis cells"},
      {"id,x,y,z,u\nH1,1,2,3,-1\n", "bad.csv:2: the measurement uncertainty"},
      {"id,x,x,z\nH1,1,2,3\n", "bad.csv:1: column 'x' appears twice"},
      {"T001,1,2,3\n", "bad.csv:1: not a measured-hole file"},
      {"", "bad.csv:1: not a measured-hole file"},
      {"TYPE,NAME,X,Y\nCIRCLE,H1,1,2\n", "bad.csv:1: missing column 'Z'"},
      {"TYPE,NAME,X,Y,Z\nCIRCLE,H1,1,2,3,\nCIRCLE,H1,1,2,3\n", "bad.csv:3: duplicate hole id 'H1'"},
      {"UNITS/MM\nFA(H1)=FEAT/CIRCLE,INNER,CART,1,2,x,0,0,1,5\n",
       "bad.csv:2: F(H1): 'x' (z) is not a finite number"},
      {"FA(H1)=FEAT/CIRCLE,INNER,CART,1,2,3\n", "bad.csv:1: F(H1): a hole needs x,y,z,i,j,k"},
      {"FA(H1)=FEAT/CIRCLE,INNER,POL,1,2,3,0,0,1,5\n", "bad.csv:1: F(H1): only CART"},
      {"FA(H1)=FEAT/CIRCLE,INNER,CART,1,2,3,0,0,1,5\nFA(H1)=FEAT/CIRCLE,INNER,CART,1,2,3,0,0,1,5\n",
       "bad.csv:2: duplicate hole id 'H1' (first on line 1)"},
      {"UNITS/FURLONG\nFA(H1)=FEAT/CIRCLE,INNER,CART,1,2,3,0,0,1,5\n",
       "bad.csv:1: unknown DMIS length unit"},
  };
  for (const Case& c : cases) {
    const std::string e = errorOf([&] { (void)parseMeasured(c.text, "bad.csv"); });
    EXPECT_EQ(e.rfind(c.expect, 0), 0u) << "input:\n" << c.text << "\ngot: " << e;
  }
  // a file that does not exist
  EXPECT_EQ(errorOf([] {
              (void)readMeasured("/nonexistent/m.csv");
            }).rfind("/nonexistent/m.csv: cannot open", 0),
            0u);
}

std::vector<ProgramHoleRef> programHoles() {
  return {{"T001", Vec3(150, 0, 250)},
          {"T002", Vec3(144.889, 38.823, 250)},
          {"R001", Vec3(-105, -170, 40)},
          {"R002", Vec3(-75, -170, 40)}};
}

TEST(Measured, MatchingReportsUnknownAndUnmeasuredHoles) {
  const MeasuredHoles m = parseMeasured(
      "id,x,y,z\nT001,150.04,0.01,250\nX999,0,0,0\nR001,-104.97,-169.98,40.01\nT002,144.9,38.8,"
      "250\n",
      "m.csv");
  const MeasuredMatch r = matchMeasured(m, programHoles());
  EXPECT_EQ(r.matched, 3);
  EXPECT_EQ(r.measured_of_program, (std::vector<int>{0, 3, 2, -1}));
  EXPECT_EQ(r.unknown, std::vector<int>{1});
  EXPECT_EQ(r.unmeasured, std::vector<int>{3});
  // nothing matches
  const MeasuredHoles none = parseMeasured("id,x,y,z\nA,1,2,3\n", "none.csv");
  EXPECT_EQ(errorOf([&] {
              (void)matchMeasured(none, programHoles());
            }).rfind("none.csv:2: no measured hole id", 0),
            0u);
}

TEST(Measured, AFileInMetresIsRefusedButASmallPartNearTheOriginIsNot) {
  const MeasuredHoles metres = parseMeasured(
      "# CMM "
      "export\nid,x,y,z\nT001,0.15004,0.00001,0.25\nT002,0.1449,0.0388,0.25\nR001,-0.105,-0.17,0."
      "04\n",
      "m.csv");
  const std::string e = errorOf([&] { (void)matchMeasured(metres, programHoles()); });
  EXPECT_EQ(e.rfind("m.csv:3: the measured positions look like metres", 0), 0u) << e;
  EXPECT_NE(e.find("mm apart"), std::string::npos);
  // a 12 mm part around the workobject origin, measured in mm: accepted
  const std::vector<ProgramHoleRef> small = {{"A", Vec3(-4, -4, 0)}, {"B", Vec3(4, 4, 0)}};
  const MeasuredHoles mm = parseMeasured("id,x,y,z\nA,-3.98,-4.01,0.002\nB,4.02,3.99,0\n", "s.csv");
  EXPECT_EQ(matchMeasured(mm, small).matched, 2);
}

/// The InputError text of parsing `text` as m.csv (or "(accepted)").
std::string parseError(const std::string& text) {
  try {
    (void)parseMeasured(text, "m.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Measured, AbsurdValuesAndADecimalCommaAreRefusedAtTheirLine) {
  EXPECT_EQ(parseError("id,x,y,z\nV01,1,2,3\nV02,1,1e300,3\n")
                .rfind("m.csv:3: hole 'V02': a "
                       "coordinate lies more than 100 m",
                       0),
            0u)
      << parseError("id,x,y,z\nV01,1,2,3\nV02,1,1e300,3\n");
  EXPECT_EQ(parseError("id,x,y,z,u\nV01,1,2,3,1e300\n")
                .rfind("m.csv:2: hole 'V01': the measurement "
                       "uncertainty u is over 10 mm",
                       0),
            0u);
  EXPECT_EQ(parseError("TYPE,NAME,X,Y,Z,D\nCIRCLE,V01,1,2,3,1e300\n")
                .rfind("m.csv:2: hole 'V01': the diameter is over 2 m", 0),
            0u);
  // A decimal comma shifted the row's values (x = -200, y = 2796, z = -199.9, u = 164.7).
  EXPECT_EQ(parseError("id,x,y,z,u\nV02,-200,2796,-199.9475,164.7312,5.0\n")
                .rfind("m.csv:2: 6 cells but the header has 5 (decimal commas?", 0),
            0u);
  // The limits leave real files alone: 100 m and 10 mm are accepted.
  EXPECT_EQ(parseError("id,x,y,z,u\nV01,100000,-100000,0,10000\n"), "(accepted)");
}

}  // namespace
}  // namespace roprec::postproc
