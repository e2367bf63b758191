// The finger's node as a nodelet (FingerNode), so that a gripper runs in one nodelet manager with the cell's regulator
// (src/cell/cell_nodelets.cpp), the regulator's pressure reaching every finger without serialization.
#include <pluginlib/class_list_macros.hpp>

#include "pneumatic_finger/ros/finger_node.hpp"
#include "pneumatic_finger/ros/node_nodelet.hpp"

namespace pneumatic_finger {

constexpr char kFingerNodeName[] = "finger_node";
using FingerNodelet = NodeNodelet<FingerNode, kFingerNodeName>;

}  // namespace pneumatic_finger

PLUGINLIB_EXPORT_CLASS(pneumatic_finger::FingerNodelet, nodelet::Nodelet)
