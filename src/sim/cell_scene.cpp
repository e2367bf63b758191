// The cell in MuJoCo (cell_scene.hpp): the composed arm compiled once to find tool0 at the pick pose, then written
// again with the table and the part there.
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

}  // namespace

std::string cellSceneMjcf(const std::string& arm_urdf_xml, const std::vector<GripperFinger>& fingers,
                          const std::vector<std::string>& arm_joint_names, const std::vector<double>& pick_joints_rad,
                          const GraspScene& scene, const MjcfOptions& mjcf) {
  graspSceneMjcf(fingers, scene, mjcf);  // refuses a part or a finger the scene cannot hold
  if (arm_joint_names.size() != pick_joints_rad.size()) {
    throw ParameterError("the pick pose has " + std::to_string(pick_joints_rad.size()) + " joints, the arm's names " +
                         std::to_string(arm_joint_names.size()));
  }
  const MujocoModelPtr arm = loadMjcfText(composedMjcf(arm_urdf_xml, fingers, mjcf, ""));
  const MujocoDataPtr d(mj_makeData(arm.get()));
  for (std::size_t j = 0; j < arm_joint_names.size(); ++j) {
    const int id = mj_name2id(arm.get(), mjOBJ_JOINT, arm_joint_names[j].c_str());
    if (id < 0) throw ParameterError("the arm has no joint '" + arm_joint_names[j] + "'");
    d->qpos[arm->jnt_qposadr[id]] = pick_joints_rad[j];
  }
  mj_kinematics(arm.get(), d.get());
  const int tool = mj_name2id(arm.get(), mjOBJ_BODY, kSceneToolName);
  if (tool < 0) throw ParameterError(std::string("the arm has no body '") + kSceneToolName + "'");
  const double* p = d->xpos + 3 * tool;
  const double* r = d->xmat + 9 * tool;  // row-major: tool z is the third column
  const double depth = scene.object_centre_depth_m, half = 0.5 * scene.object_height_m;
  const double c[3] = {p[0] + depth * r[2], p[1] + depth * r[5], p[2] + depth * r[8]};
  const double* q = d->xquat + 4 * tool;
  // The table: 12 cm square, 1 cm thick, its top at the part's base (the lower end of its axis).
  const double base_z = c[2] - half * std::fabs(r[8]);
  const std::string table = "    <geom name=\"pick_table\" type=\"box\" size=\"0.06 0.06 0.005\" pos=\"" +
                            triple(c[0], c[1], base_z - 0.005) + "\" rgba=\"0.55 0.55 0.55 1\"/>\n";
  const std::string part = partBodyMjcf(scene, triple(c[0], c[1], c[2]),
                                        formatShortest(q[0]) + " " + triple(q[1], q[2], q[3]));
  return composedMjcf(arm_urdf_xml, fingers, mjcf, table + part);
}

}  // namespace pneumatic_finger
