#pragma once
#include <stdexcept>

namespace deepgi {

// Something the user gave us is wrong (scene file, argument, output path).
// Front ends report it as one line and exit with status 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The GL context or a shader could not be created; not the user's fault.
struct GraphicsError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// No display to open a window on: a front end can point to its headless path.
struct NoDisplayError : GraphicsError {
    using GraphicsError::GraphicsError;
};

}  // namespace deepgi
