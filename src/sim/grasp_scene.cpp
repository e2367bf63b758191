// The grasp-and-lift scene as MJCF (grasp_scene.hpp): a lift rig as a robot description, the fingers composed onto
// it as onto the cell's arm, and the object added to the world body.
#include "pneumatic_finger/sim/grasp_scene.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace pneumatic_finger {

namespace {

std::string num(double v) { return formatShortest(v); }

void requirePositive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ParameterError(std::string("the grasp scene's ") + what + " must be a finite number > 0, got " +
                         formatMessage(value));
  }
}

// The rig: world -> lift (a slide along z, the carriage at its origin) -> tool0, turned half a turn about x so that
// tool z points down. The carriage's 1 kg and the slide's limits only make a valid description: the trial moves the
// carriage on a prescribed path (grasp_lift_trial.hpp).
std::string liftRigUrdf(double carriage_height_m) {
  return "<robot name=\"lift_rig\">\n"
         "  <link name=\"world\"/>\n"
         "  <link name=\"carriage\"><inertial><mass value=\"1\"/>"
         "<inertia ixx=\"1e-3\" iyy=\"1e-3\" izz=\"1e-3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
         "  <link name=\"" + std::string(kSceneToolName) + "\"/>\n"
         "  <joint name=\"" + std::string(kLiftJointName) + "\" type=\"prismatic\"><parent link=\"world\"/>"
         "<child link=\"carriage\"/><origin xyz=\"0 0 " + num(carriage_height_m) + "\"/><axis xyz=\"0 0 1\"/>"
         "<limit lower=\"-1\" upper=\"1\" effort=\"1000\" velocity=\"10\"/></joint>\n"
         "  <joint name=\"flange\" type=\"fixed\"><parent link=\"carriage\"/><child link=\"" +
         std::string(kSceneToolName) + "\"/><origin rpy=\"3.141592653589793 0 0\"/></joint>\n"
         "</robot>\n";
}

}  // namespace

std::string partBodyMjcf(const GraspScene& scene, const std::string& pos, const std::string& quat) {
  return "    <!-- The part, free: carried, slipped or dropped by physics. Its contacts are stiff (a 2 ms time constant "
         "against MuJoCo's 20 ms), so that the fingers press on it without sinking in. -->\n"
         "    <body name=\"" + std::string(kSceneObjectName) + "\" pos=\"" + pos + "\" quat=\"" + quat + "\">\n"
         "      <freejoint name=\"" + std::string(kSceneObjectName) + "\"/>\n"
         "      <geom name=\"" + std::string(kSceneObjectName) + "\" type=\"cylinder\" size=\"" +
         num(scene.object_radius_m) + " " + num(0.5 * scene.object_height_m) + "\" mass=\"" +
         num(scene.object_mass_kg) + "\" solref=\"0.002 1\" rgba=\"0.9 0.5 0.1 1\"/>\n"
         "    </body>\n";
}

std::string graspSceneMjcf(const std::vector<GripperFinger>& fingers, const GraspScene& scene, const MjcfOptions& mjcf) {
  requirePositive(scene.object_radius_m, "object radius (m)");
  requirePositive(scene.object_height_m, "object height (m)");
  requirePositive(scene.object_mass_kg, "object mass (kg)");
  if (!std::isfinite(scene.object_centre_depth_m)) {
    throw ParameterError("the grasp scene's object centre depth (m) must be finite, got " +
                         formatMessage(scene.object_centre_depth_m));
  }
  for (const GripperFinger& f : fingers) {
    if (f.mount.parent_frame != kSceneToolName) {
      throw ParameterError("finger '" + f.mount.prefix + "' is mounted on '" + f.mount.parent_frame +
                           "': the grasp scene carries fingers on '" + kSceneToolName + "'");
    }
  }
  // The object's centre lies depth below tool0, and the carriage puts tool0 at the height that sets the object's
  // base at z = 0.
  const double carriage_height_m = 0.5 * scene.object_height_m + scene.object_centre_depth_m;
  const std::string object = partBodyMjcf(scene, "0 0 " + num(0.5 * scene.object_height_m), "1 0 0 0");
  return composedMjcf(liftRigUrdf(carriage_height_m), fingers, mjcf, object);
}

}  // namespace pneumatic_finger
