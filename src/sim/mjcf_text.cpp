// MJCF text into MuJoCo (mjcf_text.hpp).
#include "pneumatic_finger/sim/mjcf_text.hpp"

#include <cstring>
#include <memory>
#include <string>

#include "pneumatic_finger/core/parameters.hpp"

namespace pneumatic_finger {

MujocoModelPtr loadMjcfText(const std::string& mjcf_xml) {
  // mjVFS holds its table of names inline (about 2 MB): on the heap, not the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(mjcf_xml.size())) != 0) {
    throw ParameterError("MuJoCo's virtual file system refused the model text");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], mjcf_xml.data(), mjcf_xml.size());
  char error[1000] = "";
  MujocoModelPtr model(mj_loadXML(name, vfs.get(), error, sizeof error));
  mj_deleteVFS(vfs.get());
  if (!model) throw ParameterError(std::string("MuJoCo does not load the model: ") + error);
  return model;
}

}  // namespace pneumatic_finger
