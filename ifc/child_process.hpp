#pragma once

#include <string>

#include "ifc/ifc_import.hpp"

namespace isg::ifc {

// IFC++ is not robust against malformed models (ci/fuzz found null dereferences in its geometry
// code, and leaks): the model is read, its elements fitted and the plan's JSON made in a child
// process, and the result handed back through a pipe, so that whatever IFC++ does to a bad file,
// isg reports the file and exits 1 with nothing written. A signal that stops the child (Ctrl-C)
// is ImportInterrupted; a crash is common::InputError naming `file`.
ImportResult importInChildProcess(const std::string& file, std::string text,
                                  const ImportOptions& options);

}  // namespace isg::ifc
