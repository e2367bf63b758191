// The descriptions as simulators and planners read them, and the finger's MJCF (finger_urdf --mjcf) against the twin:
// MuJoCo's own springs settle the free finger to the twin's joint angles, and a plate at the tip feels the twin's
// blocked force (docs/MODEL.md, "Joint springs").
// The descriptions as simulators and planners read them: MuJoCo (Debian's libmujoco, a physics engine nobody here
// wrote) loads, compiles and steps the finger's URDF and the composed cell (arm + gripper) with no NaN and no warning;
// KDL (kdl_parser, what dynamic planners and the cell's own kinematics use) builds a tree with every moving joint.
#include <gtest/gtest.h>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <mujoco/mujoco.h>
#include <urdf_parser/urdf_parser.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "pneumatic_finger/cell/grasp_hold.hpp"
#include "pneumatic_finger/cell/side_grasp.hpp"
#include "pneumatic_finger/core/grasp_plan.hpp"
#include "pneumatic_finger/core/regulator.hpp"
#include "pneumatic_finger/core/smoothstep.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/sim/cell_physics.hpp"
#include "pneumatic_finger/sim/finger_mjcf.hpp"
#include "pneumatic_finger/sim/grasp_lift_trial.hpp"
#include "pneumatic_finger/sim/joint_springs.hpp"
#include "pneumatic_finger/sim/mjcf_text.hpp"
#include "pneumatic_finger/sim/pressure_driven_finger.hpp"

namespace pf = pneumatic_finger;

namespace {

const std::string kArm = std::string(PACKAGE_SOURCE_DIR) + "/urdf/industrial_arm.urdf";
const std::string kGripper = std::string(PACKAGE_SOURCE_DIR) + "/config/gripper.yaml";

std::string composedCell() { return pf::composeRobotUrdfFiles(kArm, kGripper); }
std::string fingerAlone() { return pf::fingerUrdf(pf::FingerParameters::defaults(), pf::FingerUrdfOptions()); }

// What MuJoCo says of one description: loaded and compiled (else its error), then two simulated seconds under gravity.
struct Simulated {
  std::string error;
  int bodies = 0, moving_joints = 0, warnings = 0;
  bool finite = true;
  double lightest_moving_body_kg = INFINITY;
};

Simulated simulate(const std::string& urdf_xml, const std::string& name) {
  Simulated out;
  const std::string path = testing::TempDir() + "/" + name + ".urdf";
  std::ofstream(path) << urdf_xml;
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  out.error = error;
  if (m == nullptr) return out;
  // Room for every contact of the cell's unactuated fall: a URDF gives MuJoCo no <size>, and its default list of 100
  // filled at 0.72 s as the arm folded onto the fingers (mjWARN_CONTACTFULL), by a trajectory that a change of 1e-12 in
  // a joint limit decides. The list's size is this harness's, not the description's.
  m->nconmax = 1000;
  mjData* d = mj_makeData(m);
  for (int i = 0; i < 2000 && out.finite; ++i) {
    mj_step(m, d);
    for (int k = 0; k < m->nq; ++k) out.finite = out.finite && std::isfinite(d->qpos[k]);
  }
  for (int w = 0; w < mjNWARNING; ++w) out.warnings += d->warning[w].number;
  out.bodies = m->nbody;
  out.moving_joints = m->njnt;
  for (int b = 1; b < m->nbody; ++b) out.lightest_moving_body_kg = std::min(out.lightest_moving_body_kg, m->body_mass[b]);
  mj_deleteData(d);
  mj_deleteModel(m);
  return out;
}

int movingJoints(const std::string& urdf_xml) {
  const auto model = urdf::parseURDF(urdf_xml);
  int n = 0;
  for (const auto& j : model->joints_) n += j.second->type != urdf::Joint::FIXED;
  return n;
}

}  // namespace

TEST(Simulator, MujocoLoadsCompilesAndStepsTheFingerAlone) {
  const std::string xml = fingerAlone();
  const Simulated s = simulate(xml, "finger");
  ASSERT_TRUE(s.error.empty()) << s.error;
  EXPECT_EQ(s.moving_joints, movingJoints(xml));
  EXPECT_TRUE(s.finite);
  EXPECT_EQ(s.warnings, 0);
  EXPECT_GT(s.lightest_moving_body_kg, 0.0);
}

TEST(Simulator, MujocoLoadsCompilesAndStepsTheComposedCell) {
  const std::string xml = composedCell();
  const Simulated s = simulate(xml, "cell");
  ASSERT_TRUE(s.error.empty()) << s.error;
  EXPECT_EQ(s.moving_joints, movingJoints(xml)) << "the arm's six joints and every finger's";
  EXPECT_EQ(s.moving_joints, 6 + 3 * 7);
  EXPECT_TRUE(s.finite);
  EXPECT_EQ(s.warnings, 0);
  EXPECT_GT(s.lightest_moving_body_kg, 0.0);
}

TEST(Simulator, KdlBuildsATreeWithEveryJoint) {
  for (const std::string& xml : {fingerAlone(), composedCell()}) {
    KDL::Tree tree;
    ASSERT_TRUE(kdl_parser::treeFromString(xml, tree));
    EXPECT_EQ(static_cast<int>(tree.getNrOfJoints()), movingJoints(xml));
    const auto model = urdf::parseURDF(xml);
    for (const auto& link : model->links_) {
      if (link.first != model->getRoot()->name) {
        EXPECT_NE(tree.getSegments().find(link.first), tree.getSegments().end()) << link.first;
      }
    }
  }
}

namespace {

// A loaded MJCF (from text, through a file as MuJoCo reads it), freed at the end of the scope.
struct Loaded {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::string error;
  Loaded(const std::string& xml, const std::string& name) {
    const std::string path = testing::TempDir() + "/" + name + ".xml";
    std::ofstream(path) << xml;
    char e[1000] = "";
    m = mj_loadXML(path.c_str(), nullptr, e, sizeof e);
    error = e;
    if (m) d = mj_makeData(m);
  }
  ~Loaded() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

pf::FingerParameters membraneParameters() {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText("wall_law: membrane\nshear_modulus_pa: 2e4\nwall_thickness_m: 0.002\n"
                                    "wall_locking_jm: 50\n", "test", raw);
  return pf::FingerParameters::fromRaw(raw);
}

// Steps @p seconds of simulated time without gravity; returns the largest |q_n - q_n0| over the finger's joints.
double settledError(Loaded& sim, const std::vector<pf::JointSpring>& springs, double seconds) {
  sim.m->opt.gravity[0] = sim.m->opt.gravity[1] = sim.m->opt.gravity[2] = 0.0;
  const int steps = static_cast<int>(seconds / sim.m->opt.timestep);
  for (int i = 0; i < steps; ++i) mj_step(sim.m, sim.d);
  double worst = 0.0;
  for (std::size_t j = 0; j < springs.size(); ++j) {
    const int id = mj_name2id(sim.m, mjOBJ_JOINT, pf::jointName("finger_", static_cast<int>(j) + 1).c_str());
    worst = std::max(worst, std::fabs(sim.d->qpos[sim.m->jnt_qposadr[id]] - springs[j].rest_angle_rad));
  }
  return worst;
}

}  // namespace

// The file carries the twin's springs, exactly (written round-trip), and MuJoCo reads them as its passive springs.
TEST(SimulatorSprings, TheMjcfCarriesTheTwinsSpringsIntoMujoco) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  pf::MjcfOptions o;
  o.gauge_pa = 98066.5;
  Loaded sim(pf::fingerMjcf(p, pf::FingerUrdfOptions(), o), "finger_mjcf");
  ASSERT_NE(sim.m, nullptr) << sim.error;
  ASSERT_EQ(sim.m->njnt, 7);
  std::string why;
  const std::vector<pf::JointSpring> springs = pf::jointSprings(pf::FingerModel(p), o.gauge_pa, why);
  for (int j = 0; j < 7; ++j) {
    const int id = mj_name2id(sim.m, mjOBJ_JOINT, pf::jointName("finger_", j + 1).c_str());
    ASSERT_GE(id, 0);
    EXPECT_EQ(sim.m->jnt_stiffness[id], springs[static_cast<std::size_t>(j)].stiffness_nm_per_rad) << j;
    EXPECT_EQ(sim.m->qpos_spring[sim.m->jnt_qposadr[id]], springs[static_cast<std::size_t>(j)].rest_angle_rad) << j;
    EXPECT_GT(sim.m->dof_damping[sim.m->jnt_dofadr[id]], 0.0) << j;
  }
  EXPECT_EQ(sim.m->opt.cone, mjCONE_ELLIPTIC);
  EXPECT_GE(mj_name2id(sim.m, mjOBJ_SITE, "finger_tip"), 0);
  // The springs' stiffness holds the twin's moment at the straight joint: k q0 = M.
  for (const pf::JointSpring& s : springs) {
    EXPECT_NEAR(s.stiffness_nm_per_rad * s.rest_angle_rad, s.pressure_moment_nm, 1e-15 * s.pressure_moment_nm);
  }
}

// Without gravity or an object, MuJoCo's finger settles to the twin's joint angles, across the range, both laws.
TEST(SimulatorSprings, TheFreeFingerSettlesToTheTwinsAnglesWithinAMilliradian) {
  const pf::FingerModel membrane(membraneParameters());
  const std::vector<std::pair<pf::FingerParameters, std::vector<double>>> cases = {
      {pf::FingerParameters::defaults(), {0.0, 49033.25, 98066.5, 196133.0, 294199.5}},
      {membraneParameters(), {0.3 * membrane.limitGaugePa(), 0.6 * membrane.limitGaugePa(), 0.9 * membrane.limitGaugePa()}}};
  for (const auto& [params, pressures] : cases) {
    const pf::FingerModel twin(params);
    for (double p : pressures) {
      SCOPED_TRACE(std::string(pf::wallLawName(params.wall_law)) + " at " + std::to_string(p) + " Pa");
      pf::MjcfOptions o;
      o.gauge_pa = p;
      Loaded sim(pf::fingerMjcf(params, pf::FingerUrdfOptions(), o), "settle");
      ASSERT_NE(sim.m, nullptr) << sim.error;
      std::string why;
      const std::vector<pf::JointSpring> springs = pf::jointSprings(twin, p, why);
      EXPECT_LT(settledError(sim, springs, 1.0), 1e-3);
    }
  }
}

// A plate at the tip, orthogonal to the bending plane, where the straight finger's tip is: MuJoCo's contact force is
// the twin's blocked tip force (docs/MODEL.md "Force"), within 2 %. The plate touches only a ball at the tip (contact
// bits), its contact is stiff (solref's direct stiffness, on a short step) so that the tip stays where it is, and the
// chain settles for three simulated seconds.
TEST(SimulatorSprings, APlateAtTheTipFeelsTheTwinsBlockedForce) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  const pf::FingerModel twin(p);
  for (double gauge : {98066.5, 196133.0}) {
    SCOPED_TRACE(gauge);
    pf::MjcfOptions o;
    o.gauge_pa = gauge;
    std::string xml = pf::fingerMjcf(p, pf::FingerUrdfOptions(), o);
    const double r = 1e-3, length = p.lengthM();
    const std::string ball = "<geom name=\"tip_ball\" type=\"sphere\" size=\"" + pf::formatShortest(r) +
                             "\" contype=\"2\" conaffinity=\"2\" condim=\"1\" mass=\"0\"/>\n";
    xml.insert(xml.find("<site name=\"finger_tip\""), ball);
    // Its lower face at y = r: it touches the ball of the straight finger's tip.
    const std::string plate = "<geom name=\"plate\" type=\"box\" size=\"0.02 0.005 0.01\" pos=\"" +
                              pf::formatShortest(length) + " " + pf::formatShortest(r + 0.005) +
                              " 0\" contype=\"2\" conaffinity=\"2\" condim=\"1\" solref=\"-1e9 -1e5\"/>\n";
    xml.insert(xml.find("  </worldbody>"), "    " + plate);
    Loaded sim(xml, "plate");
    ASSERT_NE(sim.m, nullptr) << sim.error;
    sim.m->opt.timestep = 1e-5;
    sim.m->opt.gravity[1] = sim.m->opt.gravity[2] = sim.m->opt.gravity[0] = 0.0;
    for (int i = 0; i < 300000; ++i) mj_step(sim.m, sim.d);
    double normal_n = 0.0;
    for (int c = 0; c < sim.d->ncon; ++c) {
      mjtNum f[6];
      mj_contactForce(sim.m, sim.d, c, f);
      normal_n += f[0];
    }
    const double want = twin.blockedTipForceN(gauge);
    ASSERT_GT(want, 0.0);
    EXPECT_NEAR(normal_n, want, 0.02 * want);
  }
}

// The pressure-driven finger: MuJoCo steps while the regulator's fill raises the pressure, and the springs follow the
// twin at every step; held at the end, the finger settles to the twin's angles at the final pressure. The damping
// keeps the file's ratio: rewritten at a pressure, it is what a file written at that pressure has.
TEST(SimulatorSprings, AFillDrivesTheFingerThroughTheTwinsShapes) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  const pf::FingerModel twin(p);
  Loaded sim(pf::fingerMjcf(p, pf::FingerUrdfOptions(), pf::MjcfOptions()), "fill");
  ASSERT_NE(sim.m, nullptr) << sim.error;
  pf::PressureDrivenFinger finger(twin, sim.m, "finger_");
  sim.m->opt.gravity[0] = sim.m->opt.gravity[1] = sim.m->opt.gravity[2] = 0.0;
  const double top = 98066.5, fill_s = 0.5, dt = sim.m->opt.timestep;
  std::string why;
  for (int i = 0; i * dt < fill_s + 1.0; ++i) {
    ASSERT_TRUE(finger.applyPressure(std::min(top, top * i * dt / fill_s), why)) << why;
    mj_step(sim.m, sim.d);
  }
  const std::vector<pf::JointSpring> springs = pf::jointSprings(twin, top, why);
  for (std::size_t j = 0; j < springs.size(); ++j) {
    const int id = finger.jointIds()[j];
    EXPECT_NEAR(sim.d->qpos[sim.m->jnt_qposadr[id]], springs[j].rest_angle_rad, 1e-3) << j;
    EXPECT_EQ(sim.m->jnt_stiffness[id], springs[j].stiffness_nm_per_rad) << j;
  }
  pf::MjcfOptions at_top;
  at_top.gauge_pa = top;
  Loaded written(pf::fingerMjcf(p, pf::FingerUrdfOptions(), at_top), "fill_top");
  for (int id : finger.jointIds()) {
    const double want = written.m->dof_damping[written.m->jnt_dofadr[id]];
    EXPECT_NEAR(sim.m->dof_damping[sim.m->jnt_dofadr[id]], want, 1e-12 * want) << id;
  }
  // Beyond what the twin holds the springs stay as they were, and the call says why.
  const pf::FingerModel membrane(membraneParameters());
  Loaded balloon(pf::fingerMjcf(membraneParameters(), pf::FingerUrdfOptions(), pf::MjcfOptions()), "balloon");
  pf::PressureDrivenFinger ballooning(membrane, balloon.m, "finger_");
  ASSERT_TRUE(ballooning.applyPressure(0.5 * membrane.limitGaugePa(), why));
  EXPECT_FALSE(ballooning.applyPressure(std::numeric_limits<double>::quiet_NaN(), why));
  EXPECT_NE(why.find("no free shape"), std::string::npos) << why;
  EXPECT_EQ(ballooning.gaugePa(), 0.5 * membrane.limitGaugePa());
  EXPECT_THROW(pf::PressureDrivenFinger(twin, sim.m, "other_"), pf::ParameterError);
}

// The composed cell as MJCF (finger_urdf --robot --gripper --mjcf): every finger's springs, a position actuator on
// every arm joint. Under gravity the arm holds its pose (its rated torque at 10 mrad of error), and without it every
// finger settles to the twin; nothing collides, nothing warns.
TEST(SimulatorSprings, TheComposedCellHoldsItsArmAndItsFingersTakeTheTwinsShape) {
  pf::MjcfOptions o;
  o.gauge_pa = 98066.5;
  Loaded sim(pf::composedMjcf(kArm, kGripper, o), "cell_mjcf");
  ASSERT_NE(sim.m, nullptr) << sim.error;
  EXPECT_EQ(sim.m->nu, 6) << "one position actuator per arm joint";
  EXPECT_EQ(sim.m->njnt, 6 + 3 * 7);
  for (int i = 0; i < 5000; ++i) mj_step(sim.m, sim.d);  // 0.5 s under gravity, the targets at 0
  for (int j = 1; j <= 6; ++j) {
    const int id = mj_name2id(sim.m, mjOBJ_JOINT, ("joint_" + std::to_string(j)).c_str());
    ASSERT_GE(id, 0);
    EXPECT_LT(std::fabs(sim.d->qpos[sim.m->jnt_qposadr[id]]), 1e-2) << "joint_" << j;
  }
  int warnings = 0;
  for (int w = 0; w < mjNWARNING; ++w) warnings += sim.d->warning[w].number;
  EXPECT_EQ(warnings, 0);
  EXPECT_EQ(sim.d->ncon, 0) << "the fingers' and the arm's own links do not collide";
  // Each arm joint is damped critically for what it moves at the zero pose: MuJoCo's own mass matrix there.
  mjData* zero = mj_makeData(sim.m);
  mj_forward(sim.m, zero);
  for (int a = 0; a < sim.m->nu; ++a) {
    const int dof = sim.m->jnt_dofadr[sim.m->actuator_trnid[2 * a]];
    const double kp = sim.m->actuator_gainprm[a * mjNGAIN], m_jj = zero->qM[sim.m->dof_Madr[dof]];
    EXPECT_NEAR(sim.m->dof_damping[dof], 2.0 * std::sqrt(kp * m_jj), 1e-9 * sim.m->dof_damping[dof]) << a;
  }
  mj_deleteData(zero);
  sim.m->opt.gravity[0] = sim.m->opt.gravity[1] = sim.m->opt.gravity[2] = 0.0;
  for (int i = 0; i < 10000; ++i) mj_step(sim.m, sim.d);
  const pf::FingerModel twin(pf::loadGripperFile(kGripper).front().parameters);
  std::vector<double> q(7);
  ASSERT_TRUE(twin.jointAnglesAt(o.gauge_pa, q.data()));
  for (const char* prefix : {"finger_a_", "finger_b_", "finger_c_"}) {
    for (int j = 1; j <= 7; ++j) {
      const int id = mj_name2id(sim.m, mjOBJ_JOINT, pf::jointName(prefix, j).c_str());
      ASSERT_GE(id, 0);
      EXPECT_NEAR(sim.d->qpos[sim.m->jnt_qposadr[id]], q[static_cast<std::size_t>(j - 1)], 1e-3) << prefix << j;
    }
  }
}

namespace {

// The cell's gripper closed on the cell's part (config/cell.yaml: r = 16 mm, h = 35 mm) where the cell holds it, at
// the gripper action's grasp pressure: the last finger's touch plus the squeeze margin.
struct CellGrasp {
  std::vector<pf::GripperFinger> fingers = pf::loadGripperFile(kGripper);
  pf::GraspScene scene;
  double gauge_pa = 0.0;
  pf::SideGraspForces twin;
  CellGrasp() {
    scene.object_centre_depth_m = pf::sideGraspDepth(fingers, scene.object_radius_m, scene.object_height_m).centre_depth_m;
    const pf::SideGraspForces touch =
        pf::sideGraspForces(fingers, scene.object_radius_m, scene.object_height_m, scene.object_centre_depth_m, 0.0);
    gauge_pa = *std::max_element(touch.touch_gauge_pa.begin(), touch.touch_gauge_pa.end()) + pf::kDefaultSqueezeMarginPa;
    twin = pf::sideGraspForces(fingers, scene.object_radius_m, scene.object_height_m, scene.object_centre_depth_m,
                               gauge_pa);
  }
};

// No gravity: the grasp closes and settles, and nothing lifts.
pf::GraspTrialOutcome closeWithoutGravity(pf::GraspLiftTrial& trial, double gauge_pa) {
  pf::GraspTrialSettings s;
  s.hang_s = s.after_s = 0.0;
  return trial.run(gauge_pa, pf::LiftMotion{0.0, 1.0}, s);  // no lift: no step with gravity
}

}  // namespace

// Closed on the part, every finger joint's spring in MuJoCo presses with the force model's moment of a joint held at
// the angle MuJoCo gives it (FingerModel::heldJointMomentsNm, its walls' plane where the free walls stand at that
// angle). On a copy of the settled grasp, the springs are written for its state and MuJoCo's passive force, less the
// joint's damping, is read back against the twin's moment at MuJoCo's own angles.
TEST(SimulatorGrasp, EveryHeldJointPressesWithTheTwinsMomentAtItsAngle) {
  CellGrasp g;
  pf::GraspLiftTrial trial(g.fingers, g.scene, pf::MjcfOptions());
  ASSERT_TRUE(closeWithoutGravity(trial, g.gauge_pa).problem.empty());
  mjModel* m = mj_copyModel(nullptr, &trial.model());
  mjData* d = mj_copyData(nullptr, m, &trial.data());
  const pf::FingerModel twin(g.fingers.front().parameters);
  std::vector<double> q0(7), since(7), moment(7);
  ASSERT_TRUE(twin.jointAnglesAt(g.gauge_pa, q0.data()));
  int held = 0;
  for (const pf::GripperFinger& f : g.fingers) {
    pf::PressureDrivenFinger driven(twin, m, f.mount.prefix);
    std::string why;
    ASSERT_TRUE(driven.applyPressureWithHeldMoments(g.gauge_pa, *d, why)) << why;
    mj_forward(m, d);
    for (std::size_t j = 0; j < 7; ++j) {
      const int id = driven.jointIds()[j];
      const double q = d->qpos[m->jnt_qposadr[id]];
      ASSERT_LT(q, q0[j]) << "the part holds every joint short of its free angle";
      ASSERT_TRUE(twin.gaugeForHalfAngle(q / twin.jointComplianceWeight(static_cast<int>(j)), since[j]));
    }
    twin.heldJointMomentsNm(g.gauge_pa, since.data(), moment.data());
    for (std::size_t j = 0; j < 7; ++j) {
      const int dof = m->jnt_dofadr[driven.jointIds()[j]];
      const double spring = d->qfrc_passive[dof] + m->dof_damping[dof] * d->qvel[dof];
      ASSERT_GT(moment[j], 0.0);
      EXPECT_NEAR(spring, moment[j], 1e-12 * moment[j]) << f.mount.prefix << j + 1;
      ++held;
    }
  }
  EXPECT_EQ(held, 21);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// Closed on the part, MuJoCo's normal force of each finger against contactNormalForcesN's, with the file's settings
// (a 1 ms step, the fingers' armature): within 10 %, and below it. The engine lets each joint settle under the
// contact, and its soft contact lets the part in a little, both of which give back some of the twin's moment
// (docs/SIMULATION.md, "Where and why the two differ"). The linear springs (applyPressure), which carry the straight
// joint's moment, press with a third of it: the held moments are what make the grasp.
TEST(SimulatorGrasp, ClosedOnTheCellsPartEachFingerPressesWithinTenPercentOfTheTwinsForce) {
  CellGrasp g;
  pf::GraspLiftTrial trial(g.fingers, g.scene, pf::MjcfOptions());
  const pf::GraspTrialOutcome closed = closeWithoutGravity(trial, g.gauge_pa);
  ASSERT_TRUE(closed.problem.empty()) << closed.problem;
  ASSERT_EQ(closed.finger_normal_force_n.size(), 3u);
  for (std::size_t f = 0; f < 3; ++f) {
    ASSERT_GT(g.twin.normal_force_n[f], 0.0);
    EXPECT_NEAR(closed.finger_normal_force_n[f], g.twin.normal_force_n[f], 0.1 * g.twin.normal_force_n[f]) << f;
    EXPECT_LT(closed.finger_normal_force_n[f], g.twin.normal_force_n[f]) << "the engine's chain gives way";
  }
  pf::GraspTrialSettings linear;
  linear.hang_s = linear.after_s = 0.0;
  linear.held_moments = false;
  const pf::GraspTrialOutcome straight = trial.run(g.gauge_pa, pf::LiftMotion{0.0, 1.0}, linear);
  for (std::size_t f = 0; f < 3; ++f) EXPECT_LT(straight.finger_normal_force_n[f], 0.5 * g.twin.normal_force_n[f]) << f;
}

// The cell's lift at its default 12 s cycle (tool0 rises 0.108 m in 1.2 s: a peak of 0.45 m/s^2): physics carries
// the cell's 10 g part and a 200 g part slips out, and the cell's rule with the lift's inertia says the same.
TEST(SimulatorGrasp, TheCellsTenGramPartIsCarriedAndATwoHundredGramPartSlips) {
  CellGrasp g;
  const pf::LiftMotion lift{0.1076, pf::smoothstepPeakAcceleration(0.1076, 1.2)};
  const double friction = 1.0, margin = 1.5;
  const double weakest = *std::min_element(g.twin.normal_force_n.begin(), g.twin.normal_force_n.end());
  for (double mass : {0.01, 0.2}) {
    SCOPED_TRACE(mass);
    g.scene.object_mass_kg = mass;
    pf::GraspLiftTrial trial(g.fingers, g.scene, pf::MjcfOptions());
    const pf::GraspTrialOutcome out = trial.run(g.gauge_pa, lift, pf::GraspTrialSettings());
    EXPECT_TRUE(out.problem.empty()) << out.problem;
    const bool rule = pf::judgeHold(3, weakest, mass, friction, margin, lift.peak_acceleration_mps2).holds;
    EXPECT_EQ(out.carried, mass < 0.1);
    EXPECT_EQ(rule, out.carried);
    if (out.carried) {
      EXPECT_LT(out.slip_m, 0.005);
    } else {
      EXPECT_GT(out.slip_m, lift.height_m) << "it fell out, not crept";
    }
  }
}

// The whole cell in MuJoCo (CellPhysics): the arm at the pick pose, the part on its table where the gripper holds
// it. The fingers fill at the regulator's rate to the grasp pressure, then the arm's position actuators follow the
// schedule's lift from the pick pose to the pose above it (the 12 s cycle's 1.2 s), and hold for 1 s. Physics carries
// the 10 g part up with tool0 (within 5 mm of its rise) and leaves a 200 g part on the table.
TEST(SimulatorCell, TheArmLiftsTheTenGramPartOffItsTableAndLeavesTwoHundredGrams) {
  CellGrasp g;
  const YAML::Node cell = YAML::LoadFile(std::string(PACKAGE_SOURCE_DIR) + "/config/cell.yaml");
  const auto names = cell["arm_joint_names"].as<std::vector<std::string>>();
  const auto pick = cell["pick"].as<std::vector<double>>(), above = cell["above_pick"].as<std::vector<double>>();
  const pf::FingerModel twin(g.fingers.front().parameters);
  const double rate = pf::gripperFillRatePaPerS(pf::kCellRegulatorFlowM3PerS, twin.parameters(), 3);
  for (const auto& [mass, carried] : {std::tuple{0.01, true}, std::tuple{0.2, false}}) {
    SCOPED_TRACE(std::to_string(mass) + " kg");
    g.scene.object_mass_kg = mass;
    pf::CellPhysics physics(pf::readRobotUrdfFile(kArm), g.fingers, names, pick, g.scene, pf::MjcfOptions());
    const double grasp_pa = g.gauge_pa, lift_s = 1.2;
    const double dt = physics.model().opt.timestep;
    double gauge = 0.0, part_z0 = 0.0, tool_z0 = 0.0;
    std::string why;
    std::vector<double> target(names.size());
    for (double t = 0.0; t < 1.5 + lift_s + 1.0; t += dt) {
      const double u = std::clamp((t - 1.5) / lift_s, 0.0, 1.0);
      for (std::size_t j = 0; j < target.size(); ++j) target[j] = pick[j] + pf::smoothstep(u) * (above[j] - pick[j]);
      physics.setArmTargets(target);
      gauge = pf::regulatorStep(gauge, grasp_pa, rate, dt);
      ASSERT_TRUE(physics.step(gauge, why)) << why;
      if (t < 1.5) part_z0 = physics.partPose().translation().z(), tool_z0 = physics.toolPose().translation().z();
    }
    const double rise = physics.toolPose().translation().z() - tool_z0;
    const double part_rise = physics.partPose().translation().z() - part_z0;
    EXPECT_NEAR(rise, 0.1076, 2e-3) << "the arm follows the schedule's lift";
    if (carried) {
      EXPECT_NEAR(part_rise, rise, 0.005);
    } else {
      EXPECT_LT(std::fabs(part_rise), 0.005) << "it is back on the table";
    }
    EXPECT_EQ(physics.warnings(), 0);
  }
}
