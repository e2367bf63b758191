// The cell's regulator (PressureRegulator) as a nodelet: the cell's own plugin library, so that the ROS layer below
// it (src/ros) knows nothing of the cell.
#include <pluginlib/class_list_macros.hpp>

#include "pneumatic_finger/cell/pressure_regulator.hpp"
#include "pneumatic_finger/ros/node_nodelet.hpp"

namespace pneumatic_finger {

constexpr char kPressureRegulatorName[] = "pressure_regulator";
using PressureRegulatorNodelet = NodeNodelet<PressureRegulator, kPressureRegulatorName>;

}  // namespace pneumatic_finger

PLUGINLIB_EXPORT_CLASS(pneumatic_finger::PressureRegulatorNodelet, nodelet::Nodelet)
