// The descriptions as simulators and planners read them: MuJoCo (Debian's libmujoco, a physics engine nobody here
// wrote) loads, compiles and steps the finger's URDF and the composed cell (arm + gripper) with no NaN and no warning;
// KDL (kdl_parser, what dynamic planners and the cell's own kinematics use) builds a tree with every moving joint.
#include <gtest/gtest.h>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <mujoco/mujoco.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <fstream>
#include <string>

#include "pneumatic_finger/description/finger_urdf.hpp"

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
