// MJCF text straight into MuJoCo, through its virtual file system: no file on disk. ROS-free; needs libmujoco-dev.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

namespace pneumatic_finger {

/// A compiled model and its data, freed together.
struct MujocoDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MujocoModelPtr = std::unique_ptr<mjModel, MujocoDeleter>;
using MujocoDataPtr = std::unique_ptr<mjData, MujocoDeleter>;

/// Compiles @p mjcf_xml (finger_urdf --mjcf's, graspSceneMjcf's). @throws ParameterError with MuJoCo's message
MujocoModelPtr loadMjcfText(const std::string& mjcf_xml);

}  // namespace pneumatic_finger
