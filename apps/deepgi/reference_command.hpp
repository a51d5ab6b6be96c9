#pragma once
// `deepgi reference ...`: the ray-traced ground truth for deep SAO.
namespace deepgi_app {
// argv[1] is "reference". Returns the process exit status.
int run_reference_command(int argc, char** argv);
}  // namespace deepgi_app
