// The cell in MuJoCo (cell_scene.hpp): the composed arm compiled once to find tool0 at the pick pose, then written
// again with the tables and the part there.
#include "pneumatic_finger/sim/cell_scene.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "pneumatic_finger/sim/mjcf_text.hpp"

namespace pneumatic_finger {

namespace {

std::string triple(double x, double y, double z) {
  return formatShortest(x) + " " + formatShortest(y) + " " + formatShortest(z);
}

// Where the gripper holds the part with the arm at @p joints_rad: the part's centre and tool0's orientation (w x y
// z), by MuJoCo's kinematics of the composed arm.
void heldPart(mjModel* arm, mjData* d, const std::vector<std::string>& names, const std::vector<double>& joints_rad,
              double depth_m, double centre[3], double quat[4]) {
  if (names.size() != joints_rad.size()) {
    throw ParameterError("a pose has " + std::to_string(joints_rad.size()) + " joints, the arm's names " +
                         std::to_string(names.size()));
  }
  for (std::size_t j = 0; j < names.size(); ++j) {
    const int id = mj_name2id(arm, mjOBJ_JOINT, names[j].c_str());
    if (id < 0) throw ParameterError("the arm has no joint '" + names[j] + "'");
    d->qpos[arm->jnt_qposadr[id]] = joints_rad[j];
  }
  mj_kinematics(arm, d);
  const int tool = mj_name2id(arm, mjOBJ_BODY, kSceneToolName);
  if (tool < 0) throw ParameterError(std::string("the arm has no body '") + kSceneToolName + "'");
  const double* p = d->xpos + 3 * tool;
  const double* r = d->xmat + 9 * tool;  // row-major: tool z is the third column
  for (int k = 0; k < 3; ++k) centre[k] = p[k] + depth_m * r[3 * k + 2];
  for (int k = 0; k < 4; ++k) quat[k] = d->xquat[4 * tool + k];
}

// A table, 12 cm square and 1 cm thick, whose top meets the base of a part standing at @p centre (the lower end of
// its axis, tool z, whose vertical share is @p axis_z).
std::string table(const char* name, const double centre[3], double half_height_m, double axis_z) {
  const double base_z = centre[2] - half_height_m * std::fabs(axis_z);
  return "    <geom name=\"" + std::string(name) + "\" type=\"box\" size=\"0.06 0.06 0.005\" pos=\"" +
         triple(centre[0], centre[1], base_z - 0.005) + "\" rgba=\"0.55 0.55 0.55 1\"/>\n";
}

}  // namespace

std::string cellSceneMjcf(const std::string& arm_urdf_xml, const std::vector<GripperFinger>& fingers,
                          const std::vector<std::string>& arm_joint_names, const std::vector<double>& pick_joints_rad,
                          const GraspScene& scene, const MjcfOptions& mjcf,
                          const std::vector<double>& place_joints_rad) {
  graspSceneMjcf(fingers, scene, mjcf);  // refuses a part or a finger the scene cannot hold
  const MujocoModelPtr arm = loadMjcfText(composedMjcf(arm_urdf_xml, fingers, mjcf, ""));
  const MujocoDataPtr d(mj_makeData(arm.get()));
  const double half = 0.5 * scene.object_height_m;
  double c[3], q[4];
  std::string world;
  if (!place_joints_rad.empty()) {
    heldPart(arm.get(), d.get(), arm_joint_names, place_joints_rad, scene.object_centre_depth_m, c, q);
    world += table("place_table", c, half, d->xmat[9 * mj_name2id(arm.get(), mjOBJ_BODY, kSceneToolName) + 8]);
  }
  heldPart(arm.get(), d.get(), arm_joint_names, pick_joints_rad, scene.object_centre_depth_m, c, q);
  world += table("pick_table", c, half, d->xmat[9 * mj_name2id(arm.get(), mjOBJ_BODY, kSceneToolName) + 8]);
  world += partBodyMjcf(scene, triple(c[0], c[1], c[2]), formatShortest(q[0]) + " " + triple(q[1], q[2], q[3]));
  return composedMjcf(arm_urdf_xml, fingers, mjcf, world);
}

}  // namespace pneumatic_finger
