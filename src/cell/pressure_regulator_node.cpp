// pressure_regulator: the cell's simulated regulator (PressureRegulator) as a node. The same class runs as the
// nodelet pneumatic_finger/PressureRegulatorNodelet (src/cell/cell_nodelets.cpp).
#include "pneumatic_finger/cell/pressure_regulator.hpp"
#include "pneumatic_finger/ros/node_main.hpp"

int main(int argc, char** argv) {
  using pneumatic_finger::PressureRegulator;
  return pneumatic_finger::runNode<PressureRegulator>(argc, argv, "pressure_regulator", PressureRegulator::parameterSpecs());
}
