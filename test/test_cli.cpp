// The command-line tools (finger_model, finger_calibrate, finger_urdf), run as a user would: header, digits, exit
// codes, and what goes to stdout and stderr.
#include <gtest/gtest.h>

#include <algorithm>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/core/parameters.hpp"

namespace pf = pneumatic_finger;

namespace {

struct CliRun {
  int status;
  std::string out, err;
};

// Runs a shell command: exit status, stdout and stderr apart.
CliRun runShell(const std::string& command) {
  const std::string err_file = testing::TempDir() + "/cli_stderr.txt";
  const std::string cmd = command + " 2>" + err_file;
  FILE* pipe = popen(cmd.c_str(), "r");
  CliRun r{-1, "", ""};
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream e(err_file);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  return r;
}

CliRun run(const std::string& args) { return runShell(std::string(FINGER_MODEL_EXE) + " " + args); }

// finger_model refuses @p args: exit 2, and its error names @p words.
void expectRefused(const std::string& args, const std::string& words) {
  const CliRun r = run(args);
  EXPECT_EQ(r.status, 2) << "finger_model " << args;
  EXPECT_NE(r.err.find(words), std::string::npos) << "finger_model " << args << ": " << r.err;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string line;
  while (std::getline(ss, line)) out.push_back(line);
  return out;
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

// finger_model's CSV lines for @p rows, without and with @p option (header and one line per pressure each), or
// false with the failure recorded.
bool rowsWithAndWithout(const std::string& rows, const std::string& option, std::vector<std::string>& without,
                        std::vector<std::string>& with) {
  const CliRun a = run(rows), b = run(rows + " " + option);
  EXPECT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(b.status, 0) << b.err;
  without = lines(a.out);
  with = lines(b.out);
  EXPECT_EQ(with.size(), without.size());
  return a.status == 0 && b.status == 0 && with.size() == without.size() && with.size() >= 2;
}

}  // namespace

TEST(Cli, HeaderAndOneRowPerPressure) {
  const CliRun r = run("--gauge-pa 0 --gauge-pa 98066.5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto l = lines(r.out);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[0],
            "gauge_pa,stretch,bulge_m,half_angle_rad,joint_1_rad,joint_2_rad,joint_3_rad,joint_4_rad,joint_5_rad,"
            "joint_6_rad,joint_7_rad,tip_x_m,tip_y_m,supplied_volume_m3");
  EXPECT_EQ(fields(l[1]).size(), 14u);
  // At rest: the straight finger, 15 mm + 7 x 10 mm long.
  EXPECT_EQ(fields(l[1])[1], "1");
  EXPECT_DOUBLE_EQ(std::stod(fields(l[1])[11]), 0.085);
  EXPECT_EQ(fields(l[1])[12], "0");
  EXPECT_EQ(r.err, "");
}

// --chord-angle: the line from the base to the printed tip, after tip_y_m, by pressure and by volume; at these bends
// (well under a half turn) it is the tip's own atan2.
TEST(Cli, ChordAngleIsTheLineFromTheBaseToThePrintedTip) {
  for (const std::string input : {"--gauge-pa 0 --gauge-pa 98066.5 --gauge-pa 196133", "--supplied-volume-m3 2e-6"}) {
    const CliRun r = run(input + " --chord-angle");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto l = lines(r.out);
    EXPECT_EQ(fields(l[0])[13], "chord_angle_rad");
    EXPECT_EQ(fields(l[0])[14], "supplied_volume_m3");
    for (std::size_t i = 1; i < l.size(); ++i) {
      const auto f = fields(l[i]);
      ASSERT_EQ(f.size(), 15u) << l[i];
      EXPECT_NEAR(std::stod(f[13]), std::atan2(std::stod(f[12]), std::stod(f[11])), 1e-15) << l[i];
    }
    EXPECT_GT(std::stod(fields(l.back())[13]), 0.1) << r.out;  // bent: a chord worth checking
  }
}

TEST(Cli, NumbersHaveSeventeenSignificantDigitsAndRoundTrip) {
  const CliRun r = run("--gauge-pa 150000");
  ASSERT_EQ(r.status, 0);
  const auto f = fields(lines(r.out)[1]);
  const std::string theta = f[3];
  std::string digits;
  for (char c : theta.substr(0, theta.find('e'))) {
    if (isdigit(static_cast<unsigned char>(c))) digits += c;
  }
  EXPECT_EQ(digits.substr(digits.find_first_not_of('0')).size(), 17u) << theta;
  EXPECT_GT(std::stod(theta), 0.0);
}

TEST(Cli, ColumnsFollowChamberCountAndSweep) {
  const CliRun r = run("--set chamber_count=3 --sweep-pa 0:2e5:5");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto l = lines(r.out);
  ASSERT_EQ(l.size(), 6u);
  EXPECT_EQ(l[0], "gauge_pa,stretch,bulge_m,half_angle_rad,joint_1_rad,joint_2_rad,joint_3_rad,tip_x_m,tip_y_m,"
                  "supplied_volume_m3");
  EXPECT_EQ(fields(l[5])[0], "200000");
  EXPECT_EQ(fields(l[3])[0], "100000");
}

TEST(Cli, SolversAgreeOnTheValidatedRange) {
  const CliRun robust = run("--gauge-pa 196133");
  const CliRun paper = run("--solver paper --gauge-pa 196133");
  const CliRun table = run("--solver table --gauge-pa 196133");
  ASSERT_EQ(paper.status, 0);
  ASSERT_EQ(table.status, 0);
  const double t = std::stod(fields(lines(robust.out)[1])[3]);
  EXPECT_NEAR(std::stod(fields(lines(paper.out)[1])[3]), t, 1e-13);
  EXPECT_NEAR(std::stod(fields(lines(table.out)[1])[3]), t, 1e-12);
}

TEST(Cli, BadInputExitsTwoWithOneLineNamingItAndNoStdout) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--gauge-pa nan", "--gauge-pa"},
      {"--gauge-pa inf", "--gauge-pa"},
      {"--gauge-pa -inf", "--gauge-pa"},
      {"--gauge-pa 1e5 --gauge-pa abc", "'abc'"},
      {"--set chamber_gapp_m=1 --gauge-pa 1", "chamber_gapp_m"},
      {"--set chamber_gap_m=-1 --gauge-pa 1", "chamber_gap_m"},
      {"--set chamber_count=2.5 --gauge-pa 1", "chamber_count"},
      {"--set wall_critical_height_m=0.5 --gauge-pa 1", "wall_critical_height_m"},
      {"--solver quick --gauge-pa 1", "quick"},
      {"--config /nonexistent.yaml --gauge-pa 1", "/nonexistent.yaml"},
      {"--sweep-pa 0:1", "FROM:TO:COUNT"},
      {"--sweep-pa 0:1:0", "COUNT"},
      {"", "no pressure"},
      {"--frobnicate", "--frobnicate"},
  };
  for (const auto& c : cases) {
    const CliRun r = run(c.first);
    EXPECT_EQ(r.status, 2) << c.first;
    EXPECT_EQ(r.out, "") << c.first;
    EXPECT_EQ(lines(r.err).size(), 1u) << c.first << ": " << r.err;
    EXPECT_NE(r.err.find(c.second), std::string::npos) << c.first << ": " << r.err;
  }
}

TEST(Cli, AnObstacleDiskHoldsTheFingerWhereItTouches) {
  // A disk in front of the tip's path: below the touch the free finger, above it the same held shape.
  std::vector<std::string> f, h;
  ASSERT_TRUE(rowsWithAndWithout("--gauge-pa 98066.5 --gauge-pa 196133", "--obstacle-disk 0.075,0.035,0.01", f, h));
  EXPECT_EQ(h[1], f[1]) << "not yet touching: the free finger";
  EXPECT_NE(h[2], f[2]) << "touching: held";
  EXPECT_LT(std::stod(fields(h[2])[10]), std::stod(fields(f[2])[10])) << "joint 7 held below its free angle";
  expectRefused("--gauge-pa 1 --obstacle-disk 0.07,0.03,-1", "radius");
  expectRefused("--gauge-pa 1 --obstacle-disk 0.07,0.03", "X,Y,R");
}

// The time mode (eq 4): a constant flow fills the finger; the pressure of each row is P_o Q t / V_o with V_o the
// sum of the chambers' L d e, computed here from config/finger.yaml's numbers, and the rest of the row is the
// pressure mode's row for that pressure.
TEST(Cli, TimeModeFillsAtTheIdealSpringRate) {
  const CliRun r = run("--flow-lpm 0.5 --duration-s 1 --step-s 0.25");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 6u);  // header, t = 0, 0.25, 0.5, 0.75, 1
  EXPECT_EQ(rows[0].rfind("time_s,gauge_pa,stretch,", 0), 0u) << rows[0];
  EXPECT_NE(r.err.find("is above max_gauge_pa 294199.5 Pa, the top of the model's range: clamped to it"),
            std::string::npos) << r.err;
  const std::string yaml = readFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml");
  auto value = [&](const std::string& key) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(yaml, m, std::regex("\\n" + key + ": ([0-9.eE+-]+)"))) << key;
    return std::stod(m[1]);
  };
  const double volume = value("chamber_count") * value("chamber_height_m") * value("chamber_thickness_m") * value("chamber_width_m");
  const double rate = value("atmospheric_pressure_pa") * (0.5e-3 / 60.0) / volume;
  for (int k = 0; k <= 4; ++k) {
    const auto f = fields(rows[static_cast<std::size_t>(k + 1)]);
    EXPECT_EQ(std::stod(f[0]), 0.25 * k);
    // The fill passes the model's range at the end: that row is the finger at max_gauge_pa, as the node gives it.
    EXPECT_NEAR(std::stod(f[1]), std::min(rate * 0.25 * k, 294199.5), 1e-9 * rate) << "t = " << 0.25 * k;
    const auto same = lines(run("--gauge-pa " + f[1]).out);
    EXPECT_EQ(rows[static_cast<std::size_t>(k + 1)], f[0] + "," + same[1]) << "t = " << 0.25 * k;
  }
  EXPECT_EQ(run("--flow-lpm 0.5 --duration-s 1").status, 2);
  EXPECT_EQ(run("--flow-lpm -1 --duration-s 1 --step-s 0.1").status, 2);
  EXPECT_EQ(run("--flow-lpm 1 --duration-s 1 --step-s 0.1 --gauge-pa 5").status, 2);
}

TEST(Cli, VacuumWarnsAndPrintsTheStraightFinger) {
  const CliRun r = run("--gauge-pa -20000");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.err.find("warning"), std::string::npos);
  EXPECT_NE(r.err.find("vacuum"), std::string::npos);
  const auto f = fields(lines(r.out)[1]);
  EXPECT_EQ(f[0], "-20000");
  for (int j = 4; j <= 10; ++j) EXPECT_EQ(f[static_cast<std::size_t>(j)], "0");
  EXPECT_EQ(f[12], "0");
}

TEST(Cli, ParameterTableListsEveryKey) {
  const CliRun r = run("--parameters");
  ASSERT_EQ(r.status, 0);
  for (const char* key : {"chamber_count", "chamber_gap_m", "shear_modulus_pa", "atmospheric_pressure_pa"}) {
    EXPECT_NE(r.out.find(std::string("`") + key + "`"), std::string::npos) << key;
  }
}

// --pressures prints the model's own pressures, under Python's names: the EPFL fit with 5 mm walls, whose wall does
// not fold (its limit point inf, its snap where it is softest), and with 3 mm walls, which folds (snap = limit).
TEST(Cli, PressuresAreTheModelsOwnUnderPythonsNames) {
  const std::string config = std::string(PACKAGE_SOURCE_DIR) + "/config/epfl_ecoflex30_c7.yaml";
  for (const char* wall : {"0.005", "0.003"}) {
    const CliRun r = run("--config " + config + " --set drawing/wall_thickness_m=" + wall + " --pressures");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> out = lines(r.out);
    ASSERT_EQ(out.size(), 2u) << r.out;
    EXPECT_EQ(out[0], "contact_gauge_pa,snap_gauge_pa,limit_gauge_pa,far_turning_gauge_pa");
    pf::RawParameterMap raw;
    pf::loadRawParametersFromYamlFile(config, raw);
    raw["drawing/wall_thickness_m"] = {{std::stod(wall)}, false};
    const pf::FingerModel model(pf::FingerParameters::fromRaw(raw));
    EXPECT_EQ(out[1], pf::formatExact(model.contactGaugePa()) + ',' + pf::formatExact(model.snapGaugePa()) + ',' +
                          pf::formatExact(model.limitGaugePa()) + ',' + pf::formatExact(model.farTurningGaugePa()));
    const std::vector<std::string> f = fields(out[1]);
    EXPECT_EQ(f[2] == "inf", std::string(wall) == "0.005") << r.out;  // 5 mm: no fold; 3 mm: a limit point
    EXPECT_GT(std::stod(f[1]), std::stod(f[0]));                     // it snaps after its walls touch
  }
}

TEST(CalibrateCli, PrintsTableTwoAndWritesTheParameterFile) {
  const std::string out_file = testing::TempDir() + "/calibrated.yaml";
  const CliRun r = runShell(std::string(FINGER_CALIBRATE_EXE) + " --output " + out_file);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("# compared: joints; objective: minimax"), std::string::npos) << r.out;
  // In the data's units: Pa, rad and m.
  EXPECT_NE(r.out.find("gauge_pa  joint_1  joint_2  joint_3  joint_4  joint_5  joint_6  joint_7  avg_2..7 tip_angle    tip_m"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("# leave-one-out error"), std::string::npos);
  // The chambers' fit on the paper's own measure is unchanged by joint 1's parameter (fitted after it, to joint 1).
  EXPECT_NE(r.out.find("joints 2..7 average 0.00928543 rad (0.532 deg) (the paper's own model on these data: 0.647 deg)"),
            std::string::npos) << r.out;
  // The written file is the shipped one, byte for byte: config/finger.yaml is reproducible.
  EXPECT_EQ(readFile(out_file), readFile(std::string(PACKAGE_SOURCE_DIR) + "/config/finger.yaml"));
}

// The calibrated file carries the range it was calibrated on, and every reader takes it;
// the node's own keys (volume_topic) in the same file are accepted by the tools. The reference is the data: its
// highest pressure. Before: the validated range was the paper finger's 196133 Pa whatever the data, and a file with
// volume_topic was refused as "unknown parameter".
TEST(CalibrateCli, TheFileCarriesTheCalibratedRangeAndTheNodesKeys) {
  const std::string root = PACKAGE_SOURCE_DIR;
  const std::string data = testing::TempDir() + "/three_rows.csv", out_file = testing::TempDir() + "/three.yaml";
  ASSERT_EQ(runShell("grep -v '^#' " + root + "/data/sierra2022_table1.csv | head -4 > " + data).status, 0);
  const CliRun fit = runShell(std::string(FINGER_CALIBRATE_EXE) + " --data " + data +
                              " --fit shear_modulus_pa --output " + out_file);
  ASSERT_EQ(fit.status, 0) << fit.err;
  EXPECT_NE(readFile(out_file).find("\nvalidated_max_gauge_pa: 147099.75\n"), std::string::npos) << readFile(out_file);
  const CliRun above = run("--config " + out_file + " --gauge-pa 150000");
  ASSERT_EQ(above.status, 0) << above.err;
  EXPECT_NE(above.err.find("gauge pressure 150000 Pa is above the validated range (0 to 147099.75 Pa)"),
            std::string::npos)
      << above.err;
  const std::string with_node_keys = testing::TempDir() + "/node_keys.yaml";
  ASSERT_EQ(runShell("cp " + out_file + " " + with_node_keys + " && printf 'volume_topic: volume\\npressure_topic: p\\n'"
                     " >> " + with_node_keys).status, 0);
  const CliRun node_keys = run("--config " + with_node_keys + " --gauge-pa 1000");
  EXPECT_EQ(node_keys.status, 0) << node_keys.err;
  const CliRun inverted = run("--config " + out_file + " --set chamber_count=7 --gauge-pa 1000");
  EXPECT_EQ(inverted.status, 0) << inverted.err;
  const std::string bad = testing::TempDir() + "/bad_range.yaml";
  ASSERT_EQ(runShell("printf 'max_gauge_pa: 1.0e+05\\nvalidated_max_gauge_pa: 2.0e+05\\n' > " + bad).status, 0);
  const CliRun refused = run("--config " + bad + " --gauge-pa 1000");
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("validated_max_gauge_pa = 200000 Pa is above max_gauge_pa = 100000 Pa"), std::string::npos)
      << refused.err;
}

TEST(Cli, PressuresBeyondTheLimitPointAreNanRowsWithAWarning) {
  const std::string ribbed = std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml";
  const CliRun r = run("--config " + ribbed + " --gauge-pa 10000 --gauge-pa 40000 --gauge-pa 1e6");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("limit point"), std::string::npos) << r.err;
  std::istringstream lines(r.out);
  std::string header, below, beyond;
  std::getline(lines, header);
  std::getline(lines, below);
  std::getline(lines, beyond);
  EXPECT_EQ(below.find("nan"), std::string::npos) << below;
  EXPECT_EQ(beyond.find("40000,nan,nan"), 0u) << beyond;
}

TEST(CalibrateCli, WallLawAutoKeepsTheBetterPredictionAndWritesIt) {
  // The ribbed segment of Marchese 2015, the same two keys for every law (named, so each law is fitted once).
  const std::string out_file = testing::TempDir() + "/ribbed.yaml";
  const std::string root = PACKAGE_SOURCE_DIR;
  const CliRun r = runShell(std::string(FINGER_CALIBRATE_EXE) + " --config " + root +
                            "/config/marchese2015_ribbed.yaml --data " + root +
                            "/data/marchese2015_ribbed_bending.csv --fit shear_modulus_pa,chamber_gap_m "
                            "--wall-law auto --output " + out_file);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("#   paper: 2 fitted"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("it starts from its uniform wall, b = L/2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("<- chosen"), std::string::npos) << r.out;
  EXPECT_LT(r.out.find("#   paper"), r.out.find("#   membrane"));
  EXPECT_NE(r.out.find("deg)  <- chosen"), std::string::npos);
  EXPECT_GT(r.out.find("<- chosen"), r.out.find("#   membrane")) << "the membrane law predicts the ribbed segment better";
  EXPECT_NE(readFile(out_file).find("\nwall_law: membrane\n"), std::string::npos);
  const CliRun bad = runShell(std::string(FINGER_CALIBRATE_EXE) + " --wall-law balloon");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("unknown wall law 'balloon'"), std::string::npos) << bad.err;
}

TEST(CalibrateCli, MalformedDataExitsTwoNamingTheLine) {
  const std::string bad = testing::TempDir() + "/bad.csv";
  std::ofstream(bad) << "gauge_pa,joint_1_rad,joint_2_rad\n1e5,0.1,oops\n";
  const CliRun r = runShell(std::string(FINGER_CALIBRATE_EXE) + " --data " + bad);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad.csv:2: 'oops' in column joint_2_rad"), std::string::npos) << r.err;
}

TEST(UrdfCli, GeneratedUrdfPassesCheckUrdfWithPrefixedNames) {
  const std::string file = testing::TempDir() + "/finger.urdf";
  const std::string gen = std::string(FINGER_URDF_EXE) + " --prefix finger_b_ --parent flange --xyz 0,0.02,0.01 --rpy 0,0,2.0944 -o " + file;
  ASSERT_EQ(std::system(gen.c_str()), 0);
  const CliRun check = runShell("check_urdf " + file);
  ASSERT_EQ(check.status, 0) << check.out << check.err;
  const std::string& out = check.out;
  EXPECT_NE(out.find("Successfully Parsed XML"), std::string::npos) << out;
  EXPECT_NE(out.find("root Link: flange"), std::string::npos) << out;
  for (const char* link : {"finger_b_segment_0", "finger_b_segment_7", "finger_b_tip"}) {
    EXPECT_NE(out.find(link), std::string::npos) << link;
  }
  // The joints: revolute about +z, named like joint_states, with limits from the model.
  const std::string xml = readFile(file);
  EXPECT_NE(xml.find("<joint name=\"finger_b_joint_7\" type=\"revolute\">"), std::string::npos);
  EXPECT_NE(xml.find("<axis xyz=\"0 0 1\""), std::string::npos);
  EXPECT_EQ(xml.find("<mesh"), std::string::npos);  // simple shapes only
}

TEST(UrdfCli, TheComposedRobotPassesCheckUrdfAsOneTree) {
  const std::string file = testing::TempDir() + "/composed.urdf";
  const std::string gen = std::string(FINGER_URDF_EXE) + " --robot " + PACKAGE_SOURCE_DIR +
                          "/urdf/industrial_arm.urdf --gripper " + PACKAGE_SOURCE_DIR + "/config/gripper.yaml -o " + file;
  ASSERT_EQ(std::system(gen.c_str()), 0);
  const CliRun check = runShell("check_urdf " + file);
  ASSERT_EQ(check.status, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("root Link: world"), std::string::npos) << check.out;
  for (const char* link : {"gripper_plate", "finger_a_tip", "finger_b_tip", "finger_c_tip"}) {
    EXPECT_NE(check.out.find(link), std::string::npos) << link;
  }
  // A bad gripper file: exit 2, one line naming the problem.
  const std::string bad = testing::TempDir() + "/bad_gripper.yaml";
  std::ofstream(bad) << "fingers:\n  - {prefix: x_, parent: flange}\n";
  const CliRun refused = runShell(std::string(FINGER_URDF_EXE) + " --robot " + PACKAGE_SOURCE_DIR +
                                  "/urdf/industrial_arm.urdf --gripper " + bad);
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("no link 'flange'"), std::string::npos) << refused.err;
}

TEST(UrdfCli, InvalidPrefixIsRefused) {
  const std::string cmd = std::string(FINGER_URDF_EXE) + " --prefix 'bad name' >/dev/null 2>&1";
  const int raw = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(raw), 2);
}

TEST(Cli, EveryKeyOutOfRangeIsRefusedByBothToolsNamingIt) {
  ASSERT_GE(pf::parameterSpecs().size(), 12u);
  for (const pf::ParameterSpec& spec : pf::parameterSpecs()) {
    const std::string key = spec.key;
    const CliRun model = run("--set " + key + "=-7 --gauge-pa 1e5");
    EXPECT_EQ(model.status, 2) << key;
    EXPECT_EQ(model.out, "") << key;
    EXPECT_NE(model.err.find(key), std::string::npos) << model.err;
    const CliRun calibrate = runShell(std::string(FINGER_CALIBRATE_EXE) + " --set " + key + "=-7");
    EXPECT_EQ(calibrate.status, 2) << key;
    EXPECT_EQ(calibrate.out, "") << key;
    EXPECT_NE(calibrate.err.find(key), std::string::npos) << calibrate.err;
  }
}

// A figure in a document is produced by a command, never left as a template's placeholder such as "{cpu}".
namespace {
std::vector<std::string> placeholders(const std::string& text) {
  std::vector<std::string> found;
  const std::regex placeholder(R"(\{[a-z_]+\})");
  for (std::sregex_iterator it(text.begin(), text.end(), placeholder), end; it != end; ++it) found.push_back(it->str());
  return found;
}
}  // namespace

TEST(Docs, NoPlaceholderIsLeftInTheReadmeOrDocs) {
  // The check itself catches one (else it could not fail).
  ASSERT_EQ(placeholders("CPU: {cpu} of one core, {x: 1}"), std::vector<std::string>{"{cpu}"});
  std::vector<std::string> pages = {"README.md"};
  for (const auto& entry : std::filesystem::directory_iterator(std::string(PACKAGE_SOURCE_DIR) + "/docs")) {
    if (entry.path().extension() == ".md") pages.push_back("docs/" + entry.path().filename().string());
  }
  ASSERT_GE(pages.size(), 4u);
  for (const auto& page : pages) {
    EXPECT_EQ(placeholders(readFile(std::string(PACKAGE_SOURCE_DIR) + "/" + page)), std::vector<std::string>{})
        << page << " has a placeholder where a measured figure belongs";
  }
}

// --blocked-tip-force: one more column, last, with the library's number bit for bit (the model's own test checks the
// number against the reference), 0 before contact; the shape columns are unchanged.
TEST(Cli, BlockedTipForceIsTheLastColumnAndTheLibrarysNumber) {
  std::vector<std::string> lp, l;
  ASSERT_TRUE(rowsWithAndWithout("--gauge-pa 0 --gauge-pa 196133", "--blocked-tip-force", lp, l));
  EXPECT_EQ(l[0], lp[0] + ",blocked_tip_force_n");
  const pneumatic_finger::FingerModel model(pneumatic_finger::FingerParameters::defaults());
  EXPECT_EQ(l[1], lp[1] + ",0");
  EXPECT_EQ(l[2], lp[2] + "," + pneumatic_finger::formatExact(model.blockedTipForceN(196133)));
  EXPECT_GT(model.blockedTipForceN(196133), 0.1);
}

// Volume as the input (docs/MODEL.md, Volume): a pressure's supplied volume, given back, gives that pressure; under
// the membrane law a volume past the limit point gives a bent finger at a pressure below the limit, where
// --gauge-pa has no shape.
TEST(Cli, VolumeInputAnswersThePressureAndPassesTheLimitPoint) {
  const std::string membrane = "--set wall_law=membrane --set shear_modulus_pa=2e4 --set dead_volume_m3=1e-5 ";
  const CliRun by_pressure = run(membrane + "--gauge-pa 3000");
  ASSERT_EQ(by_pressure.status, 0) << by_pressure.err;
  const auto row = fields(lines(by_pressure.out)[1]);
  const std::string volume = row[13];
  const CliRun by_volume = run(membrane + "--supplied-volume-m3 " + volume);
  ASSERT_EQ(by_volume.status, 0) << by_volume.err;
  const auto back = fields(lines(by_volume.out)[1]);
  EXPECT_NEAR(std::stod(back[0]), 3000.0, 3000.0 * 1e-12);
  EXPECT_EQ(back[13], volume);
  // The model: its limit point and a volume well past it.
  const pf::FingerModel model(pf::FingerParameters::fromRaw(
      {{"wall_law", {{1.0}, false}}, {"shear_modulus_pa", {{2e4}, false}}, {"dead_volume_m3", {{1e-5}, false}}}));
  pf::FingerWorkspace ws(model);
  const double limit_volume = model.suppliedVolumeAt(model.belowLimitGaugePa());
  const CliRun past = run(membrane + "--supplied-volume-m3 " + pf::formatExact(3.0 * limit_volume));
  ASSERT_EQ(past.status, 0) << past.err;
  const auto p = fields(lines(past.out)[1]);
  const pf::FingerState& s = model.evaluateVolume(3.0 * limit_volume, ws);
  EXPECT_EQ(p[0], pf::formatExact(s.gauge_pa));
  EXPECT_LT(std::stod(p[0]), model.limitGaugePa()) << "past the limit point the pressure has fallen";
  EXPECT_EQ(p[10], pf::formatExact(s.joint_angle_rad[6]));
  // Three times the limit point's volume curls this soft segment past a full turn (13.1 rad): said, once.
  EXPECT_EQ(past.err.rfind("finger_model: warning: at " + pf::formatMessage(s.gauge_pa) +
                               " Pa gauge the finger meets itself (tip angle 13.1",
                           0),
            0u)
      << past.err;
}

TEST(Cli, VolumeInputRefusesWhatItCannotModel) {
  expectRefused("--supplied-volume-m3 nan", "--supplied-volume-m3");
  expectRefused("--supplied-volume-m3 1e-6 --gauge-pa 1000", "give one input");
  expectRefused("--supplied-volume-m3 1e-6 --blocked-tip-force", "changes its volume, which is not modelled");
  // A volume above the one that makes max_gauge_pa is clamped there, with the pressure's words:
  // the row is the finger at max_gauge_pa (before: an absurd pressure for 1 m^3, exit 0, no warning).
  const CliRun clamp = run("--supplied-volume-m3 1.0 --max-gauge-pa 1e5");
  ASSERT_EQ(clamp.status, 0) << clamp.err;
  EXPECT_NEAR(std::stod(fields(lines(clamp.out)[1])[0]), 1e5, 1e-4) << clamp.out;
  EXPECT_NE(clamp.err.find("warning: supplied volume 1 m^3 is above"), std::string::npos) << clamp.err;
  EXPECT_NE(clamp.err.find("the volume that makes max_gauge_pa 100000 Pa (the top of the model's range): clamped to "
                           "it"),
            std::string::npos)
      << clamp.err;
  // Drawn out of an incompressible fluid: the straight finger at absolute zero (the liquid cavitates), with a warning.
  const CliRun drawn = run("--supplied-volume-m3 -1e-6");
  ASSERT_EQ(drawn.status, 0) << drawn.err;
  EXPECT_EQ(fields(lines(drawn.out)[1])[0], "-101325");
  EXPECT_NE(drawn.err.find("draws fluid out"), std::string::npos) << drawn.err;
}

// Volume as the input closing on a disk: the row's pressure is gaugeForVolumeInContact's, its joints the contact
// rule's there, and its volume column the volume given; more than the finger takes on the disk is a nan row.
TEST(Cli, VolumeInputClosesOnAnObstacleDisk) {
  const pf::FingerModel model(pf::FingerParameters::fromRaw({{"dead_volume_m3", {{2e-5}, false}}}));
  pf::ContactTracker tracker(model, pf::Obstacle::disk(0.075, 0.035, 0.01));
  const double top = 294199.5, most = pf::suppliedVolumeInContact(model, tracker.solve(top), top);
  double gauge = 0.0;
  std::string why;
  ASSERT_TRUE(pf::gaugeForVolumeInContact(model, [&](double p) { return tracker.solve(p); }, 0.8 * most, top, gauge,
                                          why))
      << why;
  const pf::ContactState c = tracker.solve(gauge);
  ASSERT_EQ(c.status, pf::ContactState::Status::kInContact);
  const std::string args = "--set dead_volume_m3=2e-5 --obstacle-disk 0.075,0.035,0.01 --supplied-volume-m3 ";
  const CliRun held = run(args + pf::formatExact(0.8 * most) + " --supplied-volume-m3 " + pf::formatExact(1.1 * most));
  ASSERT_EQ(held.status, 0) << held.err;
  const auto row = fields(lines(held.out)[1]);
  EXPECT_EQ(row[0], pf::formatExact(gauge));
  EXPECT_EQ(row[10], pf::formatExact(c.joint_angle_rad[6]));
  EXPECT_EQ(row[13], pf::formatExact(0.8 * most));
  EXPECT_EQ(fields(lines(held.out)[2])[0], "nan");
  EXPECT_NE(held.err.find("is more than the finger takes on the object"), std::string::npos) << held.err;
}

// finger_urdf --mjcf: a MuJoCo model whose joints carry the twin's springs at --gauge-pa (test_simulator loads and
// steps it); refusals name the option.
TEST(UrdfCli, MjcfCarriesTheSpringsOfItsPressure) {
  const CliRun r = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --gauge-pa 98066.5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("<mujoco model=\"finger_pneumatic_finger\">"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("<compiler angle=\"radian\"/>"), std::string::npos) << "MJCF angles are degrees otherwise";
  const pf::FingerModel model(pf::FingerParameters::defaults());
  std::vector<double> q(7);
  ASSERT_TRUE(model.jointAnglesAt(98066.5, q.data()));
  EXPECT_NE(r.out.find("springref=\"" + pf::formatShortest(q[3]) + "\""), std::string::npos) << r.out;
  const CliRun no_mjcf = runShell(std::string(FINGER_URDF_EXE) + " --gauge-pa 1000");
  EXPECT_EQ(no_mjcf.status, 2);
  EXPECT_NE(no_mjcf.err.find("--gauge-pa needs --mjcf"), std::string::npos) << no_mjcf.err;
  const std::string root = PACKAGE_SOURCE_DIR;
  const CliRun cell = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --robot " + root + "/urdf/industrial_arm.urdf" +
                               " --gripper " + root + "/config/gripper.yaml");
  ASSERT_EQ(cell.status, 0) << cell.err;
  EXPECT_NE(cell.out.find("<position name=\"joint_1\" joint=\"joint_1\""), std::string::npos);
  EXPECT_NE(cell.out.find("name=\"finger_c_joint_7\""), std::string::npos);
  const CliRun half = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --gripper " + root + "/config/gripper.yaml");
  EXPECT_EQ(half.status, 2);
  EXPECT_NE(half.err.find("--mjcf with --gripper needs --robot"), std::string::npos) << half.err;
  // The range rule of every interface. 5e5 Pa writes the springs at max_gauge_pa, with the
  // node's and finger_model's words (before: springs for 500 kPa without a word); -1 Pa, the straight finger's.
  const auto body = [](const std::string& mjcf) { return mjcf.substr(mjcf.find("-->")); };  // past the header comment
  const CliRun over = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --gauge-pa 5e5");
  const CliRun top = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --gauge-pa 294199.5");
  ASSERT_EQ(over.status, 0) << over.err;
  EXPECT_EQ(body(over.out), body(top.out));
  EXPECT_NE(over.err.find("warning: gauge pressure 500000 Pa is above max_gauge_pa 294199.5 Pa, the top of the "
                          "model's range: clamped to it"),
            std::string::npos)
      << over.err;
  const CliRun vacuum = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --gauge-pa -1");
  const CliRun rest = runShell(std::string(FINGER_URDF_EXE) + " --mjcf --gauge-pa 0");
  ASSERT_EQ(vacuum.status, 0) << vacuum.err;
  EXPECT_EQ(body(vacuum.out), body(rest.out));
  EXPECT_NE(vacuum.err.find("warning: gauge pressure -1 Pa is a vacuum"), std::string::npos) << vacuum.err;
  const CliRun beyond = runShell(std::string(FINGER_URDF_EXE) +
                                 " --mjcf --set wall_law=membrane --set shear_modulus_pa=2e4 --gauge-pa 20000");
  EXPECT_EQ(beyond.status, 2);
  EXPECT_NE(beyond.err.find("no free shape at 20000 Pa gauge"), std::string::npos) << beyond.err;
}

// The help says what an option takes, one value per occurrence (it showed "--gauge-pa TEXT ...",
// and a second value was refused); a second value after one occurrence is still refused, by name.
TEST(Cli, TheHelpShowsOneValuePerOccurrence) {
  const CliRun help = run("--help");
  ASSERT_EQ(help.status, 0) << help.err;
  EXPECT_NE(help.out.find("--gauge-pa PA "), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--supplied-volume-m3 M3 "), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("TEXT ..."), std::string::npos) << help.out;
  expectRefused("--gauge-pa 1000 2000", "2000");
  EXPECT_EQ(lines(run("--gauge-pa 1000 --gauge-pa 2000").out).size(), 3u);
}
