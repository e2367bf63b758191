// The generated description (urdfdom, ROS-free): collision and inertial of every link, a wired tree, and the
// composition of a robot with a gripper file.
#include <gtest/gtest.h>

#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/yaml_parameters.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"

namespace pf = pneumatic_finger;

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kArm = std::string(PACKAGE_SOURCE_DIR) + "/urdf/industrial_arm.urdf";
const std::string kGripper = std::string(PACKAGE_SOURCE_DIR) + "/config/gripper.yaml";

std::string composeFrom(const std::string& gripper_yaml) {
  const std::string path = testing::TempDir() + "/gripper_test.yaml";
  std::ofstream(path) << gripper_yaml;
  return pf::composeRobotUrdfFiles(kArm, path);
}

std::string refusal(const std::string& gripper_yaml) {
  try {
    composeFrom(gripper_yaml);
  } catch (const pf::ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Description, EverySegmentHasCollisionAndTheInertialOfItsWalls) {
  const pf::FingerParameters p = pf::FingerParameters::defaults();
  const urdf::ModelInterface m = pf::fingerUrdfModel(p, pf::FingerUrdfOptions());
  const double rho = p.elastomer_density_kg_m3, height = p.chamber_height_m[0], width = p.chamber_width_m[0];
  for (int n = 0; n <= p.chamber_count; ++n) {
    const auto link = m.getLink(pf::segmentLinkName("finger_", n));
    ASSERT_TRUE(link && link->collision && link->visual && link->inertial) << n;
    // The collision shape is the visual one: the same box at the same place.
    const auto* box = dynamic_cast<const urdf::Box*>(link->collision->geometry.get());
    ASSERT_NE(box, nullptr);
    EXPECT_EQ(link->collision->geometry, link->visual->geometry);
    EXPECT_EQ(link->collision->origin.position.x, link->visual->origin.position.x);
    // Mass: the base segment is solid; a chamber segment is its block minus its chamber (the walls between).
    const double length = n == 0 ? p.base_segment_length_m : p.segment_length_m[0];
    const double solid_length = n == 0 ? length : length - p.chamber_thickness_m[0];
    EXPECT_DOUBLE_EQ(link->inertial->mass, rho * solid_length * height * width) << n;
    // Inertia about the centre: block minus cavity; for the cavity spanning height and width this is the two end
    // walls' own inertia plus their offset, which is what this independent form computes.
    const double m_wall = rho * (solid_length / 2) * height * width;
    const double offset = length / 2 - solid_length / 4;  // centre of each end wall from the block's centre
    const double iyy = n == 0 ? rho * length * height * width * (length * length + width * width) / 12
                              : 2 * (m_wall * ((solid_length / 2) * (solid_length / 2) + width * width) / 12 +
                                     m_wall * offset * offset);
    EXPECT_NEAR(link->inertial->iyy, iyy, 1e-20) << n;
    EXPECT_GT(link->inertial->ixx, 0);
    EXPECT_GT(link->inertial->izz, 0);
  }
  EXPECT_EQ(m.getLink(m.getRoot()->name)->inertial, nullptr) << "no inertial on the root (robot_state_publisher warns)";
}

// A drawn actuator's links are its body (docs/DRAWING.md): each block as tall as the body's top above the layer and
// as wide as drawn, its mass the block less the drawn cavity. The EPFL actuator: 2 + 7 mm pitch, 8 + 7 mm tall,
// 8 + 2 x 7 mm wide; a cavity 2 x 8 x 8 mm.
TEST(Description, ADrawnActuatorsLinksAreItsBody) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlText("wall_law: thick\ndrawing: {chamber_count: 7, cavity_height_m: 0.008, "
                                    "cavity_width_m: 0.008, cavity_length_m: 0.002, wall_thickness_m: 0.007}\n",
                                    "epfl", raw);
  const pf::FingerParameters p = pf::FingerParameters::fromRaw(raw);
  const urdf::ModelInterface m = pf::fingerUrdfModel(p, pf::FingerUrdfOptions());
  const auto link = m.getLink(pf::segmentLinkName("finger_", 3));
  ASSERT_TRUE(link && link->visual && link->inertial);
  const auto* box = dynamic_cast<const urdf::Box*>(link->visual->geometry.get());
  ASSERT_NE(box, nullptr);
  EXPECT_NEAR(box->dim.x, 0.009, 1e-17);
  EXPECT_NEAR(box->dim.y, 0.015, 1e-17);
  EXPECT_NEAR(box->dim.z, 0.022, 1e-17);
  EXPECT_NEAR(link->inertial->mass, 1070 * (0.009 * 0.015 * 0.022 - 0.002 * 0.008 * 0.008), 1e-15);
}

TEST(Description, TheModelIsAWiredTreeLikeAParsedOne) {
  const urdf::ModelInterface m = pf::fingerUrdfModel(pf::FingerParameters::defaults(), pf::FingerUrdfOptions());
  ASSERT_TRUE(m.getRoot());
  EXPECT_EQ(m.getRoot()->name, "tool0");
  // Walk from the tip to the root through parent pointers, and from the root down through children.
  int depth = 0;
  for (auto link = m.getLink("finger_tip"); link->getParent(); link = link->getParent()) {
    ASSERT_TRUE(link->parent_joint);
    EXPECT_EQ(link->parent_joint->child_link_name, link->name);
    ++depth;
  }
  EXPECT_EQ(depth, 9);  // tip, segment_7 .. segment_0
  EXPECT_EQ(m.getRoot()->child_links.size(), 1u);
  EXPECT_EQ(m.getRoot()->child_links[0]->name, "finger_segment_0");
}

TEST(Description, ComposingTheCellsGripperGivesOneTreeWithEveryFinger) {
  const std::string xml = pf::composeRobotUrdfFiles(kArm, kGripper);
  const urdf::ModelInterfaceSharedPtr m = urdf::parseURDF(xml);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->getRoot()->name, "world");
  for (const char* finger : {"finger_a_", "finger_b_", "finger_c_"}) {
    for (int n = 0; n <= 7; ++n) EXPECT_TRUE(m->getLink(pf::segmentLinkName(finger, n))) << finger << n;
    EXPECT_EQ(m->getLink(pf::segmentLinkName(finger, 0))->getParent()->name, "tool0");
  }
  EXPECT_TRUE(m->getLink("gripper_plate")) << "the robot's own links stay";
  // The robot's numbers are kept as written (urdfdom's exporter would round them to 6 digits).
  const urdf::ModelInterfaceSharedPtr arm = urdf::parseURDF(readFile(kArm));
  const auto& want = arm->getJoint("joint_6-tool0")->parent_to_joint_origin_transform.rotation;
  const auto& got = m->getJoint("joint_6-tool0")->parent_to_joint_origin_transform.rotation;
  EXPECT_EQ(got.x, want.x);
  EXPECT_EQ(got.y, want.y);
  EXPECT_EQ(got.z, want.z);
  EXPECT_EQ(got.w, want.w);
  // And each finger's mount is exactly the gripper file's pose.
  urdf::Rotation mount;
  mount.setFromRPY(-1.04719755, -1.57079633, 0.0);
  const auto& b = m->getJoint("finger_b_mount")->parent_to_joint_origin_transform;
  EXPECT_EQ(b.rotation.x, mount.x);
  EXPECT_EQ(b.rotation.w, mount.w);
  EXPECT_EQ(b.position.x, -0.03031089);
}

TEST(Description, CompositionRefusesWhatWouldBreakTheTreeNamingIt) {
  EXPECT_NE(refusal("fingers:\n  - {prefix: a_, parent: flange}\n").find("no link 'flange'"), std::string::npos);
  EXPECT_NE(refusal("fingers:\n  - {prefix: a_, parent: tool0}\n  - {prefix: a_, parent: tool0}\n")
                .find("prefix 'a_' is used twice"),
            std::string::npos);
  // No prefix: the finger's joint_1 is the arm's joint_1.
  EXPECT_NE(refusal("fingers:\n  - {prefix: '', parent: tool0}\n").find("joint 'joint_1' already exists"),
            std::string::npos);
  EXPECT_NE(refusal("fingers:\n  - {prefix: a_, parent: tool0, colour: red}\n").find("unknown key 'colour'"),
            std::string::npos);
  EXPECT_NE(refusal("fingers: []\n").find("needs 'fingers:'"), std::string::npos);
  EXPECT_NE(refusal("fingers:\n  - {prefix: a_, parent: tool0, xyz: [1, 2]}\n").find("'xyz' must be a list of 3"),
            std::string::npos);
  EXPECT_NE(refusal("fingers:\n  - {prefix: a_, parent: tool0, config: /nonexistent.yaml}\n").find("/nonexistent.yaml"),
            std::string::npos);
  EXPECT_THROW(pf::composeRobotUrdf("<robot name='x'><link name='a'/><bad", {}), pf::ParameterError);
}

// Under the membrane law the limit point comes before the range's top: the joints' upper limits are the angles just
// below it (the most the model holds), not the rest shape a pressure beyond it would leave.
TEST(Description, UnderTheMembraneLawTheUpperLimitsAreTheAnglesBelowTheLimitPoint) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml", raw);
  const pf::FingerParameters p = pf::FingerParameters::fromRaw(raw);
  const pf::FingerModel model(p);
  ASSERT_LT(model.limitGaugePa(), pf::FingerUrdfOptions().max_gauge_pa);
  std::vector<double> q(static_cast<std::size_t>(p.chamber_count));
  ASSERT_TRUE(model.jointAnglesAt(model.belowLimitGaugePa(), q.data()));
  const urdf::ModelInterface m = pf::fingerUrdfModel(p, pf::FingerUrdfOptions());
  for (int i = 1; i <= p.chamber_count; ++i) {
    const auto joint = m.joints_.at(pf::jointName(pf::FingerUrdfOptions().prefix, i));
    EXPECT_EQ(joint->limits->upper, q[static_cast<std::size_t>(i - 1)]) << i;
    EXPECT_GT(joint->limits->upper, 0.01) << i;
  }
}

// A Gent wall that snaps through: past its limit it bends on, on its far branch, up to the range's top, so the upper
// limits are the far branch's angles there (docs/MODEL.md, "The snap-through").
TEST(Description, WallsThatSnapThroughReachTheFarBranchsAnglesAtTheTopOfTheRange) {
  pf::RawParameterMap raw;
  pf::loadRawParametersFromYamlFile(std::string(PACKAGE_SOURCE_DIR) + "/config/marchese2015_ribbed.yaml", raw);
  raw["wall_locking_jm"] = {{50.0}, false};
  const pf::FingerParameters p = pf::FingerParameters::fromRaw(raw);
  const pf::FingerModel model(p);
  pf::FingerUrdfOptions options;
  options.max_gauge_pa = 2.0 * model.limitGaugePa();
  ASSERT_TRUE(std::isfinite(model.farTurningGaugePa()));
  pf::FingerWorkspace ws(model);
  model.startBranch(ws, true);
  const pf::FingerState& far = model.evaluate(options.max_gauge_pa, ws);
  ASSERT_EQ(far.status, pf::EvaluationStatus::kSnappedThrough);
  const urdf::ModelInterface m = pf::fingerUrdfModel(p, options);
  for (int i = 1; i <= p.chamber_count; ++i) {
    const auto joint = m.joints_.at(pf::jointName(options.prefix, i));
    EXPECT_EQ(joint->limits->upper, far.joint_angle_rad[i - 1]) << i;
    EXPECT_GT(joint->limits->upper, model.tipAngleBelowLimit() / p.chamber_count) << i;
  }
}
