// The registry of live temporaries that a SIGINT or SIGTERM removes before
// the program dies of it (temporaries.cpp). Internal to fileio.
#pragma once

#include <string>

namespace spiral::fileio {

// Registers a temporary file or directory for removal on a signal and
// installs the handlers where the program has none of its own. Returns the
// slot index, or -1 when all are taken (the temporary then only lacks signal
// cleanup; its owner's destructor still removes it).
int register_temporary(const std::string& path, bool directory);

// Forgets the slot (a no-op for -1): the temporary was renamed or removed.
void unregister_temporary(int slot);

}  // namespace spiral::fileio
