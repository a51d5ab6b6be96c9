#pragma once
// `deepgi report ...`: the speed-against-error report (docs/report.md).
namespace deepgi_app {
// argv[1] is "report". Returns the process exit status.
int run_report_command(int argc, char** argv);
}  // namespace deepgi_app
