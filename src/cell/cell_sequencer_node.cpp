// cell_sequencer: drives the pick-and-place cell. It moves the arm through approach -> grasp (inflate) -> lift ->
// move -> place (deflate) -> return, commands the regulator, and shows the object, carried while held.
#include <Eigen/Geometry>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <std_msgs/String.h>
#include <std_msgs/UInt32.h>
#include <urdf_parser/urdf_parser.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <vector>

namespace {

using Joints = std::vector<double>;

// Forward kinematics of the serial chain root -> tip of a urdfdom model, for the given joint values by name.
Eigen::Isometry3d chainPose(const urdf::ModelInterface& model, const std::string& tip,
                            const std::vector<std::string>& names, const Joints& q) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (auto link = model.getLink(tip); link && link->parent_joint; link = model.getLink(link->parent_joint->parent_link_name)) {
    const auto& j = *link->parent_joint;
    const auto& o = j.parent_to_joint_origin_transform;
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translate(Eigen::Vector3d(o.position.x, o.position.y, o.position.z));
    t.rotate(Eigen::Quaterniond(o.rotation.w, o.rotation.x, o.rotation.y, o.rotation.z));
    if (j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS) {
      for (std::size_t i = 0; i < names.size(); ++i) {
        if (names[i] == j.name) t.rotate(Eigen::AngleAxisd(q[i], Eigen::Vector3d(j.axis.x, j.axis.y, j.axis.z)));
      }
    }
    pose = t * pose;
  }
  return pose;
}

Joints readJoints(ros::NodeHandle& pnh, const std::string& key, std::size_t n) {
  Joints v;
  if (!pnh.getParam(key, v) || v.size() != n) {
    throw std::runtime_error("parameter '" + key + "' must be a list of " + std::to_string(n) + " joint values (rad)");
  }
  return v;
}

struct Phase {
  const char* name;
  double fraction;      // of the cycle time
  const Joints* from;   // arm motion (same pointer: hold)
  const Joints* to;
  double setpoint_pa;   // regulator setpoint during the phase
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "cell_sequencer");
  ros::NodeHandle nh, pnh("~");
  std::vector<std::string> names;
  Joints home, above_pick, pick, above_place, place;
  double cycle_time = 12.0, grasp_pa = 147099.75, offset = 0.075, radius = 0.016, height = 0.035, rate_hz = 50.0;
  int loop_count = 0;
  urdf::ModelInterfaceSharedPtr arm;
  try {
    if (!pnh.getParam("arm_joint_names", names) || names.empty()) {
      throw std::runtime_error("parameter 'arm_joint_names' is missing");
    }
    home = readJoints(pnh, "home", names.size());
    above_pick = readJoints(pnh, "above_pick", names.size());
    pick = readJoints(pnh, "pick", names.size());
    above_place = readJoints(pnh, "above_place", names.size());
    place = readJoints(pnh, "place", names.size());
    pnh.param("cycle_time_s", cycle_time, cycle_time);
    pnh.param("loop_count", loop_count, loop_count);
    pnh.param("grasp_gauge_pa", grasp_pa, grasp_pa);
    pnh.param("object_offset_m", offset, offset);
    pnh.param("object_radius_m", radius, radius);
    pnh.param("object_height_m", height, height);
    pnh.param("publish_rate_hz", rate_hz, rate_hz);
    if (!(cycle_time >= 2.0 && cycle_time <= 600)) throw std::runtime_error("parameter 'cycle_time_s' must be in [2, 600]");
    if (loop_count < 0) throw std::runtime_error("parameter 'loop_count' must be >= 0 (0: forever)");
    if (!(grasp_pa > 0 && grasp_pa <= 1e6)) throw std::runtime_error("parameter 'grasp_gauge_pa' must be in (0, 1e6]");
    std::string xml;
    if (!nh.getParam("robot_description", xml)) throw std::runtime_error("no arm URDF in 'robot_description'");
    arm = urdf::parseURDF(xml);
    if (!arm || !arm->getLink("tool0")) throw std::runtime_error("'robot_description' has no link 'tool0'");
  } catch (const std::exception& e) {
    ROS_FATAL("cell_sequencer: %s", e.what());
    return 2;
  }
  // The object stands where the gripper will hold it at the pick pose, and is left where the place pose puts it.
  const Eigen::Isometry3d held = Eigen::Isometry3d(Eigen::Translation3d(0, 0, offset));
  const Eigen::Isometry3d at_pick = chainPose(*arm, "tool0", names, pick) * held;
  const Eigen::Isometry3d at_place = chainPose(*arm, "tool0", names, place) * held;

  // Fractions of the cycle: the grasp and release phases last 1.8 s of a 12 s cycle, long enough for the
  // regulator's fill (about 1 s to 1.5 kg/cm^2) to finish before the arm moves.
  const std::vector<Phase> phases = {
      {"approach", 0.14, &home, &above_pick, 0.0},        {"descend to pick", 0.10, &above_pick, &pick, 0.0},
      {"grasp (inflate)", 0.15, &pick, &pick, grasp_pa},  {"lift", 0.10, &pick, &above_pick, grasp_pa},
      {"move", 0.14, &above_pick, &above_place, grasp_pa}, {"descend to place", 0.10, &above_place, &place, grasp_pa},
      {"place (deflate)", 0.15, &place, &place, 0.0},     {"return", 0.12, &place, &home, 0.0},
  };

  ros::Publisher joints_pub = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
  ros::Publisher setpoint_pub = nh.advertise<std_msgs::Float64>("gripper/setpoint", 10);
  ros::Publisher marker_pub = nh.advertise<visualization_msgs::MarkerArray>("cell/markers", 1, true);
  ros::Publisher phase_pub = nh.advertise<std_msgs::String>("cell/phase", 10, true);
  ros::Publisher cycles_pub = nh.advertise<std_msgs::UInt32>("cell/cycles", 10, true);

  visualization_msgs::Marker object;
  object.ns = "object";
  object.type = visualization_msgs::Marker::CYLINDER;
  object.scale.x = object.scale.y = 2 * radius;
  object.scale.z = height;
  object.color.r = 0.2f, object.color.g = 0.5f, object.color.b = 0.95f, object.color.a = 1.0f;
  visualization_msgs::Marker table = object;
  table.ns = "tables";
  table.type = visualization_msgs::Marker::CUBE;
  table.scale.x = table.scale.y = 0.12;
  table.scale.z = 0.01;
  table.color.r = table.color.g = table.color.b = 0.55f;
  auto setPose = [](visualization_msgs::Marker& m, const Eigen::Isometry3d& p) {
    m.pose.position.x = p.translation().x();
    m.pose.position.y = p.translation().y();
    m.pose.position.z = p.translation().z();
    const Eigen::Quaterniond q(p.rotation());
    m.pose.orientation.x = q.x(), m.pose.orientation.y = q.y(), m.pose.orientation.z = q.z(), m.pose.orientation.w = q.w();
  };

  sensor_msgs::JointState js;
  js.name = names;
  js.position.resize(names.size());
  std_msgs::Float64 setpoint;
  std_msgs::UInt32 cycles;
  ros::Rate rate(rate_hz);
  const ros::Time start = ros::Time::now();
  std::size_t last_phase = phases.size();
  long last_cycle = 0;
  int tick = 0;
  ROS_INFO("cell_sequencer: %.1f s cycles, %s; object at (%.3f, %.3f, %.3f) m", cycle_time,
           loop_count ? (std::to_string(loop_count) + " loops").c_str() : "looping", at_pick.translation().x(),
           at_pick.translation().y(), at_pick.translation().z());
  while (ros::ok()) {
    const double t = (ros::Time::now() - start).toSec();
    const long cycle = static_cast<long>(t / cycle_time);
    if (cycle != last_cycle) {
      cycles.data = static_cast<unsigned>(cycle);
      cycles_pub.publish(cycles);
      ROS_INFO("cell_sequencer: cycle %ld complete", cycle);
      last_cycle = cycle;
      if (loop_count > 0 && cycle >= loop_count) {
        ROS_INFO("cell_sequencer: %d cycles done", loop_count);
        break;
      }
    }
    double s = std::fmod(t, cycle_time) / cycle_time;
    std::size_t k = 0;
    while (k + 1 < phases.size() && s >= phases[k].fraction) s -= phases[k++].fraction;
    const Phase& ph = phases[k];
    const double u = std::min(1.0, s / ph.fraction);
    const double smooth = u * u * (3 - 2 * u);  // zero velocity at both ends of every motion
    for (std::size_t i = 0; i < names.size(); ++i) {
      js.position[i] = (*ph.from)[i] + smooth * ((*ph.to)[i] - (*ph.from)[i]);
    }
    js.header.stamp = ros::Time::now();
    joints_pub.publish(js);
    setpoint.data = ph.setpoint_pa;
    setpoint_pub.publish(setpoint);
    if (k != last_phase) {
      std_msgs::String msg;
      msg.data = ph.name;
      phase_pub.publish(msg);
      ROS_INFO("cell_sequencer: cycle %ld: %s (gripper setpoint %.0f Pa gauge)", cycle + 1, ph.name, ph.setpoint_pa);
      last_phase = k;
    }
    if (tick++ % 5 == 0) {
      // Held from the end of the grasp until the release starts; otherwise on its table.
      const bool holding = (k == 2 && u >= 1.0) || (k >= 3 && k <= 5);
      visualization_msgs::MarkerArray markers;
      object.header.stamp = js.header.stamp;
      if (holding) {
        object.header.frame_id = "tool0";
        setPose(object, held);
      } else {
        object.header.frame_id = "world";
        setPose(object, k >= 6 ? at_place : at_pick);
      }
      markers.markers.push_back(object);
      table.header = object.header;
      table.header.frame_id = "world";
      for (int i = 0; i < 2; ++i) {
        table.id = i;
        Eigen::Isometry3d top = i == 0 ? at_pick : at_place;
        top.translate(Eigen::Vector3d(0, 0, height / 2 + 0.005));  // tool z points down: +z is below the object
        table.pose.position.x = top.translation().x();
        table.pose.position.y = top.translation().y();
        table.pose.position.z = top.translation().z();
        table.pose.orientation = geometry_msgs::Quaternion();
        table.pose.orientation.w = 1.0;
        markers.markers.push_back(table);
      }
      marker_pub.publish(markers);
    }
    rate.sleep();
  }
  return 0;
}
