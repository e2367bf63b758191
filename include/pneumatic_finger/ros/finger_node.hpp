// The ROS wrapper: regulator pressure in; joint states, tf, the finger's state, diagnostics and a URDF out.
// All modelling is the core's (FingerModel, fingerUrdf); this class only reads parameters and moves messages.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pneumatic_finger/FingerModelState.h"
#include "pneumatic_finger/FingerNodeConfig.h"
#include "pneumatic_finger/GraspObject.h"
#include "pneumatic_finger/PressureForContactForce.h"
#include "pneumatic_finger/PressureForTipAngle.h"
#include "pneumatic_finger/core/contact.hpp"
#include "pneumatic_finger/core/finger_model.hpp"
#include "pneumatic_finger/core/grasp_object.hpp"
#include "pneumatic_finger/core/object_section.hpp"
#include "pneumatic_finger/core/pressure_input.hpp"
#include "pneumatic_finger/core/tip_uncertainty.hpp"
#include "pneumatic_finger/description/finger_urdf.hpp"
#include "pneumatic_finger/ros/node_parameters.hpp"

namespace pneumatic_finger {

class FingerNode {
 public:
  /// Publishes the URDF and the static frames and starts listening. @throws ParameterError on a bad parameter.
  FingerNode(ros::NodeHandle& nh, ros::NodeHandle& private_nh);

 private:
  void onPressure(const sensor_msgs::FluidPressure::ConstPtr& msg);
  /// Subscribes the input that drives the finger: ~volume_topic when set, else the pressure topic.
  void subscribeInput(ros::NodeHandle& nh);
  /// Volume as the input (~volume_topic): the same rules, the model driven by the supplied volume (finger_volume.cpp).
  void onVolume(const std_msgs::Float64::ConstPtr& msg);
  /// The finger driven to @p volume_m3: free (evaluateVolume), or closing on the grasp object within reach.
  void followVolume(double volume_m3, const ros::Time& now);
  void followVolumeInContact(double volume_m3, const ros::Time& now);
  /// The last pressure or volume again (the object moved, or another came).
  void republish();
  bool onInverse(PressureForTipAngle::Request& req, PressureForTipAngle::Response& res);  // finger_services.cpp
  bool onContactForce(PressureForContactForce::Request& req, PressureForContactForce::Response& res);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  void diagnoseCalibration(diagnostic_updater::DiagnosticStatusWrapper& status);
  void onReconfigure(FingerNodeConfig& config, uint32_t level);
  /// The live values as the node has them (chamber 1's for per-chamber keys).
  FingerNodeConfig currentConfig() const;
  /// Builds the model and publishes the URDF from settings_ (at start-up, and when the actuator is reconfigured).
  void buildModel(ros::NodeHandle& nh);
  /// Start-up: the fixed frames (with publish_tf), the messages sized once, the tip's error-bar marker.
  void publishStaticFrames();
  void sizeMessages();
  void setUpTipMarker(ros::NodeHandle& nh);
  /// Publishes the finger at a pressure the input rules accepted: the free model, then the contact rule when an
  /// object is within reach. False (nothing published) when a solver found no finite answer.
  bool publishAt(double gauge_pa, const ros::Time& stamp, bool clamped);
  /// Logs and counts a jump between the walls' branches (the snap-through) after an evaluation at @p gauge_pa.
  void noteBranch(double gauge_pa);
  /// @p supplied_volume_m3: the volume input's (NaN: the free chambers' at the state's pressure).
  void publish(const FingerState& state, const ContactState* contact, const ros::Time& stamp, bool clamped,
               double supplied_volume_m3 = NAN);
  /// publish()'s parts: the joints and their frames (returns the joints' sum), the backbone and the tip, the object.
  double writeJoints(const FingerState& state, const ContactState* contact, const double* q_rad,
                     const ros::Time& stamp);
  void writeShape(const FingerState& state, const Eigen::Ref<const Eigen::Matrix2Xd>& backbone, double tip_angle_rad,
                  const ros::Time& stamp);
  void writeObject(const ContactState* contact);

  // The grasp object (docs/GRASP.md).
  void onGraspObject(const GraspObject::ConstPtr& msg);
  /// Validates a new object and starts following it; false (the reason in object_refused_) for a bad one.
  bool acceptObject(const GraspObject::ConstPtr& msg);
  /// The object's frame in the finger's frame (tf and the finger's own mount); false with the reason when tf has none.
  bool objectPose(Eigen::Isometry3d& finger_from_frame, std::string& why) const;
  /// Looks the object up in the finger's frame and hands it to the tracker. Returns whether anything changed.
  bool updateObject();
  void onObjectTimer(const ros::TimerEvent&);

  NodeSettings settings_;
  std::unique_ptr<const FingerModel> model_;  // shared, const: the inverse service may run beside a pressure
  std::unique_ptr<FingerWorkspace> workspace_;  // what the pressure callback's evaluations write
  ros::Subscriber pressure_sub_, volume_sub_;
  ros::Publisher joint_states_pub_, finger_state_pub_;
  // The tip's error bar (the parameter file's tip_uncertainty) as a translucent sphere at the tip, republished only
  // when its size changes by more than 1 % or it becomes (or stops being) an extrapolation.
  ros::Publisher tip_marker_pub_;
  ros::Publisher force_marker_pub_;  // contact_force_markers: an arrow per contact, scaled in newtons
  bool arrows_shown_ = false;
  visualization_msgs::Marker tip_marker_;  // the sphere, built once; a change sets its size and colour
  TipUncertainty tip_uncertainty_;
  double marker_bar_m_ = -1.0;
  bool marker_extrapolated_ = false;
  /// The held joints' moments and the contact forces into finger_state and joint_states.effort (only in contact).
  void writeForces(double gauge_pa, const ContactState* contact);
  void publishTipMarker(const TipUncertainty::At& bar);
  ros::ServiceServer inverse_srv_, force_srv_;
  // Made only with publish_tf: without it the node does not even advertise /tf and /tf_static.
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_tf_;
  diagnostic_updater::Updater diagnostics_;
  ros::WallTimer diagnostics_timer_;

  // Preallocated outgoing messages: the per-message cycle fills them in place.
  sensor_msgs::JointState joint_states_;
  FingerModelState finger_state_;
  std::vector<geometry_msgs::TransformStamped> transforms_;

  // The input rules (stamps, time jumps, clamping, throttling, staleness) and their counters: ROS-free, in the core.
  PressureInputPolicy input_;

  // dynamic_reconfigure: the calibrated parameters and the input rates, validated like rosparams, applied live.
  std::unique_ptr<dynamic_reconfigure::Server<FingerNodeConfig>> reconfigure_;
  bool reconfigure_synced_ = false;
  ros::NodeHandle nh_;
  std::string log_name_;  // the private namespace, the first word of every log line

  // The grasp object. Nothing here works without one: the tf listener is made for the first object in another
  // frame, the timer runs only while there is an object, and an object out of reach costs no contact solve.
  ros::Subscriber object_sub_;
  ros::Timer object_timer_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  GraspObject::ConstPtr object_;                  ///< null: no object
  SolidObject object_in_frame_;                   ///< the object in its message's frame
  std::string object_refused_;                    ///< why the last object was refused, empty when it was not
  std::unique_ptr<GraspObjectTracker> grasp_;     ///< section, touch events, status: the core's, made with the model
  ros::WallTime object_since_;                    ///< when the object arrived
  bool object_located_once_ = false;              ///< its pose was known once since
  /// A transform missing this long after the object arrived is a problem (WARN); before, the frames are coming.
  static constexpr double kTransformGraceS = 3.0;
  // The last accepted pressure: an object that moves re-publishes the finger at it.
  bool have_pressure_ = false, last_clamped_ = false;
  bool on_far_branch_ = false;              // the walls' branch after the last evaluation (the snap-through)
  long snaps_through_ = 0, snaps_back_ = 0;  // jumps between the branches, for diagnostics
  double last_gauge_pa_ = 0.0;
  std::string announced_object_;  // the grasp object (id and frame) last logged: each change is logged once
  double max_volume_m3_ = 0.0;   // the volume that makes max_gauge_pa: above it a volume is clamped (pressure_range.hpp)
  double last_volume_m3_ = 0.0;  // the last accepted supplied volume (~volume_topic), re-followed when the object moves
};

}  // namespace pneumatic_finger
